// Stencil evaluation in wasm against OpenSubdiv natively, in one run: for each case, OpenSubdiv's
// Osd::CpuEvaluator::EvalStencils (tools/osd/osd_stencil_bench, built from Debian's libosd-dev)
// and subsurf's Evaluator.evaluate through the npm package (pkg/, one thread, simd128), on the
// same mesh, scheme, level and stencil count. Refined stencils ("refined") and the limit with
// normals ("limit": OpenSubdiv's LimitStencilTable with du/dv, ours with the two tangent weights
// and the normal computed per point). Also: our evaluator's build time against one `subdivide`
// call with the same options (and the time of the table's first use, where the evaluator left
// it out because a closed form gives every point), both tables' bytes per output point, what
// our frame reads per point (`Evaluator.bytes`); and the frame left in
// place (`Evaluator.evaluateView`, views of the module's memory: no copy out); and the tables
// level by level (`Evaluator.levelStencils()`, what the GPU evaluator uploads for an evaluator
// without normals): their time against the `subdivide` and their bytes per output point.
// Figures, not assertions.
//
//   node bench/stencil.mjs [REPEATS]     (after scripts/build-pkg.sh; default 10 timed frames)
//
// Cases: the 100k-quad torus (tools/osd/make_meshes.py torus --major 400 --minor 250) at
// Catmull-Clark level 2, and the horse (48,485 vertices, 96,966 triangles) at Loop levels 2 and 3
// and Catmull-Clark level 2 when it is found: bench/meshes/horse.obj, or an OBJ named by $HORSE
// (see bench/meshes/SOURCES.md for where to get it; it is not redistributed here).
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { BaseMesh, readObj, subdivide } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);
const repeats = Math.max(3, Number(process.argv[2] ?? 10));

const tmp = mkdtempSync(join(tmpdir(), 'subsurf-stencil-'));
const osdBench = join(root, 'target', 'osd', 'osd_stencil_bench');
mkdirSync(dirname(osdBench), { recursive: true });
const built = spawnSync('g++', ['-O2', '-std=c++14', '-o', osdBench, join(root, 'tools/osd/osd_stencil_bench.cpp'), '-losdCPU'], { stdio: 'inherit' });
if (built.status !== 0) throw new Error('building tools/osd/osd_stencil_bench.cpp failed (apt-get install libosd-dev)');
const torusPath = join(tmp, 'torus_400x250.obj');
spawnSync('python3', [join(root, 'tools/osd/make_meshes.py'), 'torus', '--major', '400', '--minor', '250', torusPath], { stdio: 'inherit' });

const horsePath = [join(root, 'bench/meshes/horse.obj'), process.env.HORSE].find((p) => p && existsSync(p));
const cases = [['torus 100k quads', torusPath, 'catmull-clark', 2]];
if (horsePath) {
  cases.push(['horse', horsePath, 'loop', 2], ['horse', horsePath, 'loop', 3], ['horse', horsePath, 'catmull-clark', 2]);
} else {
  console.log('(horse not found: set HORSE=/path/to/horse.obj; see bench/meshes/SOURCES.md)');
}

const osd = (path, scheme, level, limit) => {
  const args = ['--scheme', scheme === 'loop' ? 'loop' : 'catmark', '--level', String(level), '--repeats', String(repeats)];
  if (!limit) args.push('--no-limit');
  const run = spawnSync(osdBench, [...args, path], { encoding: 'utf8', maxBuffer: 1 << 24 });
  if (run.status !== 0) return null;
  const line = run.stdout.split('\n').find((l) => l.startsWith(`table=${limit ? 'limit' : 'refined'} `));
  return line ? Object.fromEntries(line.split(' ').map((f) => f.split('='))) : null;
};

const median = (times) => [...times].sort((a, b) => a - b)[times.length >> 1];
const best = (times) => Math.min(...times);
const timeIt = (n, f) => Array.from({ length: n }, () => { const s = performance.now(); f(); return performance.now() - s; });

