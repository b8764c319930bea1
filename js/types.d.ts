// The interfaces of subsurf's JS API. wasm-bindgen appends this file to the subsurf.d.ts it
// generates (src/wasm/mod.rs includes it as a typescript_custom_section), after the declarations of
// the exported functions and classes, which refer to these names.
/**
 * Names accepted by `SubdivideOptions.scheme`. 'loop', 'sqrt3' and 'midpoint' take triangles
 * only; the others take any polygons. `schemeNames()` lists them at run time.
 */
export type SchemeName =
  'catmull-clark' | 'loop' | 'doo-sabin' | 'quad-triangle' | 'sqrt3' | 'bilinear' | 'midpoint';

/** Names accepted by `SubdivideOptions.boundary`; `boundaryRules()` lists them at run time. */
export type BoundaryRule = 'edge-and-corner' | 'edge-only' | 'fixed' | 'average' | 'none';

/**
 * Names accepted by `SubdivideOptions.fvarLinear`, from smoothest to most linear (OpenSubdiv's
 * `FVarLinearInterpolation`); `fvarLinearModes()` lists them at run time.
 */
export type FVarLinearMode =
  'none' | 'corners-only' | 'corners-plus1' | 'corners-plus2' | 'boundaries' | 'all';

/** A polygon mesh as flat typed arrays. The arrays are only read, never modified. */
export interface SubdivideMesh {
  /** x, y, z of each vertex. */
  positions: Float32Array;
  /** The vertex indices of every face, face after face, counter-clockwise seen from outside. */
  indices: Uint32Array;
  /** How many indices each face uses. Omitted: every face is a triangle. */
  faceSizes?: Uint32Array;
  /** Ignored, so that a `SubdivideResult` can be subdivided again. */
  triangles?: Uint32Array;
  /**
   * Ignored, so that a `readObj` result can be passed as it is. Tags take effect only as
   * options: `subdivide(mesh, { ...mesh.tags, levels: 2 })`.
   */
  tags?: ObjTags;
  /** Ignored, so that a `toDrawable` result can be passed as it is (to `vertexNormals`, ...). */
  origins?: Uint32Array;
  /**
   * Data besides positions, by name (colours, skin weights, morph targets, UVs): each channel is
   * refined with the same weights as the positions (face-varying ones by OpenSubdiv's
   * face-varying rules, see `fvarLinear`) and comes back in the result's `attributes` under the
   * same name.
   */
  attributes?: Record<string, AttributeChannel>;
}

/**
 * One channel of `itemSize` floats (1 to 16) per value. Without `indices` it is vertex-varying:
 * one value per vertex, in vertex order. With `indices` it is face-varying (UVs split at seams):
 * `indices[k]` is the value of face corner k, parallel to the mesh's `indices`, so a vertex may
 * have a different value in each of its faces.
 */
export interface AttributeChannel {
  array: Float32Array;
  itemSize: number;
  indices?: Uint32Array;
}

/** How to subdivide. Every field is optional. */
export interface SubdivideOptions {
  /** One scheme for every level, or one per level. Default 'catmull-clark'. */
  scheme?: SchemeName | SchemeName[];
  /** Number of levels, a whole number from 0 to 32. Default 1, or the length of a `scheme` array. */
  levels?: number;
  /** What happens at boundary edges and vertices. Default 'edge-and-corner'. */
  boundary?: BoundaryRule;
  /** Refuse, before any work, when the result would have more faces than this. Default 16777216. */
  maxFaces?: number;
  /** Refuse, before any work, when the result's arrays would take more bytes. Default 1073741824 (1 GiB). */
  maxBytes?: number;
  /** Sharp edges (Catmull-Clark and Loop): vertex pairs, and one sharpness per pair or one for all (10 = infinitely sharp). */
  creases?: { edges: Uint32Array; sharpness: Float32Array };
  /** Sharp vertices: vertex indices, and one sharpness per vertex or one for all. */
  corners?: { vertices: Uint32Array; sharpness: Float32Array };
  /** Faces left out of the result (they still shape their neighbours). */
  holes?: Uint32Array;
  /** How semi-sharp creases decay from level to level. Default 'uniform'. */
  creaseMethod?: 'uniform' | 'chaikin';
  /** Catmull-Clark: OpenSubdiv's smooth-triangle rule. Default false. */
  smoothTriangles?: boolean;
  /**
   * Where face-varying channels (UVs) are interpolated linearly instead of smoothly: 'none'
   * (smooth everywhere), 'corners-only', 'corners-plus1', 'corners-plus2', 'boundaries' (along
   * boundaries and seams) or 'all' (everywhere, as bilinear). Default 'corners-plus1'.
   */
  fvarLinear?: FVarLinearMode;
  /**
   * Move the last level's points and every attribute (face-varying ones too) to the limit
   * surface, as OpenSubdiv's `Limit` and `LimitFaceVarying` do. For a last level of
   * 'catmull-clark', 'loop' and 'quad-triangle' (whose points where quads meet triangles stay);
   * 'bilinear' and 'midpoint' points are on their limit already and stay; 'doo-sabin' and
   * 'sqrt3' throw. Default false.
   */
  limit?: boolean;
  /**
   * Add `normals` to the result: one unit normal per vertex, outward as the faces are wound.
   * After 'catmull-clark', 'loop' and 'quad-triangle', the limit
   * surface's normal (the cross product of its two tangents; a crease or corner gets one
   * side's); after the other schemes, the normalised sum of the faces' area vectors around the
   * vertex. Without `limit`, the points stay where the level put them. Default false.
   */
  normals?: boolean;
  /**
   * Called after each level (the last one included) with where the call is. Whatever it throws
   * stops the call and is thrown by `subdivide`. Used by `subdivide` and `BaseMesh.subdivide`;
   * `subsurf/worker` passes it on from its worker. Ignored by `predictCounts` and `evaluator`.
   */
  onProgress?: (progress: SubdivideProgress) => void;
}

