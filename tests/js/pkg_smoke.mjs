// Smoke test of the built npm package in pkg/ (run scripts/build-pkg.sh first):
//   node tests/js/pkg_smoke.mjs
// Installs pkg/'s `files` into a temporary node_modules/subsurf, imports it the three ways a
// user would (`subsurf/node`, `initSync`, `await init`), subdivides a cube and checks counts,
// positions, errors, BaseMesh and `into` through the generated glue, and the TypeScript
// declarations: their text, and `tsc` (package.json's pinned version) on a consumer file,
// tests/js/types_check.ts (and worker_types_check.ts). Exits non-zero on the first failure.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { cpSync, mkdtempSync, readFileSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { torus } from '../../bench/torus.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkgDir = join(root, 'pkg');
let checks = 0;

function check(name, fn) {
  try {
    fn();
    checks++;
  } catch (error) {
    console.error(`pkg_smoke: FAILED ${name}\n${error.stack ?? error}`);
    process.exit(1);
  }
}

// ---- package.json and files
const pkg = JSON.parse(readFileSync(join(pkgDir, 'package.json'), 'utf8'));
const cargoVersion = readFileSync(join(root, 'Cargo.toml'), 'utf8').match(/^version\s*=\s*"([^"]+)"/m)[1];
check('package.json', () => {
  assert.equal(pkg.name, 'subsurf');
  assert.equal(pkg.version, cargoVersion);
  assert.equal(pkg.type, 'module');
  assert.equal(pkg.types, './subsurf.d.ts');
  assert.ok(pkg.exports['.'] && pkg.exports['./node'], 'exports . and ./node');
  assert.equal(pkg.exports['.'].node, './node.js', "'.' has a node condition");
  assert.equal(pkg.exports['.'].default, './auto.js', "'.' initialises itself elsewhere (top-level await)");
  assert.deepEqual(pkg.exports['./init'], { types: './subsurf.d.ts', default: './init.js' });
  assert.deepEqual(pkg.exports['./webgpu'], { types: './webgpu.d.ts', default: './webgpu.js' });
  assert.deepEqual(pkg.exports['./worker'], { types: './worker.d.ts', node: './worker-node.js', default: './worker.js' });
  assert.deepEqual(pkg.exports['./worker-thread'], { types: './worker-thread.d.ts', default: './worker-thread.js' });
});

const scratch = mkdtempSync(join(tmpdir(), 'subsurf-smoke-'));
process.on('exit', () => rmSync(scratch, { recursive: true, force: true }));
const installed = join(scratch, 'node_modules', 'subsurf');
mkdirSync(installed, { recursive: true });
for (const file of [...pkg.files, 'package.json']) {
  cpSync(join(pkgDir, file), join(installed, file)); // throws when `files` names a missing file
}
writeFileSync(
  join(scratch, 'consumer.mjs'),
  "export * as node from 'subsurf/node';\nexport * as web from 'subsurf';\nexport * as webgpu from 'subsurf/webgpu';\n",
);

// ---- the three ways to load it
const { node, web, webgpu } = await import(pathToFileURL(join(scratch, 'consumer.mjs')).href);
// `import ... from 'subsurf'` in Node takes the "node" condition: ready with no init, and a
// browser-style `await init()` returns at once.
await web.default();
const bytes = readFileSync(join(installed, 'subsurf_bg.wasm'));
// A query string gives a separate module instance, so each loader starts from scratch.
const viaInitSync = await import(pathToFileURL(join(installed, 'subsurf.js')).href + '?initSync');
viaInitSync.initSync({ module: bytes });
const viaInit = await import(pathToFileURL(join(installed, 'subsurf.js')).href + '?init');
await viaInit.default({ module_or_path: bytes });

const cube = () => ({
  positions: new Float32Array([-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1, -1, -1, 1, 1, -1, 1, -1, 1, 1, 1, 1, 1]),
  indices: new Uint32Array([0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5]),
  faceSizes: new Uint32Array([4, 4, 4, 4, 4, 4]),
});
const near = (a, b) => Math.abs(a - b) < 1e-6;

