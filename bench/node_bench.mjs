// Times the built wasm package (pkg/, from scripts/build-pkg.sh) in Node on the benchmark
// meshes of benches/table.rs and tools/osd/far_perf.sh: a 1 M-quad torus (level 1) and a
// 100 k-triangle torus (levels 1-3), every scheme, median of 5 calls of `subdivide`.
//   node bench/node_bench.mjs [scheme ...]
// Prints a markdown table: ms per call and million output faces per second.
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { subdivide } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);

// The torus layout of src/shapes.rs: vertex i*segments + j, face (i,j),(i+1,j),(i+1,j+1),(i,j+1).
function torus(rings, segments, major, minor, triangles) {
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

const quads = torus(1000, 1000, 1.0, 0.25, false);
const tris = torus(250, 200, 1.0, 0.25, true);
const cases = [['torus 1M quads', quads, 1], ['torus 100k tris', tris, 1], ['torus 100k tris', tris, 2], ['torus 100k tris', tris, 3]];
const all = ['catmull-clark', 'loop', 'doo-sabin', 'quad-triangle', 'sqrt3', 'bilinear', 'midpoint'];
const schemes = process.argv.length > 2 ? process.argv.slice(2) : all;
const triangleOnly = new Set(['loop', 'midpoint', 'sqrt3']);

console.log('| scheme | mesh | level | faces out | ms (median of 5) | M faces/s |');
console.log('|---|---|---|---|---|---|');
for (const scheme of schemes) {
  for (const [name, mesh, levels] of cases) {
    if (triangleOnly.has(scheme) && mesh.faceSizes) continue;
    const times = [];
    let faces = 0;
    for (let run = 0; run < 5; run++) {
      const start = performance.now();
      const out = subdivide(mesh, { scheme, levels });
      times.push(performance.now() - start);
      faces = out.faceSizes.length;
    }
    times.sort((a, b) => a - b);
    const ms = times[2];
    console.log(`| ${scheme} | ${name} | ${levels} | ${faces} | ${ms.toFixed(1)} | ${(faces / ms / 1e3).toFixed(1)} |`);
  }
}