/** What `SubdivideOptions.onProgress` is told after each level. */
export interface SubdivideProgress {
  /** Levels done, 1 to `levels`. */
  level: number;
  /** Levels of the call. */
  levels: number;
  /** Faces of the mesh this level made (holes are left out only after the last level). */
  faces: number;
  /** Vertices of the mesh this level made. */
  vertices: number;
}

/** A polygon mesh with every field present, as `shape` returns it. */
export interface PolygonMesh {
  positions: Float32Array;
  indices: Uint32Array;
  faceSizes: Uint32Array;
}

/**
 * The OpenSubdiv `t` tags of an OBJ file under the names and in the shapes `SubdivideOptions`
 * takes, so that `subdivide(mesh, { ...mesh.tags, levels: 2 })` honours them (spread them last to
 * let the file override your options). Indices are 0-based, into the mesh's vertices and faces.
 */
export interface ObjTags {
  /** `t crease` lines: vertex pairs, one sharpness per pair, in file order; empty arrays without any. */
  creases: { edges: Uint32Array; sharpness: Float32Array };
  /** `t corner` lines: vertices, one sharpness per vertex, in file order; empty arrays without any. */
  corners: { vertices: Uint32Array; sharpness: Float32Array };
  /** `t hole` lines: faces, in file order; empty without any. */
  holes: Uint32Array;
  /** `t interpolateboundary` 0, 1 or 2. Absent when the file has no such tag. */
  boundary?: 'none' | 'edge-and-corner' | 'edge-only';
  /** `t creasemethod chaikin`. Absent when the file asks for the default, 'uniform' ('normal'), or has no such tag. */
  creaseMethod?: 'chaikin';
  /** `t smoothtriangles smooth`. Absent when the file asks for the default (false) or has no such tag. */
  smoothTriangles?: true;
}

/** What `readObj` returns: the polygons of an OBJ file, its tags and its texture coordinates. */
export interface ObjMesh extends PolygonMesh {
  tags: ObjTags;
  /**
   * The file's `vt` lines (u, v; a third component is dropped) and its corners' `vt` indices, as
   * the face-varying channel `uv`; absent when the faces give no `vt` indices.
   */
  attributes?: { uv: AttributeChannel };
}

/**
 * The refined mesh: arrays owned by the caller, fresh or (when passed back as `into`) written
 * over by a later call, the attribute channels' arrays included.
 */
export interface SubdivideResult extends PolygonMesh {
  /** A triangle list of the same faces (fans), ready for `gl.drawElements(gl.TRIANGLES, ...)`. */
  triangles: Uint32Array;
  /**
   * The refined channels of `mesh.attributes`, by name; present when the mesh had some. A
   * face-varying channel's `indices` are parallel to this result's `indices`; `toDrawable`
   * turns the result into one index buffer for WebGL.
   */
  attributes?: Record<string, AttributeChannel>;
  /** Unit vertex normals (x, y, z per vertex) when `normals: true` was asked for. */
  normals?: Float32Array;
}

/**
 * An evaluator's stencil table (`Evaluator.stencils()`, or one of `Evaluator.levelStencils()`,
 * whose control vertices are the previous table's outputs), OpenSubdiv's `Far::StencilTable`
 * layout: output vertex i is the sum over k from `offsets[i]` to `offsets[i + 1]` of
 * `weights[k]` times control vertex `indices[k]`.
 */
export interface StencilArrays {
  /** One more than there are output vertices; `offsets[0]` is 0. */
  offsets: Uint32Array;
  /** The control vertex of each entry: a row names each of its control vertices once, in no set order (as OpenSubdiv's tables). */
  indices: Uint32Array;
  weights: Float32Array;
  /** With normals: the two limit tangents' weights on the same entries; the normal is their cross product, normalised. */
  tangentWeights?: [Float32Array, Float32Array];
  /** The number of control vertices the table reads (the base mesh's, or the previous level table's outputs). */
  numControlVertices: number;
}

/** One frame of `Evaluator.evaluate`: pass it back as `into` to reuse its arrays. */
export interface EvaluatedFrame {
  /** x, y, z per output vertex. */
  positions: Float32Array;
  /** Unit normals, x, y, z per output vertex, when the evaluator was built with `normals: true`. */
  normals?: Float32Array;
}
