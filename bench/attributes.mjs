// What attribute channels cost in wasm: Catmull-Clark on the 1 M-quad torus at level 1, plain,
// with a vertex-varying `color` (itemSize 3), and with that colour and a face-varying `uv`
// (itemSize 2, the torus's (u, v) grid: seams along both closing loops), calls rotating in one
// process (rounds, the first left out) so that the drift of a shared VM hits all alike. Prints
// best and median ms of each and the ratios of the medians to the plain call (the attributes
// issue's target for uv + color is at most 1.6).
//   node bench/attributes.mjs [ROUNDS]
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { quadTorus, torusUvs } from './torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { subdivide } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);

const rounds = Math.max(2, Number(process.argv[2] ?? 8));
const plain = quadTorus();
const color = new Float32Array(plain.positions.length);
for (let i = 0; i < color.length; i++) color[i] = (i % 7) / 7;
const colored = { ...plain, attributes: { color: { array: color, itemSize: 3 } } };
const uv = torusUvs(1000, 1000);
const textured = { ...plain, attributes: { uv, color: { array: color, itemSize: 3 } } };

const time = (mesh) => {
  const start = performance.now();
  subdivide(mesh, { levels: 1 });
  return performance.now() - start;
};
const cases = [plain, colored, textured];
const times = cases.map(() => []);
for (let round = 0; round < rounds; round++) {
  cases.forEach((mesh, i) => {
    const t = time(mesh);
    if (round > 0) times[i].push(t);
  });
}
const stats = (t) => {
  const s = [...t].sort((x, y) => x - y);
  return [s[0], s[s.length >> 1]];
};
const [[bestA, medA], [bestB, medB], [bestC, medC]] = times.map(stats);
console.log(
  `catmull-clark 1M quads L1: positions only best ${bestA.toFixed(0)} median ${medA.toFixed(0)} ms | ` +
    `+ color (3) best ${bestB.toFixed(0)} median ${medB.toFixed(0)} ms, ratio ${(medB / medA).toFixed(3)} | ` +
    `+ uv (2, face-varying) + color best ${bestC.toFixed(0)} median ${medC.toFixed(0)} ms, ratio ${(medC / medA).toFixed(3)}`,
);
