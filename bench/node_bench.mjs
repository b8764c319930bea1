// Times the built wasm package (pkg/, from scripts/build-pkg.sh) in Node on the benchmark
// meshes of benches/table.rs and tools/osd/far_perf.sh: a 1 M-quad torus (level 1) and a
// 100 k-triangle torus (levels 1-3), every scheme, 7 calls of `subdivide` each (the first, which
// also grows the wasm memory, is left out; best and median of the other 6).
//   node bench/node_bench.mjs [scheme ...]
// Three ways to call, each timed so:
//   fresh     subdivide(mesh, options): every call returns fresh arrays;
//   into      subdivide(mesh, options, previous): the previous result's arrays are written over;
//   BaseMesh  new BaseMesh(mesh) once ("create", the best of 7), then
//             base.subdivide(options, previous): OpenSubdiv's split, where create is
//             TopologyRefinerFactory::Create and the call is refine + interpolate.
// Prints a markdown table: ms per call (best / median) and million output faces per second of
// the medians. The last column is the floor fresh arrays set: allocating typed arrays of the
// result's sizes and writing them once, in plain JS, in the same process. On a VM, first-touch
// page faults make most of it.
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { quadTorus, triangleTorus } from './torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { subdivide, BaseMesh } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);

const quads = quadTorus();
const tris = triangleTorus();
const cases = [['torus 1M quads', quads, 1], ['torus 100k tris', tris, 1], ['torus 100k tris', tris, 2], ['torus 100k tris', tris, 3]];
const all = ['catmull-clark', 'loop', 'doo-sabin', 'quad-triangle', 'sqrt3', 'bilinear', 'midpoint'];
const schemes = process.argv.length > 2 ? process.argv.slice(2) : all;
const triangleOnly = new Set(['loop', 'midpoint', 'sqrt3']);

// Fresh typed arrays of the result's sizes, each written once: what returning the result costs
// before any subdivision is done.
function floorMs(out) {
  const sizes = ['positions', 'indices', 'faceSizes', 'triangles'].map((k) => out[k].length);
  const times = [];
  for (let run = 0; run < 5; run++) {
    const start = performance.now();
    for (const n of sizes) new Uint32Array(n).fill(1);
    times.push(performance.now() - start);
  }
  return times.sort((a, b) => a - b)[2];
}

const runs = 7;

/// Best and median of runs 2..7 of `call(previous result)`, and the last result.
function time(call) {
  const times = [];
  let out;
  for (let run = 0; run < runs; run++) {
    const start = performance.now();
    out = call(out);
    times.push(performance.now() - start);
  }
  const sorted = times.slice(1).sort((a, b) => a - b);
  return { best: sorted[0], median: sorted[sorted.length >> 1], out };
}

console.log('| scheme | mesh | level | faces out | fresh ms | into ms | BaseMesh create ms | BaseMesh ms | M faces/s fresh / into / BaseMesh | JS floor ms |');
console.log('|---|---|---|---|---|---|---|---|---|---|');
for (const scheme of schemes) {
  for (const [name, mesh, levels] of cases) {
    if (triangleOnly.has(scheme) && mesh.faceSizes) continue;
    const options = { scheme, levels };
    // Let the previous result go before the next call, as an app would.
    const fresh = time(() => subdivide(mesh, options));
    const into = time((previous) => subdivide(mesh, options, previous));
    let base;
    const create = time(() => (base?.free(), (base = new BaseMesh(mesh))));
    const based = time((previous) => base.subdivide(options, previous));
    base.free();
    const faces = fresh.out.faceSizes.length;
    const floor = floorMs(fresh.out);
    const ms = (t) => `${t.best.toFixed(1)} / ${t.median.toFixed(1)}`;
    const rate = (t) => (faces / t.median / 1e3).toFixed(1);
    console.log(`| ${scheme} | ${name} | ${levels} | ${faces} | ${ms(fresh)} | ${ms(into)} | ${create.best.toFixed(1)} | ${ms(based)} | ${rate(fresh)} / ${rate(into)} / ${rate(based)} | ${floor.toFixed(1)} |`);
  }
}
