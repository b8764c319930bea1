// The edges of a triangle geometry (three.js BufferGeometry, indexed) welded by position bits,
// for the watertightness checks of the glTF tests: shared by tests/js/gltf.mjs (Node) and the
// page of tests/e2e/gltf_model.mjs (Chromium, served as /tests/edges.mjs), so it uses no Node API.

/**
 * `{ boundary, loops, interior }` (boundary edges, boundary loops, interior edges) when every
 * edge is used once each way or once (a boundary), boundaries close and no two leave one vertex;
 * otherwise a string saying what is wrong.
 */
export function edgeCounts(geometry) {
  const p = geometry.getAttribute('position');
  const ids = new Map();
  const f32 = new Float32Array(3), bits = new Uint32Array(f32.buffer);
  const id = (v) => {
    f32[0] = p.getX(v) + 0; f32[1] = p.getY(v) + 0; f32[2] = p.getZ(v) + 0; // + 0: -0 as 0
    const k = `${bits[0]},${bits[1]},${bits[2]}`;
    if (!ids.has(k)) ids.set(k, ids.size);
    return ids.get(k);
  };
  const directed = new Map();
  const index = geometry.index.array;
  for (let t = 0; t < index.length; t += 3) {
    for (let j = 0; j < 3; j++) {
      const a = id(index[t + j]), b = id(index[t + ((j + 1) % 3)]);
      if (a === b) return `triangle ${t / 3} is degenerate by position`;
      const k = `${a},${b}`;
      if (directed.has(k)) return `edge ${k} is used twice the same way`;
      directed.set(k, [a, b]);
    }
  }
  let interior = 0;
  const next = new Map(); // boundary: from -> to
  for (const [a, b] of directed.values()) {
    if (directed.has(`${b},${a}`)) interior++;
    else {
      if (next.has(a)) return 'two boundary edges leave one vertex (a non-manifold boundary)';
      next.set(a, b);
    }
  }
  let loops = 0;
  const seen = new Set();
  for (const start of next.keys()) {
    if (seen.has(start)) continue;
    loops++;
    for (let v = start; !seen.has(v); v = next.get(v)) {
      if (!next.has(v)) return 'a boundary that does not close';
      seen.add(v);
    }
  }
  return { boundary: next.size, loops, interior: interior / 2 };
}
