// The types of the demo's helpers (shape, shapeNames, predictCounts, vertexNormals, edgeList),
// appended to subsurf.d.ts as js/types.d.ts is.
/** Predicted sizes after 0, 1, ..., `levels` levels: entry `l` is the size after `l` levels. */
export interface PredictedCounts {
  vertices: Float64Array;
  /** The number `maxFaces` is compared with; exact except for 'doo-sabin' and 'quad-triangle' (upper bounds). */
  faces: Float64Array;
}
