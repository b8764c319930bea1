// The types of the triangle-soup functions (weldTriangles, triangleFaces, sideNormals), appended
// to subsurf.d.ts as js/types.d.ts is. subsurf/three's subdivideGeometry is built on them;
// weldTriangles is useful on its own, the other two are low-level.

/** What `weldTriangles(positions, index, weld)` returns. */
export interface WeldedTriangles {
  /** Per input vertex, its welded vertex (numbered by first use in `index`), or -1 if no triangle uses it. */
  weldOf: Int32Array;
  /** x, y, z per welded vertex: its first copy's position (never averaged). */
  positions: Float32Array;
  /** The input triangles (index offset / 3) kept, ascending: those whose corners weld to three different vertices. */
  kept: Uint32Array;
  /** Three welded vertices per kept triangle. */
  corners: Uint32Array;
}

/** The first argument of `triangleFaces`: welded triangles. */
export interface TriangleFacesInput {
  /** x, y, z per welded vertex (`WeldedTriangles.positions`). */
  positions: Float32Array;
  /** Three welded vertices per triangle (`WeldedTriangles.corners`). */
  corners: Uint32Array;
  /** The input vertex of each corner, parallel to `corners` (for `splitNormals` and `cornerClasses`). */
  inputCorners: Uint32Array;
}

/** Options of `triangleFaces`; by default it lists the triangles as they are. */
export interface TriangleFacesOptions {
  /** Edges whose triangles' normals differ by more than this angle (radians, 0 to Math.PI) become sharp. */
  creaseAngle?: number;
  /** x, y, z per input vertex: edges where the input's copies carry normals more than about 1° apart, at both ends, become sharp. */
  splitNormals?: Float32Array;
  /** Creases of the caller's, as welded vertex pairs: no quad joins across them; sharpness 10 or more splits `sides`. */
  creases?: { edges: Uint32Array; sharpness: Float32Array };
  /** Join pairs of triangles into quads (Blender's "Tris to Quads"); angles in radians, default 40° each. */
  quads?: boolean | { faceAngle?: number; shapeAngle?: number };
  /** A group per triangle: quads never join two groups. */
  groups?: Uint32Array;
  /** A class per input vertex: quads join two triangles only where their corners at each end of the shared edge are of one class. */
  cornerClasses?: Uint32Array;
  /** Triangles that are holes: they join nothing, and `holes` of the result lists their faces. */
  holes?: Uint32Array;
  /** Return `sides`, the smoothing fan of each face corner, when some edge is infinitely sharp. */
  sides?: boolean;
}

/** What `triangleFaces` returns: the faces to subdivide. */
export interface TriangleFaces {
  /** 3 or 4 per face. */
  faceSizes: Uint32Array;
  /** The welded vertex of each face corner. */
  indices: Uint32Array;
  /** The input vertex of each face corner. */
  inputIndices: Uint32Array;
  /** Per face, its (first) triangle. */
  firstTriangles: Uint32Array;
  /** The edges found sharp (creaseAngle, splitNormals), as welded vertex pairs: infinitely sharp creases. */
  creases: Uint32Array;
  /** The faces made of hole triangles. */
  holes: Uint32Array;
  /** With `sides`, when some edge is infinitely sharp: per face corner, its smoothing fan. */
  sides?: Uint32Array;
}
