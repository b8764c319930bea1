// Two builds of the package in one Node process, alternating, on stencil tables: per case the
// build time of `BaseMesh.evaluator` against one `BaseMesh.subdivide` with the same options, and
// `evaluate` per output point. The way to judge a change to the stencil code on a shared VM,
// where separate runs differ by 20-30 % (see bench/ab.mjs).
//   node bench/stencil_ab.mjs PKG_A PKG_B [ROUNDS] [CASES]
// CASES: comma-separated of refined, limit (the 100k-quad torus, Catmull-Clark level 2) and
// horse-loop2, horse-loop3, horse-cc2 (refined and limit; the OBJ named by $HORSE). Default
// refined,limit. Prints medians per package and the median of B/A over the rounds (below 1:
// B is faster).
import { readFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

import { torus } from './torus.mjs';

const [dirA, dirB, roundsArg = '5', casesArg = 'refined,limit'] = process.argv.slice(2);
if (!dirA || !dirB) {
  console.error('usage: node bench/stencil_ab.mjs PKG_A PKG_B [ROUNDS] [CASES]');
  process.exit(2);
}
const load = (dir) => import(pathToFileURL(resolve(dir, 'node.js')).href);
const pkgs = [await load(dirA), await load(dirB)];
const rounds = Math.max(2, Number(roundsArg));
const torusMesh = torus(400, 250, 1.0, 0.25, false);
let horse;
const horseMesh = () => {
  if (!horse) {
    const obj = readFileSync(process.env.HORSE ?? 'bench/meshes/horse.obj', 'utf8');
    const m = pkgs[0].readObj(obj);
    horse = { positions: m.positions, indices: m.indices, faceSizes: m.faceSizes };
  }
  return horse;
};
const cases = [];
for (const name of casesArg.split(',')) {
  const add = (label, mesh, scheme, levels) => {
    cases.push([`${label} refined`, mesh, { scheme, levels }]);
    cases.push([`${label} limit+normals`, mesh, { scheme, levels, limit: true, normals: true }]);
  };
  if (name === 'refined') cases.push(['torus CC L2 refined', torusMesh, { scheme: 'catmull-clark', levels: 2 }]);
  else if (name === 'limit') cases.push(['torus CC L2 limit+normals', torusMesh, { scheme: 'catmull-clark', levels: 2, limit: true, normals: true }]);
  else if (name === 'horse-loop2') add('horse Loop L2', horseMesh(), 'loop', 2);
  else if (name === 'horse-loop3') add('horse Loop L3', horseMesh(), 'loop', 3);
  else if (name === 'horse-cc2') add('horse CC L2', horseMesh(), 'catmull-clark', 2);
  else throw new Error(`unknown case ${name}`);
}
const median = (t) => [...t].sort((x, y) => x - y)[t.length >> 1];
const now = () => performance.now();
for (const [label, mesh, opts] of cases) {
  const options = { ...opts, maxBytes: 4 * 2 ** 30 };
  const state = pkgs.map((p) => ({ base: new p.BaseMesh(mesh), sub: [], build: [], evalNs: [], ev: undefined, frame: undefined }));
  const control = new Float32Array(mesh.positions.length);
  let t = 0;
  for (let round = 0; round <= rounds; round++) {
    for (const s of round % 2 ? [...state].reverse() : state) {
      let start = now();
      s.base.subdivide(options);
      const sub = now() - start;
      s.ev?.free();
      start = now();
      s.ev = s.base.evaluator(options);
      const build = now() - start;
      const frames = [];
      for (let f = 0; f < 5; f++) {
        t += 1;
        for (let i = 0; i < control.length; i++) control[i] = mesh.positions[i] * (1 + 0.001 * t);
        start = now();
        s.frame = s.ev.evaluate(control, s.frame);
        frames.push(now() - start);
      }
      if (round > 0) {
        s.sub.push(sub);
        s.build.push(build);
        s.evalNs.push((median(frames) * 1e6) / s.ev.numVertices);
      }
    }
  }
  const ratio = (f) => median(state[0][f].map((a, i) => state[1][f][i] / a));
  const line = (s, n) => `${n}: subdivide ${median(s.sub).toFixed(0)} ms, build ${median(s.build).toFixed(0)} ms (${median(s.build.map((b, i) => b / s.sub[i])).toFixed(2)}x), eval ${median(s.evalNs).toFixed(1)} ns/pt`;
  console.log(`${label} (${state[0].ev.numVertices} points)\n  ${line(state[0], 'A')}\n  ${line(state[1], 'B')}\n  B/A: build ${ratio('build').toFixed(3)}, eval ${ratio('evalNs').toFixed(3)}`);
  for (const s of state) { s.ev.free(); s.base.free(); }
}
