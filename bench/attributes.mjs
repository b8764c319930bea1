// What attribute channels cost in wasm: Catmull-Clark on the 1 M-quad torus at level 1, plain,
// with a vertex-varying `color` (itemSize 3), with a face-varying `uv` (itemSize 2, the torus's
// (u, v) grid: seams along both closing loops), and with both, calls rotating in one process
// (rounds, the first left out) so that the drift of a shared VM hits all alike. Prints best and
// median ms of each, the ratios of the best times to the plain call's, and the median of each
// round's ratio to the plain call of that round (the attributes issue's target for uv + color is
// at most 1.6; the medians catch the VM's spikes). Given
// package directories (pkg/ of two worktrees, each from scripts/build-pkg.sh), it alternates
// them too (each going first in every other round) and prints one line per package: the way to
// tell whether a change helped.
// INTO=1 passes each case's previous result as `into`, so that every call writes over arrays
// it already has (a per-frame caller's steady state) instead of making fresh ones, whose
// first-touch page faults are most of a call on our VMs.
//   [INTO=1] node bench/attributes.mjs [ROUNDS] [PKG ...]
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { quadTorus, torusUvs } from './torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const rounds = Math.max(2, Number(process.argv[2] ?? 8));
const dirs = process.argv.length > 3 ? process.argv.slice(3).map((d) => resolve(d)) : [join(root, 'pkg')];
const packages = [];
for (const dir of dirs) packages.push(await import(pathToFileURL(join(dir, 'node.js')).href));

const plain = quadTorus();
const color = new Float32Array(plain.positions.length);
for (let i = 0; i < color.length; i++) color[i] = (i % 7) / 7;
const uv = torusUvs(1000, 1000);
const cases = {
  'positions only': plain,
  '+ color (3)': { ...plain, attributes: { color: { array: color, itemSize: 3 } } },
  '+ uv (2, face-varying)': { ...plain, attributes: { uv } },
  '+ uv + color': { ...plain, attributes: { uv, color: { array: color, itemSize: 3 } } },
};

const times = packages.map(() => Object.fromEntries(Object.keys(cases).map((name) => [name, []])));
const reuse = Boolean(process.env.INTO);
const previous = packages.map(() => ({}));
// The packages take turns going first (ABBA): with one fixed order, whichever ran first was
// slower by a few percent, which is the size of the changes this is meant to judge.
const order = packages.map((_, k) => k);
// The cases take turns going first too: the collection of a round's fresh arrays lands in the
// next calls, and always in the plain one it made that call slower and every ratio smaller.
const entries = Object.entries(cases);
for (let round = 0; round < rounds; round++) {
  const shift = round % entries.length;
  for (const [name, mesh] of [...entries.slice(shift), ...entries.slice(0, shift)]) {
    const turn = round % 2 === 0 ? order : [...order].reverse();
    turn.forEach((k) => {
      const { subdivide } = packages[k];
      const into = reuse ? previous[k][name] : undefined;
      const start = performance.now();
      const result = subdivide(mesh, { levels: 1 }, into);
      const t = performance.now() - start;
      if (reuse) previous[k][name] = result;
      if (round > 0) times[k][name].push(t);
    });
  }
}
const stats = (t) => {
  const s = [...t].sort((x, y) => x - y);
  return { best: s[0], median: s[s.length >> 1] };
};
packages.forEach((_, k) => {
  const all = Object.fromEntries(Object.entries(times[k]).map(([name, t]) => [name, stats(t)]));
  const base = all['positions only'];
  // Each round's call against the plain call of the same round, then the median of those: calls
  // made side by side share the VM's state of the moment, which the best and median times of
  // separate calls do not (the VM drifts by 10-30 % within a run).
  const plainTimes = times[k]['positions only'];
  const paired = (name) => stats(times[k][name].map((t, r) => t / plainTimes[r])).median;
  const parts = Object.entries(all).map(([name, { best, median }]) => {
    const ratio =
      name === 'positions only'
        ? ''
        : `, ratio ${(best / base.best).toFixed(2)} (per round: median ${paired(name).toFixed(2)})`;
    return `${name} best ${best.toFixed(0)} median ${median.toFixed(0)} ms${ratio}`;
  });
  const label = packages.length > 1 ? `${dirs[k]}: ` : '';
  const mode = reuse ? ' (into: arrays reused)' : '';
  console.log(`${label}catmull-clark 1M quads L1${mode}: ${parts.join(' | ')}`);
});
