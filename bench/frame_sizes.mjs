// Catmull-Clark limit + normals frames (evaluateView, in place) on tori of triangles of three
// sizes, frames interleaved in one process: what a frame costs per point when its topology and
// points stay in the caches against when they do not. The code path is the horse's (the
// levels' steps, then the last level's rings), so the difference is its memory traffic.
//   node bench/frame_sizes.mjs [ROUNDS]     (after scripts/build-pkg.sh; default 15)
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { torus } from './torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { BaseMesh } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);
const rounds = Math.max(3, Number(process.argv[2] ?? 15));
const sizes = [[20, 12], [60, 40], [250, 200]];
const cases = sizes.map(([rings, segments]) => {
  const mesh = torus(rings, segments, 1.0, 0.25, true);
  const options = { scheme: 'catmull-clark', levels: 2, limit: true, normals: true };
  return { mesh, evaluator: new BaseMesh(mesh).evaluator(options), times: [] };
});
for (let r = 0; r < rounds; r++) {
  for (const { mesh, evaluator, times } of cases) {
    const control = new Float32Array(mesh.positions);
    control[0] += 1e-6 * r;
    // About 1.2M points per timing whatever the size, so each timing is long enough to read.
    const repeats = Math.max(1, Math.round(1.2e6 / evaluator.numVertices));
    const start = performance.now();
    for (let k = 0; k < repeats; k++) evaluator.evaluateView(control);
    times.push(((performance.now() - start) * 1e6) / repeats / evaluator.numVertices);
  }
}
const median = (x) => [...x].sort((a, b) => a - b)[x.length >> 1];
console.log('| output points | median ns / point | best ns / point |');
console.log('|---|---|---|');
for (const { evaluator, times } of cases) {
  console.log(`| ${evaluator.numVertices} | ${median(times).toFixed(1)} | ${Math.min(...times).toFixed(1)} |`);
}