for (const [name, api] of [['subsurf/node', node], ["'subsurf' in Node, no init", web], ['initSync', viaInitSync], ['await init', viaInit]]) {
  check(`${name}: version`, () => assert.equal(api.version(), cargoVersion));

  check(`${name}: cube counts`, () => {
    for (const [levels, vertices, faces] of [[1, 26, 24], [2, 98, 96], [3, 386, 384]]) {
      const out = api.subdivide(cube(), { levels });
      assert.ok(out.positions instanceof Float32Array && out.triangles instanceof Uint32Array);
      assert.equal(out.positions.length, 3 * vertices, `level ${levels} vertices`);
      assert.equal(out.faceSizes.length, faces, `level ${levels} faces`);
      assert.equal(out.indices.length, 4 * faces);
      assert.equal(out.triangles.length, 6 * faces);
    }
  });

  check(`${name}: cube positions (seed 003)`, () => {
    const input = cube();
    const p = api.subdivide(input, { levels: 1 }).positions;
    for (let v = 0; v < 8; v++) {
      for (let k = 0; k < 3; k++) assert.ok(near(p[3 * v + k], (input.positions[3 * v + k] * 5) / 9), `vertex ${v}`);
    }
    const points = [];
    for (let v = 8; v < 26; v++) points.push([p[3 * v], p[3 * v + 1], p[3 * v + 2]]);
    const has = (q) => points.some((r) => r.every((x, k) => near(x, q[k])));
    assert.ok(has([0, -1, 0]), 'face point (0, -1, 0)');
    assert.ok(has([0, -0.75, -0.75]), 'edge point (0, -0.75, -0.75)');
    assert.deepEqual(input, cube(), 'input arrays unchanged');
  });

  check(`${name}: triangles when faceSizes is omitted`, () => {
    const tetra = { positions: new Float32Array([1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1]), indices: new Uint32Array([0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2]) };
    const out = api.subdivide(tetra);
    assert.equal(out.positions.length, 3 * 14);
    assert.equal(out.faceSizes.length, 12);
  });

  check(`${name}: errors, then still working`, () => {
    assert.throws(() => api.subdivide(cube(), { level: 2 }), (e) => e instanceof Error && /unknown option 'level'.*'levels'.*'maxFaces'/.test(e.message));
    assert.throws(() => api.subdivide({ ...cube(), indices: new Float32Array(24) }), /mesh\.indices must be a Uint32Array, got Float32Array/);
    assert.throws(() => api.subdivide(cube(), { levels: -1 }), /levels must be a whole number.*got -1/);
    assert.throws(() => api.subdivide(cube(), { boundary: 'sharp' }), /'sharp'.*'edge-and-corner'/);
    assert.throws(() => api.readObj('v 0 0 0\nf 1 2 3\n'), /OBJ line 2/);
    assert.equal(api.subdivide(cube(), { levels: 2 }).faceSizes.length, 96);
  });

  // Through the generated class glue (the wasm-bindgen tests call the Rust methods directly).
  check(`${name}: BaseMesh, setPositions and into`, () => {
    const base = new api.BaseMesh(cube());
    assert.equal(base.numVertices, 8);
    assert.equal(base.numFaces, 6);
    const plain = api.subdivide(cube(), { levels: 2 });
    const first = base.subdivide({ levels: 2 });
    assert.deepEqual(first, plain);
    base.setPositions(cube().positions.map((x) => 2 * x));
    const second = base.subdivide({ levels: 2 }, first);
    for (const key of ['positions', 'indices', 'faceSizes', 'triangles']) assert.equal(second[key], first[key], `${key} reused`);
    // Catmull-Clark commutes with scaling (affine invariance): twice the input, twice the result.
    assert.ok(second.positions.every((x, i) => near(x, 2 * plain.positions[i])), 'moved');
    assert.deepEqual(second.indices, plain.indices);
    assert.throws(() => base.setPositions(new Float32Array(3)), /1 vertices.*the mesh has 8/);
    assert.throws(() => base.subdivide({ levels: 1 }, 5), /into must be a result of an earlier subdivide call/);
    const reused = api.subdivide(cube(), { levels: 2 }, second);
    assert.equal(reused.positions, second.positions);
    assert.deepEqual(reused, plain);
    const evaluator = base.evaluator({ levels: 1 });
    // An evaluator shares its BaseMesh's connectivity for the table it makes on first use:
    // moving and freeing the BaseMesh changes nothing of it.
    const limit = { levels: 2, limit: true, normals: true };
    const lazy = base.evaluator(limit);
    assert.equal(lazy.hasStencilTable, false, 'the cube is a closed cage: its table waits');
    base.setPositions(cube().positions.map((x) => 3 * x));
    base.free();
    // The package's entries say what was freed and what to do (freed.js); the bare glue
    // (subsurf.js loaded directly: the last two loaders) keeps wasm-bindgen's own message.
    const guarded = api === node || api === web;
    const freed = (what) => (guarded ? new RegExp(`${what} called after free\\(\\); `) : Error);
    assert.throws(() => base.subdivide({ levels: 1 }), freed('BaseMesh\\.subdivide'), 'a freed BaseMesh throws');
    assert.throws(() => base.numVertices, freed('BaseMesh\\.numVertices'), 'and its getters');
    assert.equal(evaluator.evaluate(cube().positions).positions.length, 3 * 26, 'an evaluator outlives its BaseMesh');
    const fresh = new api.BaseMesh(cube());
    assert.deepEqual(lazy.stencils(), fresh.evaluator(limit).stencils(), 'its table on first use, after its BaseMesh moved and was freed');
    assert.deepEqual(lazy.levelStencils(), fresh.evaluator(limit).levelStencils(), 'and its level stencils');
    lazy.free();
    fresh.free();
    evaluator.free();
    assert.throws(() => evaluator.evaluate(cube().positions), freed('Evaluator\\.evaluate'), 'a freed Evaluator throws');
    assert.throws(() => evaluator.evaluateView(cube().positions), freed('Evaluator\\.evaluateView'), 'a freed Evaluator throws on evaluateView');
    if (guarded) {
      evaluator.free();
      base[Symbol.dispose]?.();
    }
    assert.equal(api.subdivide(cube(), { levels: 1 }).faceSizes.length, 24, 'and the module works on');
  });

  // UVs through the glue: readObj's face-varying channel, writeObj's vt lines, and toDrawable
  // splitting the two vertices of a seam (the square's two triangles each with its own values).
  check(`${name}: UVs, writeObj and toDrawable`, () => {
    const text = 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 2 2\nvt 3 3\n' +
      'f 1/1 2/2 3/3\nf 1/5 3/6 4/4\n';
    const mesh = api.readObj(text);
    assert.equal(mesh.attributes.uv.itemSize, 2);
    assert.deepEqual([...mesh.attributes.uv.indices], [0, 1, 2, 4, 5, 3]);
    assert.match(api.writeObj(mesh), /\nf 1\/5 3\/6 4\/4\n/);
    const drawable = api.toDrawable(mesh);
    assert.deepEqual([...drawable.origins], [0, 0, 1, 2, 2, 3], 'vertices 1 and 3 (0 and 2) split');
    assert.deepEqual([...drawable.triangles], [0, 2, 3, 1, 4, 5]);
    assert.deepEqual([...drawable.attributes.uv.array.slice(2, 4)], [2, 2]);
    assert.equal(drawable.attributes.uv.indices, undefined);
    assert.deepEqual(api.fvarLinearModes(), ['none', 'corners-only', 'corners-plus1', 'corners-plus2', 'boundaries', 'all']);
    assert.throws(() => api.subdivide(cube(), { fvarLinear: 'linear' }), /unknown fvarLinear 'linear'/);
    assert.equal(api.shape('torus').attributes.uv.indices.length, 4 * 288);
  });

  check(`${name}: OBJ round trip`, () => {
    const refined = api.subdivide(cube(), { levels: 1 });
    const again = api.readObj(api.writeObj(refined));
    assert.deepEqual(again.indices, refined.indices);
    assert.deepEqual(again.faceSizes, refined.faceSizes);
  });
}