console.log(`| case | table | points | OSD ns/pt | ours ns/pt | OSD/ours | ours ms/frame (best) | in place ns/pt | OSD B/pt | ours B/pt | frame reads B/pt | build/subdivide | table on demand / subdivide | level tables / subdivide | level tables B/pt |`);
console.log('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|');
for (const [name, path, scheme, level] of cases) {
  const mesh = readObj(readFileSync(path, 'utf8'));
  const base = new BaseMesh({ positions: mesh.positions, indices: mesh.indices, faceSizes: mesh.faceSizes });
  for (const limit of [false, true]) {
    if (limit && scheme === 'catmull-clark' && level > 2 && name === 'horse') continue;
    const reference = osd(path, scheme, level, limit);
    const options = { scheme, levels: level, limit, normals: limit, maxBytes: 4 * 2 ** 30 };
    // Five of each, so that the first call's growth of wasm memory (about 1.6 times a later
    // call) is not the median: with three, a subdivide measured 77 ms where later ones take 54.
    const subdivideMs = median(timeIt(5, () => base.subdivide(options)));
    let evaluator;
    const buildMs = median(timeIt(5, () => { evaluator?.free(); evaluator = base.evaluator(options); }));
    const points = evaluator.numVertices;
    let frame;
    let t = 0;
    const control = new Float32Array(mesh.positions.length);
    const step = () => {
      t += 1;
      const s = 1 + 0.001 * t;
      for (let i = 0; i < control.length; i++) control[i] = mesh.positions[i] * s;
    };
    step();
    frame = evaluator.evaluate(control, frame); // warm-up
    // Alternating with `evaluateView` (the frame left in place, as views of the module's
    // memory: the same work without the copy out).
    const times = [];
    const inPlace = [];
    for (let r = 0; r < repeats; r++) {
      step();
      let start = performance.now();
      frame = evaluator.evaluate(control, frame);
      times.push(performance.now() - start);
      step();
      start = performance.now();
      evaluator.evaluateView(control);
      inPlace.push(performance.now() - start);
    }
    const inPlaceNs = (median(inPlace) * 1e6) / points;
    const oursNs = (median(times) * 1e6) / points;
    const osdNs = reference ? Number(reference.ns_per_stencil) : NaN;
    // The table and, for Loop at the limit, the closed forms' data (`Evaluator.bytes`).
    const frameBytes = evaluator.bytes / points;
    // The tables level by level (`levelStencils()`: what the GPU evaluator uploads for an
    // evaluator without normals), made on each call: first, as a GPU user calls it, before any
    // composed table is held.
    const levelStart = performance.now();
    const levelTables = evaluator.levelStencils();
    const levelMs = performance.now() - levelStart;
    const arrayBytes = (t) => t.offsets.byteLength + t.indices.byteLength + t.weights.byteLength * (t.tangentWeights ? 3 : 1);
    const levelBytes = levelTables.reduce((sum, t) => sum + arrayBytes(t), 0) / points;
    // An evaluator whose closed forms give every point leaves its table out until it is asked
    // for (`stencils()`, `stencilBytes`, the GPU): that first call's time, else 0.
    const start = performance.now();
    const ourBytes = evaluator.stencilBytes / points;
    const onDemandMs = performance.now() - start;
    console.log(`| ${name} ${scheme} L${level} | ${limit ? 'limit + normals' : 'refined'} | ${points} | ${osdNs.toFixed(1)} | ${oursNs.toFixed(1)} | ${(osdNs / oursNs).toFixed(2)} | ${best(times).toFixed(1)} | ${inPlaceNs.toFixed(1)} | ${reference ? Number(reference.bytes_per_stencil).toFixed(1) : '-'} | ${ourBytes.toFixed(1)} | ${frameBytes.toFixed(1)} | ${(buildMs / subdivideMs).toFixed(2)} (${buildMs.toFixed(0)} / ${subdivideMs.toFixed(0)} ms) | ${(onDemandMs / subdivideMs).toFixed(2)} | ${(levelMs / subdivideMs).toFixed(2)} | ${levelBytes.toFixed(1)} |`);
    if (reference && Number(reference.stencils) !== points) console.log(`  (stencil counts differ: OSD ${reference.stencils}, ours ${points})`);
    evaluator.free();
  }
  base.free();
}
