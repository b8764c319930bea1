// What attribute channels cost in wasm: Catmull-Clark on the 1 M-quad torus at level 1, plain
// and with a vertex-varying `color` (itemSize 3), calls alternating in one process (pairs, the
// first left out) so that the drift of a shared VM hits both alike. Prints best and median ms
// of each and the ratio of the medians (the attributes issue's target is at most 1.6).
//   node bench/attributes.mjs [PAIRS]
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { quadTorus } from './torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { subdivide } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);

const pairs = Math.max(2, Number(process.argv[2] ?? 8));
const plain = quadTorus();
const color = new Float32Array(plain.positions.length);
for (let i = 0; i < color.length; i++) color[i] = (i % 7) / 7;
const colored = { ...plain, attributes: { color: { array: color, itemSize: 3 } } };

const time = (mesh) => {
  const start = performance.now();
  subdivide(mesh, { levels: 1 });
  return performance.now() - start;
};
const [a, b] = [[], []];
for (let pair = 0; pair < pairs; pair++) {
  const [ta, tb] = [time(plain), time(colored)];
  if (pair > 0) a.push(ta), b.push(tb);
}
const stats = (t) => {
  const s = [...t].sort((x, y) => x - y);
  return [s[0], s[s.length >> 1]];
};
const [[bestA, medA], [bestB, medB]] = [stats(a), stats(b)];
console.log(
  `catmull-clark 1M quads L1: positions only best ${bestA.toFixed(0)} median ${medA.toFixed(0)} ms | ` +
    `+ color (3) best ${bestB.toFixed(0)} median ${medB.toFixed(0)} ms | ratio ${(medB / medA).toFixed(3)}`,
);