// ---- triangle lists (subsurf::triangles, which subsurf/three is built on)
check('weldTriangles, triangleFaces, sideNormals', () => {
  // Two triangles of a unit square stored with six vertices, and one that collapses.
  const positions = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0]);
  const original = positions.slice();
  const w = node.weldTriangles(positions, new Uint32Array([0, 1, 2, 3, 4, 5, 0, 3, 1]));
  assert.deepEqual([...w.weldOf], [0, 1, 2, 0, 2, 3]);
  assert.deepEqual([...w.kept], [0, 1]);
  assert.deepEqual([...w.corners], [0, 1, 2, 0, 2, 3]);
  assert.equal(w.positions.length, 12);
  assert.deepEqual(positions, original, 'the input is not written');
  const near = node.weldTriangles(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0, 1.0001, 0, 0]), new Uint32Array([0, 1, 2, 3, 2, 0]), 0.001);
  assert.deepEqual([...near.weldOf], [0, 1, 2, 1]);
  const faces = node.triangleFaces(
    { positions: w.positions, corners: w.corners, inputCorners: new Uint32Array([0, 1, 2, 3, 4, 5]) },
    { quads: true, sides: true },
  );
  assert.deepEqual([...faces.faceSizes], [4]);
  assert.deepEqual([...faces.indices], [2, 3, 0, 1]);
  assert.equal(faces.sides, undefined, 'no sharp edge, no sides');
  assert.throws(() => node.weldTriangles(positions, new Uint32Array([0, 1, 9])), /corner 2 \(triangle 0\) names vertex 9, but there are only 6 vertices/);
  assert.throws(() => node.weldTriangles(positions, new Uint16Array([0, 1, 2])), /weldTriangles: index must be a Uint32Array, got Uint16Array; convert it/);
  assert.throws(() => node.triangleFaces({ positions: w.positions, corners: w.corners }, {}), /triangleFaces: inputCorners must be a Uint32Array, got undefined/);
  assert.throws(() => node.triangleFaces({ positions: w.positions, corners: w.corners, inputCorners: w.corners }, { quad: true }), /unknown field 'quad' \(did you mean 'quads'\?\)/);
  const mesh = { positions: w.positions, indices: faces.indices, faceSizes: faces.faceSizes };
  assert.throws(() => node.sideNormals(mesh, new Uint32Array(4), 0, new Uint32Array(4), new Float32Array(12)), /corner 0 has side 0, but there are 0/);
  const same = node.sideNormals(mesh, new Uint32Array(4), 1, new Uint32Array([0, 1, 2, 3]), new Float32Array(12).fill(0.5));
  assert.deepEqual([...same], new Array(12).fill(0.5), 'one side everywhere: the normals stay');
});

