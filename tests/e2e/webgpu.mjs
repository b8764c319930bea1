// End-to-end test of subsurf/webgpu (js/webgpu.js) in headless Chromium with WebGPU on
// SwiftShader (no GPU needed):
//   node tests/e2e/webgpu.mjs                    (after scripts/build-pkg.sh)
//   PKG_DIR=/elsewhere/pkg node tests/e2e/webgpu.mjs
//
// Serves the built package on 127.0.0.1 (WebGPU needs a secure context) and, in the page,
// evaluates stencil tables on the GPU and compares the read-back with a plain JS sum in f32:
// a hand-written table whose answer is known (corners, edge midpoints and the centre of a
// square, with constant tangents), seeded random sparse tables with weights summing to 1 and
// tangent weights summing to 0 (positions and normals, control points as a Float32Array, as a
// caller's GPUBuffer and through a caller's command encoder), normals that must be (0, 0, 0)
// (parallel tangents, an overflowing cross product, an empty row), a table of over 4.2 M rows
// (the 2D dispatch) and a table too big to interleave its weights under the default limits
// (the three-binding shader); the wasm Evaluator (BaseMesh.evaluator({ levels: 2, limit: true,
// normals: true }) on five built-in shapes, as built and twisted): GPU vs evaluator.evaluate.
// Then the errors: bad tables, a control of the wrong length or
// type or with a NaN or a value beyond ±1e30, a destroyed evaluator, a lost device (device.destroy()), and requestGpuDevice where
// navigator.gpu is missing (deleted on a secure page, and a page that is not a secure context).
// Prints the GPU time per evaluate for 1 M output points, random and the torus at level 6 (with
// the wasm evaluator.evaluate's for comparison; never asserted). Exits non-zero on
// failure.
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { checks, launchChromium, pkg, serveStatic } from './harness.mjs';

const TOLERANCE = 1e-5;
const PAGE = '<!doctype html><meta charset="utf-8"><title>subsurf webgpu test</title><body></body>';

