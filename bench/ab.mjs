// Compares two builds of the wasm package in one Node process, calls alternating, so that the
// drift of a shared VM (steal time, other tenants) hits both alike: the way to tell whether a
// change made `subdivide` faster when separate runs of bench/node_bench.mjs differ by 20-30 %.
//   node bench/ab.mjs PKG_A PKG_B [PAIRS] [quads|tris|all] [SCHEME] [fresh|basemesh]
// `basemesh` times `base.subdivide(options, previous)` on a BaseMesh built once per package:
// the compute alone, without the fresh arrays' page faults that make most of a fresh call (a
// 16 % slower refinement showed as 4 % in fresh calls).
// PKG_A and PKG_B are package directories (pkg/ of two worktrees, each from
// scripts/build-pkg.sh). The first pair is left out (it grows the wasm memories). Prints best and
// median per package and the geometric mean of B/A over the pairs: below 1 means B is faster.
// Whichever package goes second in a pair tends to gain a few per cent, so swap A and B and run
// again before trusting a small difference.
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

import { quadTorus, triangleTorus } from './torus.mjs';

const [dirA, dirB, pairsArg = '12', which = 'quads', scheme = 'catmull-clark', way = 'fresh'] = process.argv.slice(2);
if (!dirA || !dirB) {
  console.error('usage: node bench/ab.mjs PKG_A PKG_B [PAIRS] [quads|tris|all] [SCHEME] [fresh|basemesh]');
  process.exit(2);
}
const load = (dir) => import(pathToFileURL(resolve(dir, 'node.js')).href);
const [a, b] = [await load(dirA), await load(dirB)];
const pairs = Math.max(2, Number(pairsArg));

const quads = which === 'tris' ? null : quadTorus();
const tris = which === 'quads' ? null : triangleTorus();
const cases = [
  ...(quads && scheme !== 'loop' && scheme !== 'midpoint' && scheme !== 'sqrt3' ? [['1M quads', quads, 1]] : []),
  ...(tris ? (which === 'all' ? [1, 2, 3] : [3]).map((l) => ['100k tris', tris, l]) : []),
];

// Per package and mesh: a BaseMesh and the previous result, for `basemesh`.
const kept = new Map();
const time = (pkg, mesh, levels) => {
  if (way === 'basemesh') {
    if (!kept.has(pkg)) kept.set(pkg, new Map());
    const mine = kept.get(pkg);
    if (!mine.has(mesh)) mine.set(mesh, { base: new pkg.BaseMesh(mesh), previous: undefined });
    const state = mine.get(mesh);
    const start = performance.now();
    state.previous = state.base.subdivide({ scheme, levels }, state.previous);
    return [performance.now() - start, state.previous.faceSizes.length];
  }
  const start = performance.now();
  const faces = pkg.subdivide(mesh, { scheme, levels }).faceSizes.length;
  return [performance.now() - start, faces];
};
for (const [name, mesh, levels] of cases) {
  const [ta, tb] = [[], []];
  let faces = 0;
  for (let pair = 0; pair < pairs; pair++) {
    ta.push(time(a, mesh, levels)[0]);
    const [t, n] = time(b, mesh, levels);
    tb.push(t);
    faces = n;
  }
  const stats = (t) => {
    const s = t.slice(1).sort((x, y) => x - y);
    const [best, median] = [s[0], s[s.length >> 1]];
    return `best ${best.toFixed(0)} median ${median.toFixed(0)} ms (${(faces / best / 1e3).toFixed(1)} / ${(faces / median / 1e3).toFixed(1)} M faces/s)`;
  };
  const logRatio = ta.slice(1).reduce((sum, x, i) => sum + Math.log(tb[i + 1] / x), 0) / (pairs - 1);
  console.log(`${scheme} ${name} L${levels}: A ${stats(ta)} | B ${stats(tb)} | B/A ${Math.exp(logRatio).toFixed(3)}`);
}