// ---- TypeScript declarations are precise, not `any`
// Whitespace collapsed: wasm-bindgen re-indents the custom section and lines may wrap.
const dts = readFileSync(join(installed, 'subsurf.d.ts'), 'utf8').replace(/\s+/g, ' ');
check('subsurf.d.ts', () => {
  for (const line of [
    'export function subdivide(mesh: SubdivideMesh, options?: SubdivideOptions, into?: SubdivideResult): SubdivideResult;',
    'export class BaseMesh {',
    'constructor(mesh: SubdivideMesh);',
    'subdivide(options?: SubdivideOptions, into?: SubdivideResult): SubdivideResult;',
    'setPositions(positions: Float32Array): void;',
    'export function readObj(text: string): ObjMesh;',
    'export interface ObjMesh extends PolygonMesh { tags: ObjTags;',
    'attributes?: { uv: AttributeChannel };',
    'export function toDrawable(mesh: SubdivideMesh): DrawableMesh;',
    'export function fvarLinearModes(): FVarLinearMode[];',
    'export function shape(name: string): ShapeMesh;',
    'fvarLinear?: FVarLinearMode;',
    'export function writeObj(mesh: SubdivideMesh): string;',
    'export function version(): string;',
    'export interface SubdivideMesh {',
    'export interface SubdivideOptions {',
    'export interface SubdivideResult extends PolygonMesh {',
    'export function weldTriangles(positions: Float32Array, index: Uint32Array, weld?: number): WeldedTriangles;',
    'export function triangleFaces(input: TriangleFacesInput, options?: TriangleFacesOptions): TriangleFaces;',
    'export interface WeldedTriangles {',
  ]) {
    assert.ok(dts.includes(line), `subsurf.d.ts should contain: ${line}`);
  }
  // The hand-written unions must list what the library accepts.
  const union = (names) => names.map((n) => `'${n}'`).join(' | ');
  const schemes = `export type SchemeName = ${union(node.schemeNames())};`;
  const boundaries = `export type BoundaryRule = ${union(node.boundaryRules())};`;
  const modes = `export type FVarLinearMode = ${union(node.fvarLinearModes())};`;
  assert.ok(dts.includes(modes), `subsurf.d.ts should contain: ${modes}`);
  assert.ok(dts.includes(schemes), `subsurf.d.ts should contain: ${schemes}`);
  assert.ok(dts.includes(boundaries), `subsurf.d.ts should contain: ${boundaries}`);
  assert.ok(dts.includes('export function schemeNames(): SchemeName[];'));
  assert.ok(node.schemeNames().includes('catmull-clark') && node.boundaryRules()[0] === 'edge-and-corner');
  assert.ok(readFileSync(join(installed, 'node.d.ts'), 'utf8').includes("export * from './subsurf.js';"));
});

