// The types of the demo's helpers (shape, shapeNames, predictCounts, vertexNormals, edgeList,
// toDrawable), appended to subsurf.d.ts as js/types.d.ts is.
/** Predicted sizes after 0, 1, ..., `levels` levels: entry `l` is the size after `l` levels. */
export interface PredictedCounts {
  vertices: Float64Array;
  /** The number `maxFaces` is compared with; exact except for 'doo-sabin' and 'quad-triangle' (upper bounds). */
  faces: Float64Array;
}

/** A built-in mesh (`shape(name)`) with its UV layout as a face-varying channel. */
export interface ShapeMesh extends PolygonMesh {
  attributes: { uv: AttributeChannel };
}

/**
 * What `toDrawable` returns: a mesh whose every channel has one value per vertex, so that one
 * index buffer (`triangles`) draws it; vertices are split where a face-varying channel has a
 * seam.
 */
export interface DrawableMesh extends PolygonMesh {
  /** The fan triangulation of the faces, for `gl.drawElements(gl.TRIANGLES, ...)`. */
  triangles: Uint32Array;
  /** The input vertex each vertex comes from, ascending. */
  origins: Uint32Array;
  /** Every channel of the input, by name, with `itemSize` floats per vertex and no `indices`. */
  attributes: Record<string, AttributeChannel>;
}
