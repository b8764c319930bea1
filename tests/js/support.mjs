// Engines without WebAssembly SIMD, and without WebAssembly (js/support.js):
//   node tests/js/support.mjs          (after scripts/build-pkg.sh)
// Node and Chromium run SIMD, so an engine that does not (Safari before 16.4) is stood in for
// by a fresh Node process, or a Chromium page, whose WebAssembly is changed before the package
// loads: `validate` refuses any module with a v128, as such an engine's does, and compiling
// subsurf_bg.wasm (told by its size) fails with a CompileError about an opcode. There:
// - every entry that loads the module by itself (subsurf in Node and in the browser,
//   subsurf/init's init() in the browser, subsurf/worker in Node and in the browser) takes
//   subsurf_nosimd.wasm instead, and subdivides as this process does with SIMD: the same face
//   lists, positions, normals and UVs to 1e-6 of the size (Catmull-Clark limit with normals and
//   Loop, on the built-in shapes);
// - given subsurf_bg.wasm's bytes, initSync and init fail with a message that says what the
//   engine lacks and what to pass instead, the engine's error as its cause;
// - with both modules failing, or no WebAssembly at all, importing subsurf says so too.
// And this Node, which runs SIMD, must validate the probe (a wrong byte in it would send every
// user the slower module). Exits non-zero on the first failure.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { checks, launchChromium, serveStatic } from '../e2e/harness.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkg = join(root, 'pkg');
const { check, finish } = checks('support');

const { hasSimd, explained } = await import(pathToFileURL(join(pkg, 'support.js')).href);
check('this Node runs the SIMD probe', hasSimd() === true);
const other = new TypeError('some other failure');
check('explained passes an error through where nothing is missing', explained(other) === other);

/** What each case subdivides, the same in every engine: small enough to pass back as JSON. */
const CASES = `
const CASES = [
  ['cube', { scheme: 'catmull-clark', levels: 2, limit: true, normals: true }],
  ['icosahedron', { scheme: 'loop', levels: 2, limit: true, normals: true }],
  ['torus', { scheme: 'catmull-clark', levels: 1 }],
];
/** A result's arrays as plain lists, to pass back as JSON. */
const plain = (name, r) => ({ name, positions: [...r.positions], normals: r.normals ? [...r.normals] : null, indices: [...r.indices],
  uv: r.attributes.uv ? [...r.attributes.uv.array] : null, uvIndices: r.attributes.uv?.indices ? [...r.attributes.uv.indices] : null });
const results = (S) => CASES.map(([name, options]) => plain(name, S.subdivide(S.shape(name), options)));
/** The same through subsurf/worker's \`worker\`, with \`shape\` from a loaded subsurf. */
const workerResults = (worker, shape) => Promise.all(CASES.map(async ([name, options]) => plain(name, await worker.subdivide(shape(name), options))));
`;
const { subdivide, shape } = await import(pathToFileURL(join(pkg, 'node.js')).href);
const expected = new Function('S', `${CASES}; return results(S);`)({ subdivide, shape });

/** `got` (results()) equals this process's: indices exactly, floats to 1e-6 of the size. */
function same(got) {
  if (!Array.isArray(got) || got.length !== expected.length) return `got ${JSON.stringify(got)?.slice(0, 200)}`;
  for (const [k, want] of expected.entries()) {
    const have = got[k];
    for (const key of ['indices', 'uvIndices']) {
      if (JSON.stringify(have[key]) !== JSON.stringify(want[key])) return `${want.name}: ${key} differ`;
    }
    for (const key of ['positions', 'normals', 'uv']) {
      if ((want[key] === null) !== (have[key] === null)) return `${want.name}: ${key} missing`;
      if (want[key] === null) continue;
      if (want[key].length !== have[key].length) return `${want.name}: ${key} lengths`;
      const scale = Math.max(1, ...want[key].map(Math.abs));
      const worst = Math.max(...want[key].map((x, i) => Math.abs(x - have[key][i])));
      if (worst > 1e-6 * scale) return `${want.name}: ${key} differ by ${worst}`;
    }
  }
  return '';
}