// ---- the declarations compile, as a TypeScript project would use them
// Two configurations: the library files checked too (skipLibCheck off), which needs the
// `esnext.disposable` lib because wasm-bindgen's classes declare [Symbol.dispose] (TypeScript
// 5.2 or later); and the `tsc --init` default, skipLibCheck on, with an older lib.
writeFileSync(join(scratch, 'package.json'), JSON.stringify({ type: 'module' }));
for (const file of ['types_check.ts', 'webgpu_types_plain.ts', 'webgpu_types_check.ts', 'worker_types_check.ts']) {
  cpSync(join(root, 'tests', 'js', file), join(scratch, file));
}
for (const [skipLibCheck, lib] of [[false, ['es2022', 'esnext.disposable', 'dom']], [true, ['es2022', 'dom']]]) {
  check(`tsc on tests/js/types_check.ts, skipLibCheck ${skipLibCheck}`, () => {
    const compilerOptions = {
      strict: true, noEmit: true, skipLibCheck, target: 'es2022', module: 'nodenext', moduleResolution: 'nodenext', lib, types: [],
    };
    // subsurf/webgpu without WebGPU typings (its stand-in types) and subsurf/worker go with the
    // main check.
    const files = ['types_check.ts', 'webgpu_types_plain.ts', 'worker_types_check.ts'];
    writeFileSync(join(scratch, 'tsconfig.json'), JSON.stringify({ compilerOptions, files }));
    const tsc = spawnSync(join(root, 'node_modules', '.bin', 'tsc'), ['-p', scratch], { encoding: 'utf8' });
    assert.equal(tsc.status, 0, `tsc failed:\n${tsc.stdout}${tsc.stderr}`);
  });
}

// subsurf/webgpu as a WebGPU app uses it, with @webgpu/types (a devDependency) installed: the
// evaluator's device and buffers must be the real GPUDevice and GPUBuffer.
check('tsc on tests/js/webgpu_types_check.ts with @webgpu/types', () => {
  cpSync(join(root, 'node_modules', '@webgpu', 'types'), join(scratch, 'node_modules', '@webgpu', 'types'), { recursive: true });
  const compilerOptions = {
    strict: true, noEmit: true, skipLibCheck: false, target: 'es2022', module: 'nodenext', moduleResolution: 'nodenext',
    lib: ['es2022', 'esnext.disposable', 'dom'], types: [],
  };
  writeFileSync(join(scratch, 'tsconfig.json'), JSON.stringify({ compilerOptions, files: ['webgpu_types_check.ts'] }));
  const tsc = spawnSync(join(root, 'node_modules', '.bin', 'tsc'), ['-p', scratch], { encoding: 'utf8' });
  assert.equal(tsc.status, 0, `tsc failed:\n${tsc.stdout}${tsc.stderr}`);
});

// subsurf/webgpu loads without WebGPU (tests/e2e/webgpu.mjs runs it in Chromium) and says why it
// cannot work here.
const noGpu = await webgpu.requestGpuDevice().then(() => null, (error) => error);
check('subsurf/webgpu in Node', () => {
  assert.ok(noGpu instanceof Error, 'requestGpuDevice rejects in Node');
  assert.match(noGpu.message, /WebGPU is not available.*Node\.js has no WebGPU.*evaluator\.evaluate/);
  assert.equal(typeof webgpu.createGpuEvaluator, 'function');
  assert.match(webgpu.stencilShader({ normals: true }), /@compute @workgroup_size\(64\)/);
  assert.throws(() => webgpu.createGpuEvaluator(undefined, {}, 0), /must be a GPUDevice.*requestGpuDevice/);
});