// ---- helpers installed in the page as window.T
function pageHelpers() {
  const f = Math.fround;
  /** A seeded generator of floats in [0, 1) (mulberry32). */
  function rng(seed) {
    let a = seed >>> 0;
    return () => {
      a = (a + 0x6d2b79f5) >>> 0;
      let t = a;
      t = Math.imul(t ^ (t >>> 15), t | 1);
      t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
      return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
  }
  /**
   * A random sparse table: rows of minLength..maxLength distinct-or-not control indices, weights
   * positive and summing to 1, tangent weights summing to 0 (as a derivative's do).
   */
  function randomTable({ seed, numVertices, numControlVertices, minLength = 0, maxLength = 24, tangents = true }) {
    const random = rng(seed);
    const offsets = new Uint32Array(numVertices + 1);
    for (let i = 0; i < numVertices; i++) {
      offsets[i + 1] = offsets[i] + minLength + Math.floor(random() * (maxLength - minLength + 1));
    }
    const nnz = offsets[numVertices];
    const indices = new Uint32Array(nnz);
    const weights = new Float32Array(nnz);
    const t1 = tangents ? new Float32Array(nnz) : null;
    const t2 = tangents ? new Float32Array(nnz) : null;
    for (let i = 0; i < numVertices; i++) {
      const start = offsets[i];
      const end = offsets[i + 1];
      let sum = 0;
      let mean1 = 0;
      let mean2 = 0;
      for (let k = start; k < end; k++) {
        indices[k] = Math.floor(random() * numControlVertices);
        weights[k] = 0.05 + random();
        sum += weights[k];
        if (tangents) {
          t1[k] = random() * 2 - 1;
          t2[k] = random() * 2 - 1;
          mean1 += t1[k] / (end - start);
          mean2 += t2[k] / (end - start);
        }
      }
      for (let k = start; k < end; k++) {
        weights[k] /= sum;
        if (tangents) {
          t1[k] -= mean1;
          t2[k] -= mean2;
        }
      }
    }
    return tangents ? { offsets, indices, weights, tangentWeights: [t1, t2] } : { offsets, indices, weights };
  }
  function randomControl(seed, count, centre = [5, -3, 2]) {
    const random = rng(seed);
    const control = new Float32Array(3 * count);
    for (let i = 0; i < control.length; i++) control[i] = centre[i % 3] + random() * 2 - 1;
    return control;
  }
  /**
   * The reference: the contract's sums, in f32, in index order; the tangents, whose weights sum
   * to 0, on differences from the row's first control point, as the contract says.
   */
  function cpuEvaluate({ offsets, indices, weights, tangentWeights }, control) {
    const n = offsets.length - 1;
    const positions = new Float32Array(3 * n);
    const normals = tangentWeights ? new Float32Array(3 * n) : undefined;
    const [w1, w2] = tangentWeights ?? [];
    for (let i = 0; i < n; i++) {
      let px = 0, py = 0, pz = 0, ax = 0, ay = 0, az = 0, bx = 0, by = 0, bz = 0;
      const first = offsets[i] < offsets[i + 1] ? 3 * indices[offsets[i]] : -1;
      const [ox, oy, oz] = first < 0 ? [0, 0, 0] : [control[first], control[first + 1], control[first + 2]];
      for (let k = offsets[i]; k < offsets[i + 1]; k++) {
        const c = 3 * indices[k];
        const x = control[c], y = control[c + 1], z = control[c + 2];
        const w = weights[k];
        px = f(px + f(w * x)); py = f(py + f(w * y)); pz = f(pz + f(w * z));
        if (normals) {
          const dx = f(x - ox), dy = f(y - oy), dz = f(z - oz);
          ax = f(ax + f(w1[k] * dx)); ay = f(ay + f(w1[k] * dy)); az = f(az + f(w1[k] * dz));
          bx = f(bx + f(w2[k] * dx)); by = f(by + f(w2[k] * dy)); bz = f(bz + f(w2[k] * dz));
        }
      }
      positions[3 * i] = px; positions[3 * i + 1] = py; positions[3 * i + 2] = pz;
      if (normals) {
        const nx = f(f(ay * bz) - f(az * by)), ny = f(f(az * bx) - f(ax * bz)), nz = f(f(ax * by) - f(ay * bx));
        const length = f(Math.sqrt(f(f(f(nx * nx) + f(ny * ny)) + f(nz * nz))));
        if (length > 0 && Number.isFinite(length)) {
          normals[3 * i] = f(nx / length); normals[3 * i + 1] = f(ny / length); normals[3 * i + 2] = f(nz / length);
        }
      }
    }
    return { positions, normals };
  }
  /**
   * The largest difference between two arrays relative to the largest |expected| value (the
   * data's scale; for unit normals that is 1); also where the worst one is, and whether every
   * expected (0, 0, 0) normal is zero in the result too.
   */
  function compare(actual, expected) {
    if (!actual || actual.length !== expected.length) {
      return { error: Infinity, detail: `length ${actual?.length} instead of ${expected.length}` };
    }
    let scale = 0;
    for (const v of expected) scale = Math.max(scale, Math.abs(v));
    let worst = 0;
    let at = -1;
    for (let i = 0; i < expected.length; i++) {
      const d = Math.abs(actual[i] - expected[i]);
      if (!(d <= worst)) { worst = d; at = i; }
    }
    const error = worst / (scale || 1);
    return { error, detail: at < 0 ? 'identical' : `worst at [${at}]: ${actual[at]} vs ${expected[at]}` };
  }
  /** Runs fn (sync or async) and returns the message of the Error it throws, or null. */
  async function message(fn) {
    try {
      await fn();
      return null;
    } catch (error) {
      return error instanceof Error ? error.message : `not an Error: ${String(error)}`;
    }
  }
  window.T = { rng, randomTable, randomControl, cpuEvaluate, compare, message };
}

const figures = [];
const { check, finish } = checks('e2e webgpu');
const pass = (name, detail) => check(name, true, detail);
const fail = (name, detail) => check(name, false, detail);
/** Checks a { error, detail } from T.compare against the tolerance. */
function within(name, result, tolerance = TOLERANCE) {
  if (result.error <= tolerance) pass(name, `max error ${result.error.toExponential(2)}`);
  else fail(name, `error ${result.error} > ${tolerance}; ${result.detail}`);
}
/** Checks an error message: thrown, and containing every fragment. */
function says(name, text, ...fragments) {
  if (text === null) return fail(name, 'nothing was thrown');
  const missing = fragments.filter((fragment) => !text.includes(fragment));
  if (missing.length) fail(name, `message "${text}" lacks ${missing.map((m) => JSON.stringify(m)).join(', ')}`);
  else pass(name, `"${text.length > 150 ? `${text.slice(0, 147)}...` : text}"`);
}

async function run() {
  if (!existsSync(join(pkg, 'webgpu.js'))) throw new Error(`${pkg}/webgpu.js is missing; run scripts/build-pkg.sh`);
  // / is an empty page, /pkg/... the built package.
  const server = await serveStatic({ pages: { '/': PAGE }, routes: { '/pkg/': pkg } });
  const browser = await launchChromium({ args: ['--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan'] });
  const pageErrors = [];
  try {
    const context = await browser.newContext();
    // http://insecure.test/ is served by the same handler but is not a secure context.
    await context.route('http://insecure.test/**', (route) => {
      const { status, type, body } = server.respond(new URL(route.request().url()).pathname);
      return route.fulfill({ status, contentType: type, body });
    });
    const page = await context.newPage();
    page.on('pageerror', (error) => pageErrors.push(error.message));
    await page.goto(`${server.origin}/`);
    await page.addScriptTag({ content: `(${pageHelpers})();` });
    const adapter = await page.evaluate(async () => {
      window.W = await import('/pkg/webgpu.js');
      window.device = await W.requestGpuDevice();
      const adapter = await navigator.gpu.requestAdapter();
      return { architecture: adapter.info.architecture, maxStorageBufferBindingSize: device.limits.maxStorageBufferBindingSize };
    });
    console.log(`  adapter: ${adapter.architecture}; requestGpuDevice gave maxStorageBufferBindingSize ${adapter.maxStorageBufferBindingSize}`);

    // ---- a table whose answer is known: a square's corners, edge midpoints and centre
    const known = await page.evaluate(async () => {
      const control = new Float32Array([0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0]);
      const rows = [[[0, 1]], [[1, 1]], [[2, 1]], [[3, 1]], [[0, 0.5], [1, 0.5]], [[1, 0.5], [2, 0.5]], [[2, 0.5], [3, 0.5]],
        [[3, 0.5], [0, 0.5]], [[0, 0.25], [1, 0.25], [2, 0.25], [3, 0.25]]];
      const offsets = new Uint32Array(rows.length + 1);
      rows.forEach((row, i) => { offsets[i + 1] = offsets[i] + row.length; });
      const indices = new Uint32Array(rows.flat().map(([index]) => index));
      const weights = new Float32Array(rows.flat().map(([, weight]) => weight));
      const plain = W.createGpuEvaluator(device, { offsets, indices, weights }, 4);
      plain.evaluate(control);
      const first = await plain.readBack();
      // The same points with the bilinear tangents d/du = (v1 - v0 + v2 - v3) / 2 and
      // d/dv = (v3 - v0 + v2 - v1) / 2 on every control point of each row: normal (0, 0, 1).
      const n = rows.length;
      const dense = { offsets: new Uint32Array(n + 1).map((_, i) => 4 * i), indices: new Uint32Array(4 * n), weights: new Float32Array(4 * n),
        tangentWeights: [new Float32Array(4 * n), new Float32Array(4 * n)] };
      rows.forEach((row, i) => {
        for (let c = 0; c < 4; c++) {
          dense.indices[4 * i + c] = c;
          dense.weights[4 * i + c] = row.find(([index]) => index === c)?.[1] ?? 0;
          dense.tangentWeights[0][4 * i + c] = [-0.5, 0.5, 0.5, -0.5][c];
          dense.tangentWeights[1][4 * i + c] = [-0.5, -0.5, 0.5, 0.5][c];
        }
      });
      const withNormals = W.createGpuEvaluator(device, dense, 4);
      withNormals.evaluate(control);
      const second = await withNormals.readBack();
      const usage = withNormals.positions.usage;
      const result = {
        positions: [...first.positions], hasNormals: plain.hasNormals, normalsBuffer: plain.normals === undefined,
        densePositions: [...second.positions], normals: [...second.normals],
        usage: usage === (GPUBufferUsage.VERTEX | GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC),
        sizes: [withNormals.positions.size, withNormals.normals.size, withNormals.numVertices, withNormals.numControlVertices],
      };
      plain.destroy();
      withNormals.destroy();
      return result;
    });
    const expected = [0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 0, 0, 2, 1, 0, 1, 2, 0, 0, 1, 0, 1, 1, 0];
    const exact = (name, actual, wanted) => {
      if (JSON.stringify(actual) === JSON.stringify(wanted)) pass(name);
      else fail(name, `got ${JSON.stringify(actual)}, expected ${JSON.stringify(wanted)}`);
    };
    exact('known table: corners, edge midpoints and centre of a square, exactly', known.positions, expected);
    exact('known table without tangent weights: hasNormals false, no normals buffer', [known.hasNormals, known.normalsBuffer], [false, true]);
    exact('known table with tangents: the same positions', known.densePositions, expected);
    exact('known table with tangents: every normal (0, 0, 1)', known.normals, Array.from({ length: 27 }, (_, i) => (i % 3 === 2 ? 1 : 0)));
    exact('output buffers: usage VERTEX | STORAGE | COPY_SRC, 12 bytes per vertex', [known.usage, ...known.sizes], [true, 108, 108, 9, 4]);

    // ---- normals that must be (0, 0, 0): parallel tangents, a cross product overflowing f32
    // (1e30 x 1e30), an empty row; and tangents of 1e5 whose normal is (0, 0, 1). Tangent
    // weights sum to 0, as the contract asks.
    const zero = await page.evaluate(async () => {
      const table = {
        offsets: new Uint32Array([0, 2, 5, 8, 8]),
        indices: new Uint32Array([2, 3, 2, 0, 1, 2, 0, 1]),
        weights: new Float32Array([0.5, 0.5, 0, 0.5, 0.5, 0, 0.5, 0.5]),
        tangentWeights: [
          new Float32Array([-1, 1, -1, 1, 0, -1e-25, 1e-25, 0]),
          new Float32Array([-2, 2, -1, 0, 1, -1e-25, 0, 1e-25]),
        ],
      };
      const control = new Float32Array([1e30, 0, 0, 0, 1e30, 0, 0, 0, 0, 1, 2, 3]);
      const gpu = W.createGpuEvaluator(device, table, 4);
      gpu.evaluate(control);
      const result = await gpu.readBack();
      gpu.destroy();
      return { normals: [...result.normals], reference: [...T.cpuEvaluate(table, control).normals] };
    });
    exact('zero normals: parallel tangents, overflow, empty row (and the reference agrees)',
      [zero.normals, zero.reference], [[0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0], [0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0]]);

    // ---- seeded random tables against the JS reference
    const random = await page.evaluate(async () => {
      const out = {};
      const numControlVertices = 400;
      const table = T.randomTable({ seed: 1, numVertices: 5000, numControlVertices });
      const control = T.randomControl(2, numControlVertices);
      const reference = T.cpuEvaluate(table, control);
      const gpu = W.createGpuEvaluator(device, table, numControlVertices);
      out.nnz = table.indices.length;
      gpu.evaluate(control);
      let result = await gpu.readBack();
      out.arrayPositions = T.compare(result.positions, reference.positions);
      out.arrayNormals = T.compare(result.normals, reference.normals);
      // A caller's storage buffer as control.
      const control2 = T.randomControl(3, numControlVertices, [-20, 40, 7]);
      const reference2 = T.cpuEvaluate(table, control2);
      const buffer = device.createBuffer({ size: control2.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
      device.queue.writeBuffer(buffer, 0, control2);
      gpu.evaluate(buffer);
      result = await gpu.readBack();
      out.bufferPositions = T.compare(result.positions, reference2.positions);
      out.bufferNormals = T.compare(result.normals, reference2.normals);
      // A caller's command encoder, submitted by the caller.
      const encoder = device.createCommandEncoder();
      gpu.evaluate(control, encoder);
      device.queue.submit([encoder.finish()]);
      result = await gpu.readBack();
      out.encoderPositions = T.compare(result.positions, reference.positions);
      // Positions only.
      const { tangentWeights, ...plainTable } = table;
      const plain = W.createGpuEvaluator(device, plainTable, numControlVertices);
      plain.evaluate(control);
      result = await plain.readBack();
      out.plainPositions = T.compare(result.positions, reference.positions);
      out.plainHasNormals = plain.hasNormals || 'normals' in result;
      // An object shaped like the wasm Evaluator.
      const evaluatorLike = { numControlVertices, hasNormals: true, numVertices: 5000, stencils: () => table };
      const fromEvaluator = W.createGpuEvaluator(device, evaluatorLike);
      fromEvaluator.evaluate(control);
      result = await fromEvaluator.readBack();
      out.evaluatorLike = T.compare(result.normals, reference.normals);
      // Arrays carrying numControlVertices, as Evaluator.stencils() returns them.
      const fromArrays = W.createGpuEvaluator(device, { ...table, numControlVertices });
      fromArrays.evaluate(control);
      result = await fromArrays.readBack();
      out.arraysWithCount = T.compare(result.positions, reference.positions);
      for (const e of [gpu, plain, fromEvaluator, fromArrays]) e.destroy();
      buffer.destroy();
      return out;
    });
    console.log(`  random table: 5000 rows of 0..24 entries (${random.nnz} weights), 400 control points`);
    within('random table, Float32Array control: positions', random.arrayPositions);
    within('random table, Float32Array control: normals', random.arrayNormals);
    within('random table, GPUBuffer control: positions', random.bufferPositions);
    within('random table, GPUBuffer control: normals', random.bufferNormals);
    within('random table, caller\'s command encoder: positions', random.encoderPositions);
    within('random table without tangents: positions', random.plainPositions);
    exact('random table without tangents: no normals', random.plainHasNormals, false);
    within('an Evaluator-shaped source (stencils(), numControlVertices): normals', random.evaluatorLike);
    within('stencil arrays carrying numControlVertices: positions', random.arraysWithCount);

    // ---- over 65535 * 64 rows: the 2D dispatch
    const tall = await page.evaluate(async () => {
      const numVertices = 65535 * 64 + 1000;
      const numControlVertices = 1000;
      const table = { offsets: new Uint32Array(numVertices + 1).map((_, i) => i), indices: new Uint32Array(numVertices),
        weights: new Float32Array(numVertices) };
      for (let i = 0; i < numVertices; i++) {
        table.indices[i] = (i * 7919) % numControlVertices;
        table.weights[i] = 1 + (i % 5) * 0.25;
      }
      const control = T.randomControl(4, numControlVertices);
      const gpu = W.createGpuEvaluator(device, table, numControlVertices);
      gpu.evaluate(control);
      const result = await gpu.readBack();
      gpu.destroy();
      return { numVertices, dispatch: gpu._stages.at(-1).groups, positions: T.compare(result.positions, T.cpuEvaluate(table, control).positions) };
    });
    within(`${tall.numVertices} rows, dispatched as ${tall.dispatch.join(' x ')} workgroups: positions`, tall.positions);

    // ---- 1 M output points: the default-limit device (weights in three bindings) and the raised
    // one (interleaved), checked against the reference, and timed
    const big = await page.evaluate(async () => {
      const numVertices = 1 << 20;
      const numControlVertices = 50_000;
      const table = T.randomTable({ seed: 5, numVertices, numControlVertices, minLength: 16, maxLength: 16 });
      const control = T.randomControl(6, numControlVertices);
      let started = performance.now();
      const reference = T.cpuEvaluate(table, control);
      const cpuMs = performance.now() - started;
      const adapter = await navigator.gpu.requestAdapter();
      const defaultDevice = await adapter.requestDevice();
      const out = { nnz: table.indices.length, cpuMs, runs: [] };
      const { tangentWeights, ...plainTable } = table;
      for (const [name, dev, source] of [['normals, interleaved weights', device, table], ['normals, three weight bindings (default limits)', defaultDevice, table],
        ['positions only', device, plainTable]]) {
        started = performance.now();
        const gpu = W.createGpuEvaluator(dev, source, numControlVertices);
        const uploadMs = performance.now() - started;
        gpu.evaluate(control);
        await dev.queue.onSubmittedWorkDone();
        let count = 0;
        started = performance.now();
        while (count < 3 || performance.now() - started < 1000) {
          gpu.evaluate(control);
          await dev.queue.onSubmittedWorkDone();
          count++;
        }
        const ms = (performance.now() - started) / count;
        const result = await gpu.readBack();
        out.runs.push({
          name, merged: gpu._stages.at(-1).merged, uploadMs, ms, count,
          positions: T.compare(result.positions, reference.positions),
          normals: source.tangentWeights ? T.compare(result.normals, reference.normals) : null,
        });
        gpu.destroy();
      }
      defaultDevice.destroy();
      return out;
    });
    for (const runResult of big.runs) {
      within(`1 M points, ${runResult.name}: positions`, runResult.positions);
      if (runResult.normals) within(`1 M points, ${runResult.name}: normals`, runResult.normals);
      figures.push(`${runResult.name}: ${runResult.ms.toFixed(1)} ms per evaluate (${runResult.count} runs, upload included; ` +
        `table upload ${runResult.uploadMs.toFixed(0)} ms)`);
    }
    exact('the default-limit device splits the weights, the raised one interleaves them',
      big.runs.map((r) => r.merged), [true, false, false]);
    figures.unshift(`GPU evaluate, 1,048,576 points x 16 weights (${(big.nnz / 1e6).toFixed(1)} M), SwiftShader:`);
    figures.push(`plain JS reference (f32 sums with normals, one thread): ${big.cpuMs.toFixed(0)} ms`);

    // ---- the wasm Evaluator's real tables: BaseMesh(...).evaluator({ levels: 2, limit: true, normals: true })
    const real = await page.evaluate(async () => {
      const S = await import('/pkg/subsurf.js');
      await S.default();
      if (typeof S.BaseMesh.prototype.evaluator !== 'function') return null;
      const out = [];
      // The limit with normals, and refined points (closed cages: tables written from the
      // levels' steps); each through the Evaluator (its tables level by level without normals,
      // its composed table with them), the list of levelStencils() and the composed table.
      const cases = [['cube', 'catmull-clark', true], ['torus', 'catmull-clark', true], ['sheet-with-holes', 'catmull-clark', true],
        ['icosahedron', 'loop', true], ['house', 'catmull-clark', true], ['torus', 'catmull-clark', false], ['icosahedron', 'loop', false],
        ['sheet-with-holes', 'catmull-clark', false]];
      for (const [name, scheme, limit] of cases) for (const tables of ['evaluator', 'levels', 'composed']) {
        const { positions, indices, faceSizes } = S.shape(name);
        const mesh = { positions, indices, faceSizes };
        // (Positions only: with the shapes' UVs every evaluator makes its table.)
        const base = new S.BaseMesh(mesh);
        const evaluator = base.evaluator({ scheme, levels: 2, limit, normals: limit });
        const levels = evaluator.levelStencils().length;
        // (Made only now: the Evaluator's composed table is left out on closed cages.)
        const tableLeftOut = !evaluator.hasStencilTable;
        const source = tables === 'evaluator' ? evaluator : tables === 'levels' ? evaluator.levelStencils() : evaluator.stencils();
        const gpu = W.createGpuEvaluator(device, source);
        const random = T.rng(9);
        // The shape as built, then twisted about z and jittered.
        const moved = mesh.positions.slice();
        for (let i = 0; i < moved.length; i += 3) {
          const [x, y, z] = [moved[i], moved[i + 1], moved[i + 2]];
          const angle = 0.4 * z;
          moved[i] = Math.cos(angle) * x - Math.sin(angle) * y + 0.05 * (random() - 0.5);
          moved[i + 1] = Math.sin(angle) * x + Math.cos(angle) * y + 0.05 * (random() - 0.5);
          moved[i + 2] = z + 0.05 * (random() - 0.5);
        }
        for (const [pose, control] of [['as built', mesh.positions], ['twisted', moved]]) {
          const cpu = evaluator.evaluate(control);
          gpu.evaluate(control);
          const back = await gpu.readBack();
          out.push({ name, scheme, pose, limit, tables, tableLeftOut, passes: gpu._stages.length, levels, numVertices: gpu.numVertices,
            entries: evaluator.stencils().indices.length, positions: T.compare(back.positions, cpu.positions),
            normals: limit ? T.compare(back.normals, cpu.normals) : !('normals' in back) });
        }
        gpu.destroy();
        evaluator.free();
        base.free();
      }
      return out;
    });
    if (real === null) fail('the wasm Evaluator', 'the built package has no BaseMesh.evaluator');
    for (const r of real ?? []) {
      const what = `evaluator ${r.name} (${r.scheme}, levels 2, ${r.limit ? 'limit' : 'refined'}, ${r.numVertices} points, ${r.entries} weights, ` +
        `${r.tables}: ${r.passes} pass(es)), ${r.pose}`;
      within(`${what}: positions`, r.positions);
      if (r.limit) within(`${what}: normals`, r.normals);
      else exact(`${what}: no normals`, r.normals, true);
      // Level by level: a pass per level, and one more for the limit's masks.
      // An Evaluator goes level by level without normals where it left its table out (the
      // closed cages), else through its composed table.
      const levelByLevel = r.tables === 'levels' || (r.tables === 'evaluator' && !r.limit && r.tableLeftOut);
      exact(`${what}: passes`, r.passes, levelByLevel ? r.levels : 1);
      if (!r.limit && r.tables === 'evaluator') exact(`${what}: composed table left out`, r.tableLeftOut, r.name !== 'sheet-with-holes');
      exact(`${what}: tables`, r.levels, r.limit ? 3 : 2);
    }

    // ---- a real table of 1.2 M points (the torus at level 6, limit, normals): GPU vs wasm, timed
    const torus = await page.evaluate(async () => {
      const S = await import('/pkg/subsurf.js');
      const mesh = S.shape('torus');
      const base = new S.BaseMesh(mesh);
      let started = performance.now();
      const evaluator = base.evaluator({ levels: 6, limit: true, normals: true });
      const buildMs = performance.now() - started;
      started = performance.now();
      const gpu = W.createGpuEvaluator(device, evaluator);
      const uploadMs = performance.now() - started;
      const timed = async (step) => {
        await step();
        let count = 0;
        const start = performance.now();
        while (count < 3 || performance.now() - start < 1000) {
          await step();
          count++;
        }
        return { ms: (performance.now() - start) / count, count };
      };
      let frame;
      const cpu = await timed(() => { frame = evaluator.evaluate(mesh.positions, frame); });
      const gpuTime = await timed(async () => { gpu.evaluate(mesh.positions); await device.queue.onSubmittedWorkDone(); });
      const back = await gpu.readBack();
      const out = {
        numVertices: gpu.numVertices, entries: evaluator.stencils().indices.length, buildMs, uploadMs, cpu, gpu: gpuTime,
        positions: T.compare(back.positions, frame.positions), normals: T.compare(back.normals, frame.normals),
      };
      gpu.destroy();
      evaluator.free();
      base.free();
      return out;
    });
    within(`evaluator torus, levels 6 (${torus.numVertices} points, ${torus.entries} weights): positions`, torus.positions);
    within(`evaluator torus, levels 6: normals`, torus.normals);
    figures.push(`torus, levels 6, limit, normals (${torus.numVertices.toLocaleString('en-US')} points x ` +
      `${(torus.entries / torus.numVertices).toFixed(1)} weights): GPU ${torus.gpu.ms.toFixed(1)} ms per evaluate ` +
      `(${torus.gpu.count} runs), wasm evaluator.evaluate ${torus.cpu.ms.toFixed(1)} ms (${torus.cpu.count} runs); ` +
      `evaluator build ${torus.buildMs.toFixed(0)} ms, GPU table upload ${torus.uploadMs.toFixed(0)} ms`);

    // ---- errors
    const errors = await page.evaluate(async () => {
      const m = T.message;
      const table = T.randomTable({ seed: 7, numVertices: 100, numControlVertices: 10 });
      const gpu = W.createGpuEvaluator(device, table, 10);
      const noStorage = device.createBuffer({ size: 120, usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST });
      const small = device.createBuffer({ size: 64, usage: GPUBufferUsage.STORAGE });
      const out = {
        shortControl: await m(() => gpu.evaluate(new Float32Array(29))),
        float64: await m(() => gpu.evaluate(new Float64Array(30))),
        array: await m(() => gpu.evaluate(Array(30).fill(0))),
        missing: await m(() => gpu.evaluate()),
        nan: await m(() => gpu.evaluate(new Float32Array(30).fill(NaN, 7, 8))),
        huge: await m(() => gpu.evaluate(new Float32Array(30).fill(-1e35, 29))),
        noStorage: await m(() => gpu.evaluate(noStorage)),
        smallBuffer: await m(() => gpu.evaluate(small)),
        notDevice: await m(() => W.createGpuEvaluator({}, table, 10)),
        noCount: await m(() => W.createGpuEvaluator(device, table)),
        indexRange: await m(() => W.createGpuEvaluator(device, table, 5)),
        weightsLength: await m(() => W.createGpuEvaluator(device, { ...table, weights: table.weights.subarray(1) }, 10)),
        offsetsEnd: await m(() => W.createGpuEvaluator(device, { ...table, offsets: table.offsets.subarray(0, 50) }, 10)),
        wrongType: await m(() => W.createGpuEvaluator(device, { ...table, indices: Array.from(table.indices) }, 10)),
        tangentsLength: await m(() => W.createGpuEvaluator(device, { ...table, tangentWeights: [table.weights, new Float32Array(3)] }, 10)),
        // Positions' weights (summing to 1) given as a tangent's.
        tangentsSum: await m(() => W.createGpuEvaluator(device, { ...table, tangentWeights: [table.weights, table.weights] }, 10)),
        // Lists of tables run in turn: the second reads the first's 100 outputs.
        emptyList: await m(() => W.createGpuEvaluator(device, [], 10)),
        listInputs: await m(() => W.createGpuEvaluator(device, [T.randomTable({ seed: 9, numVertices: 5, numControlVertices: 10 }), table]
          .map(({ offsets, indices, weights }) => ({ offsets, indices, weights })), 10)),
        listTangents: await m(() => W.createGpuEvaluator(device,
          [{ ...table, tangentWeights: [new Float32Array(table.weights.length), new Float32Array(table.weights.length)] },
            T.randomTable({ seed: 8, numVertices: 20, numControlVertices: 100 })], 10)),
      };
      gpu.destroy();
      out.destroyed = await m(() => gpu.evaluate(new Float32Array(30)));
      out.destroyedReadBack = await m(() => gpu.readBack());
      noStorage.destroy();
      small.destroy();
      // A lost device: destroy it, then evaluate.
      const lostDevice = await W.requestGpuDevice();
      const onLost = W.createGpuEvaluator(lostDevice, table, 10);
      onLost.evaluate(T.randomControl(8, 10));
      await onLost.readBack();
      lostDevice.destroy();
      // Before device.lost settles, evaluate cannot know (WebGPU ignores the work); readBack
      // waits for the map to fail, by which time it does.
      out.lostAtOnce = await m(() => onLost.evaluate(T.randomControl(8, 10)));
      out.lostAtOnceReadBack = await m(() => onLost.readBack());
      await lostDevice.lost;
      out.lost = await m(() => onLost.evaluate(T.randomControl(8, 10)));
      out.lostReadBack = await m(() => onLost.readBack());
      // A device too small for a table: 128 MiB bindings against 12 M indices (48 MB) fit, but
      // not 34 M (136 MB).
      const adapter = await navigator.gpu.requestAdapter();
      const defaultDevice = await adapter.requestDevice();
      const huge = { offsets: new Uint32Array([0, 34_000_000]), indices: new Uint32Array(34_000_000), weights: new Float32Array(34_000_000) };
      out.tooBig = await m(() => W.createGpuEvaluator(defaultDevice, huge, 1));
      defaultDevice.destroy();
      // navigator.gpu missing (an older browser): hide it on this secure page.
      const descriptor = Object.getOwnPropertyDescriptor(Navigator.prototype, 'gpu');
      Object.defineProperty(Navigator.prototype, 'gpu', { configurable: true, get: () => undefined });
      out.noGpu = await m(() => W.requestGpuDevice());
      Object.defineProperty(Navigator.prototype, 'gpu', descriptor);
      return out;
    });
    says('control of the wrong length', errors.shortControl, '29 floats', 'needs 30', '10 base-mesh vertices');
    says('control of the wrong type (Float64Array)', errors.float64, 'Float32Array', 'got a Float64Array', 'new Float32Array');
    says('control of the wrong type (Array)', errors.array, 'Float32Array', 'got an Array');
    says('no control', errors.missing, 'must be a Float32Array', 'got undefined');
    says('a NaN in the control', errors.nan, 'control[7] (vertex 2, y) is NaN', 'finite');
    says('a control value beyond ±1e30', errors.huge, 'control[29] (vertex 9, z)', 'within ±1e30');
    says('control GPUBuffer without STORAGE usage', errors.noStorage, 'GPUBufferUsage.STORAGE');
    says('control GPUBuffer too small', errors.smallBuffer, '64 bytes', 'needs 120');
    says('not a device', errors.notDevice, 'must be a GPUDevice', 'requestGpuDevice');
    says('table without numControlVertices', errors.noCount, 'numControlVertices');
    says('index out of range', errors.indexRange, 'only 5 control vertices');
    says('weights not parallel to indices', errors.weightsLength, 'must be parallel');
    says('offsets not ending at indices.length', errors.offsetsEnd, 'end at indices.length');
    says('indices not a Uint32Array', errors.wrongType, 'stencils.indices must be a Uint32Array');
    says('tangent weights not parallel', errors.tangentsLength, 'tangentWeights[1]', 'must be parallel');
    says('tangent weights not summing to 0', errors.tangentsSum, 'tangentWeights[0]', 'in row', 'must sum to 0');
    says('an empty list of tables', errors.emptyList, 'list of stencil tables is empty', 'levelStencils()');
    says('a list whose second table reads past the first\'s outputs', errors.listInputs, 'table 1 of 2', 'only 5 control vertices');
    says('a list with tangent weights before its last table', errors.listTangents, 'table 0 of 2 has tangentWeights', 'only the last');
    says('destroyed evaluator: evaluate', errors.destroyed, 'destroyed', 'createGpuEvaluator');
    says('destroyed evaluator: readBack', errors.destroyedReadBack, 'destroyed');
    says('lost device: evaluate', errors.lost, 'device was lost', 'destroyed', 'requestGpuDevice()', 'evaluator.evaluate');
    says('lost device: readBack', errors.lostReadBack, 'device was lost');
    exact('lost device: evaluate right after device.destroy() does not throw', errors.lostAtOnce, null);
    says('lost device: readBack right after device.destroy()', errors.lostAtOnceReadBack, 'device was lost', 'requestGpuDevice()');
    says('table over maxStorageBufferBindingSize', errors.tooBig, 'indices need 136000000 bytes', 'maxStorageBufferBindingSize 134217728', 'requestGpuDevice()');
    says('requestGpuDevice without navigator.gpu', errors.noGpu, 'WebGPU is not available in this browser', 'navigator.gpu is missing',
      'secure context', 'evaluator.evaluate');

    // ---- a page that is not a secure context has no navigator.gpu
    const insecure = await context.newPage();
    insecure.on('pageerror', (error) => pageErrors.push(error.message));
    await insecure.goto('http://insecure.test/');
    const insecureResult = await insecure.evaluate(async () => {
      const W = await import('/pkg/webgpu.js');
      try {
        await W.requestGpuDevice();
        return { secure: window.isSecureContext, message: null };
      } catch (error) {
        return { secure: window.isSecureContext, message: error.message };
      }
    });
    if (insecureResult.secure) fail('not a secure context', 'http://insecure.test/ is a secure context here');
    says('requestGpuDevice on a page that is not a secure context', insecureResult.message, 'WebGPU is not available',
      'not a secure context', 'http://insecure.test', 'evaluator.evaluate');
  } finally {
    await browser.close();
    server.close();
  }
  for (const error of pageErrors) fail('page error', error);
  for (const line of figures) console.log(`  ${line}`);
}

try {
  await run();
} catch (error) {
  fail('run', error.stack ?? error);
}
finish();