const simdSize = statSync(join(pkg, 'subsurf_bg.wasm')).size;
const scalarSize = statSync(join(pkg, 'subsurf_nosimd.wasm')).size;
check('the two modules differ in size (how the stand-in engines tell them apart)', simdSize !== scalarSize);

/**
 * An engine without SIMD: `validate` refuses a v128 (the probe) and subsurf_bg.wasm, and
 * compiling the modules of the sizes in `failing` fails with an engine's CompileError. Node
 * compiles modules of its own, which must still load. `bytesOf` is the argument's length.
 */
const noSimd = (failing) => `
const failing = ${JSON.stringify(failing)};
const sizeOf = (x) => x?.byteLength ?? x?.length ?? -1;
const fails = (x) => failing.includes(sizeOf(x));
const fail = () => { throw new WebAssembly.CompileError('WebAssembly.Module(): invalid opcode 0xfd'); };
const { validate, Module, compile, instantiate } = WebAssembly;
WebAssembly.validate = (bytes) => validate(bytes) && !fails(bytes) && !new Uint8Array(bytes).includes(253);
WebAssembly.Module = function (bytes, ...rest) { return fails(bytes) ? fail() : new Module(bytes, ...rest); };
WebAssembly.compile = async (bytes) => (fails(bytes) ? fail() : compile(bytes));
WebAssembly.instantiate = async (bytes, ...rest) => (fails(bytes) ? fail() : instantiate(bytes, ...rest));
`;

/** Runs `body` (an async module body) after `stub` in a fresh Node; its `out`, as JSON. */
function run(stub, body) {
  const script = `const pkg = ${JSON.stringify(pathToFileURL(pkg).href)};\n${stub}\n${CASES}\n` +
    `const describe = (e) => ({ message: String(e?.message), cause: e?.cause?.constructor?.name ?? null });\n` +
    `const out = {};\n${body}\nprocess.stdout.write(JSON.stringify(out));\n`;
  // A file, not `-e`: worker_threads would inherit `--input-type`.
  const dir = mkdtempSync(join(tmpdir(), 'subsurf-support-'));
  const file = join(dir, 'engine.mjs');
  writeFileSync(file, script);
  const result = spawnSync(process.execPath, [file], { encoding: 'utf8' });
  rmSync(dir, { recursive: true, force: true });
  assert.equal(result.status, 0, `the script failed: ${result.stderr}`);
  return JSON.parse(result.stdout);
}

const SAYS_NO_SIMD = /subsurf could not load its module on this engine, which does not run WebAssembly SIMD\. Such engines need subsurf_nosimd\.wasm .* Safari 15 or later; subsurf_bg\.wasm needs Chrome 91, Edge 91, Firefox 89, Safari 16\.4, Node 16\.4 or later/;
/** Whether `failure` (a describe()d error) says SIMD is missing, the engine's CompileError its cause. */
const saysNoSimd = (failure) => SAYS_NO_SIMD.test(failure?.message) && failure.cause === 'CompileError';

const node = run(noSimd([simdSize]), `
const S = await import(pkg + '/node.js');
out.results = results(S);
`);
check('without SIMD, subsurf in Node loads subsurf_nosimd.wasm and subdivides as with SIMD', same(node.results) === '', same(node.results));

const explicit = run(noSimd([simdSize]), `
const { readFileSync } = await import('node:fs');
const init = await import(pkg + '/init.js');
const simd = readFileSync(new URL(pkg + '/subsurf_bg.wasm'));
try { init.initSync({ module: simd }); out.initSync = 'loaded'; } catch (e) { out.initSync = describe(e); }
try { await init.default({ module_or_path: simd }); out.init = 'loaded'; } catch (e) { out.init = describe(e); }
init.initSync({ module: readFileSync(new URL(pkg + '/subsurf_nosimd.wasm')) });
out.results = results(init);
`);
for (const entry of ['initSync', 'init']) {
  check(`without SIMD, ${entry} given subsurf_bg.wasm fails saying what to pass instead`, saysNoSimd(explicit[entry]), JSON.stringify(explicit[entry]));
}
check('without SIMD, initSync given subsurf_nosimd.wasm subdivides as with SIMD', same(explicit.results) === '', same(explicit.results));