// The stencils level by level, as a user's own shader would run them: each table on the one
// before's outputs (numControlVertices says how many), in f32, gives evaluate's frame; with
// normals the last table holds the limit's masks and the tangent weights.
check('levelStencils run in turn give the frame', () => {
  const mesh = torus(24, 16, 1, 0.3, false);
  const base = new node.BaseMesh(mesh);
  const moved = mesh.positions.map((x, i) => x + 0.05 * Math.sin(i));
  const run = (table, input, width = 3) => {
    const out = new Float32Array(width * (table.offsets.length - 1));
    for (let v = 0; v < table.offsets.length - 1; v++) {
      for (let k = table.offsets[v]; k < table.offsets[v + 1]; k++) {
        for (let c = 0; c < width; c++) out[width * v + c] = Math.fround(out[width * v + c] + Math.fround(table.weights[k] * input[width * table.indices[k] + c]));
      }
    }
    return out;
  };
  for (const [limit, count] of [[false, 2], [true, 3]]) {
    const evaluator = base.evaluator({ levels: 2, limit, normals: limit });
    const tables = evaluator.levelStencils();
    assert.equal(tables.length, count, `limit ${limit}: tables`);
    assert.equal(tables[0].numControlVertices, mesh.positions.length / 3);
    let points = moved;
    tables.forEach((table, k) => {
      if (k > 0) assert.equal(table.numControlVertices, tables[k - 1].offsets.length - 1, `table ${k}'s inputs`);
      assert.equal('tangentWeights' in table, limit && k === count - 1, `table ${k}: tangent weights`);
      points = run(table, points);
    });
    const frame = evaluator.evaluate(moved);
    assert.equal(points.length, frame.positions.length);
    const worst = points.reduce((m, x, i) => Math.max(m, Math.abs(x - frame.positions[i])), 0);
    assert.ok(worst < 1e-5, `limit ${limit}: level tables' frame ${worst} from evaluate's`);
    // The refined closed cage left its composed table out; the level tables did not make it.
    assert.equal(evaluator.hasStencilTable, false, `limit ${limit}: composed table made`);
    evaluator.free();
    assert.throws(() => evaluator.levelStencils(), /levelStencils called after free\(\)/);
  }
  base.free();
});

// A limit table past maxBytes is refused before it takes the memory: the 1M-quad torus at level
// 2 once built its level's mesh after its stencils had overflowed, and reserved 16-byte entries
// against a limit counted in 8-byte ones: more than wasm's 4 GB, and the instance aborted
// ("RuntimeError: unreachable"). The error comes back and the module works on.
// Here the torus's patches give every point, so its evaluator leaves the table out and is
// built; the table is refused on first use (`stencils()`). With a vertex-varying channel the
// build itself is refused: its values at build time come from one `subdivide`, whose result (1.5
// GB with the channel) passes maxBytes first.
check('a limit table past maxBytes is refused without running out of memory', () => {
  const mesh = torus(1000, 1000, 1, 0.25, false);
  const base = new node.BaseMesh(mesh);
  const tooLarge = /stencil table of more than \d+ bytes.*maxBytes/;
  for (const normals of [false, true]) {
    const evaluator = base.evaluator({ levels: 2, limit: true, normals });
    assert.throws(() => evaluator.stencils(), tooLarge);
    assert.throws(() => evaluator.stencilBytes, tooLarge);
    evaluator.free();
  }
  base.free();
  const weight = { array: new Float32Array(mesh.positions.length / 3), itemSize: 1 };
  const channelled = new node.BaseMesh({ ...mesh, attributes: { weight } });
  assert.throws(() => channelled.evaluator({ levels: 2, limit: true, normals: true }), /output too large: .* bytes .*maxBytes/);
  channelled.free();
  assert.equal(node.subdivide(cube(), { levels: 1, limit: true, normals: true }).normals.length, 3 * 26);
});

console.log(`pkg_smoke: ok (${checks} checks; subsurf ${pkg.version}, subsurf_bg.wasm ${bytes.length} bytes)`);
