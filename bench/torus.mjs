// The benchmark tori of src/shapes.rs and tools/osd/make_meshes.py, as typed arrays: vertex
// i*segments + j, face (i,j),(i+1,j),(i+1,j+1),(i,j+1), or its two triangles (i,j),(i+1,j),
// (i+1,j+1) and (i,j),(i+1,j+1),(i,j+1). Without faceSizes when all faces are triangles.
export function torus(rings, segments, major, minor, triangles) {
  const positions = new Float32Array(3 * rings * segments);
  for (let i = 0; i < rings; i++) {
    const theta = (2 * Math.PI * i) / rings;
    for (let j = 0; j < segments; j++) {
      const phi = (2 * Math.PI * j) / segments;
      const r = major + minor * Math.cos(phi);
      positions.set([r * Math.cos(theta), r * Math.sin(theta), minor * Math.sin(phi)], 3 * (i * segments + j));
    }
  }
  const v = (i, j) => (i % rings) * segments + (j % segments);
  const quads = rings * segments;
  const indices = new Uint32Array(triangles ? 6 * quads : 4 * quads);
  let k = 0;
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < segments; j++) {
      const [a, b, c, d] = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
      if (triangles) indices.set([a, b, c, a, c, d], k), (k += 6);
      else indices.set([a, b, c, d], k), (k += 4);
    }
  }
  const faceSizes = triangles ? undefined : new Uint32Array(quads).fill(4);
  return { positions, indices, faceSizes };
}

// The two benchmark meshes: 1 M quads (level 1) and 100 k triangles (levels 1-3).
export const quadTorus = () => torus(1000, 1000, 1.0, 0.25, false);
export const triangleTorus = () => torus(250, 200, 1.0, 0.25, true);

// The (u, v) grid of torus(rings, segments, ...) as a face-varying channel: one value per grid
// point of (rings + 1) x (segments + 1), so the two closing loops are seams.
export function torusUvs(rings, segments) {
  const array = new Float32Array(2 * (rings + 1) * (segments + 1));
  for (let i = 0; i <= rings; i++) {
    for (let j = 0; j <= segments; j++) array.set([i / rings, j / segments], 2 * (i * (segments + 1) + j));
  }
  const value = (i, j) => i * (segments + 1) + j;
  const indices = new Uint32Array(4 * rings * segments);
  let k = 0;
  for (let i = 0; i < rings; i++) {
    for (let j = 0; j < segments; j++) {
      indices.set([value(i, j), value(i + 1, j), value(i + 1, j + 1), value(i, j + 1)], k);
      k += 4;
    }
  }
  return { array, itemSize: 2, indices };
}