const worker = run(noSimd([simdSize]), `
const { shape } = await import(pkg + '/node.js');
const { createWorker } = await import(pkg + '/worker-node.js');
const worker = createWorker();
try { out.results = await workerResults(worker, shape); } catch (e) { out.results = describe(e); }
worker.terminate();
`);
check('without SIMD, subsurf/worker in Node takes subsurf_nosimd.wasm and subdivides as with SIMD', same(worker.results) === '', same(worker.results));

const neither = run(noSimd([simdSize, scalarSize]), `
try { await import(pkg + '/node.js'); out.node = 'loaded'; } catch (e) { out.node = describe(e); }
`);
check('with neither module compiling, subsurf in Node says what the engine lacks', saysNoSimd(neither.node), JSON.stringify(neither.node));

const noWasm = run('delete globalThis.WebAssembly;', `
try { await import(pkg + '/node.js'); out.node = 'loaded'; } catch (e) { out.node = describe(e); }
`);
check('without WebAssembly, subsurf in Node says so',
  /subsurf needs WebAssembly, which this JavaScript environment does not have: use Chrome 75/.test(noWasm.node?.message), JSON.stringify(noWasm.node));

// The browser entries, in pages whose WebAssembly runs no SIMD (the streaming compilers too).
const pageNoSimd = `<!doctype html><meta charset="utf-8"><title>subsurf without SIMD</title><script type="module">
${noSimd([simdSize])}
const { compileStreaming, instantiateStreaming } = WebAssembly;
const streamed = async (response) => { const bytes = await (await response).arrayBuffer(); return { bytes, fails: fails(bytes) }; };
WebAssembly.compileStreaming = async (response) => { const s = await streamed(response); return s.fails ? fail() : compile(s.bytes); };
WebAssembly.instantiateStreaming = async (response, imports) => { const s = await streamed(response); return s.fails ? fail() : instantiate(s.bytes, imports); };
window.ready = true;
</script>`;
const server = await serveStatic({ pages: { '/': pageNoSimd }, routes: { '/pkg/': pkg } });
const browser = await launchChromium();
try {
  const inPage = async (body) => {
    const page = await browser.newPage();
    await page.goto(`${server.origin}/`);
    await page.waitForFunction(() => window.ready === true);
    return page.evaluate(`(async () => { ${CASES}
      const describe = (e) => ({ message: String(e?.message), cause: e?.cause?.constructor?.name ?? null });
      const out = {}; ${body}; return out; })()`);
  };
  const auto = await inPage(`try { out.results = results(await import('/pkg/auto.js')); } catch (e) { out.results = describe(e); }`);
  check('in Chromium without SIMD, importing subsurf loads subsurf_nosimd.wasm and subdivides as with SIMD', same(auto.results) === '', same(auto.results));
  const init = await inPage(`const S = await import('/pkg/init.js'); await S.default(); out.results = results(S);`);
  check("in Chromium without SIMD, subsurf/init's init() loads subsurf_nosimd.wasm and subdivides as with SIMD", same(init.results) === '', same(init.results));
  const onThread = await inPage(`
    const S = await import('/pkg/init.js'); await S.default();
    const { createWorker } = await import('/pkg/worker.js');
    const worker = createWorker();
    try { out.results = await workerResults(worker, S.shape); } catch (e) { out.results = describe(e); }
    worker.terminate();`);
  check('in Chromium without SIMD, subsurf/worker takes subsurf_nosimd.wasm and subdivides as with SIMD', same(onThread.results) === '', same(onThread.results));
  const unserved = await inPage(`
    const S = await import('/pkg/init.js'); await S.default();
    const { createWorker } = await import('/pkg/worker.js');
    const worker = createWorker({ wasm: '/pkg/missing.wasm' });
    try { await worker.subdivide(S.shape(CASES[0][0]), CASES[0][1]); out.error = 'resolved'; } catch (e) { out.error = describe(e); }
    worker.terminate();`);
  check('in Chromium without SIMD, a subsurf/worker .wasm that does not load names subsurf_nosimd.wasm as the file to serve',
    /missing\.wasm: HTTP 404; pass createWorker\(\{ wasm \}\) the URL where subsurf_nosimd\.wasm is served/.test(unserved.error?.message), JSON.stringify(unserved.error));
} finally {
  await browser.close();
  server.close();
}

finish();
