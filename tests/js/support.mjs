// What the package says where the engine cannot run its module (js/support.js):
//   node tests/js/support.mjs          (after scripts/build-pkg.sh)
// Node runs WebAssembly SIMD, so the engines that do not are stood in for by a fresh Node
// process whose WebAssembly is changed before the package loads: `validate` refusing the SIMD
// probe and every compilation failing with a CompileError about an opcode, as Safari 15's does;
// or no WebAssembly at all. Each entry that loads the module (subsurf in Node, subsurf/init's
// initSync and init, subsurf/worker in Node) must then fail with the message naming what is
// missing and the engines that have it, the engine's own error as its cause; so must the
// browser entries (subsurf's top-level init, subsurf/worker) in headless Chromium, whose page
// changes its WebAssembly the same way. And in this
// Node, which has SIMD, the probe must validate (a wrong byte in it would otherwise send every
// user the SIMD message). Exits non-zero on the first failure.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import { checks, launchChromium, serveStatic } from '../e2e/harness.mjs';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkg = join(root, 'pkg');
const { check, finish } = checks('support');

const { missingSupport, explained } = await import(pathToFileURL(join(pkg, 'support.js')).href);
check('this Node runs the SIMD probe: nothing is missing', missingSupport() === null, missingSupport() ?? '');
const other = new TypeError('some other failure');
check('explained passes an error through where nothing is missing', explained(other) === other);

/**
 * Engines without SIMD: `validate` says no to v128, and compiling subsurf's module (told by its
 * size: Node compiles modules of its own, which must still load) fails with an engine's error.
 */
const NO_SIMD = `
const size = (await import('node:fs')).statSync(new URL(pkg + '/subsurf_bg.wasm')).size;
const ours = (bytes) => (bytes?.byteLength ?? bytes?.length) === size;
const fail = () => { throw new WebAssembly.CompileError('WebAssembly.Module(): invalid opcode 0xfd'); };
const { validate, Module, compile, instantiate } = WebAssembly;
WebAssembly.validate = (bytes) => validate(bytes) && !ours(bytes) && !new Uint8Array(bytes).includes(253);
WebAssembly.Module = function (bytes, ...rest) { return ours(bytes) ? fail() : new Module(bytes, ...rest); };
WebAssembly.compile = async (bytes) => (ours(bytes) ? fail() : compile(bytes));
WebAssembly.instantiate = async (bytes, ...rest) => (ours(bytes) ? fail() : instantiate(bytes, ...rest));
`;
const NO_WASM = 'delete globalThis.WebAssembly;\n';

/** Runs `body` (an async module body) after `stub` in a fresh Node; its stdout as JSON. */
function run(stub, body) {
  const script = `const pkg = ${JSON.stringify(pathToFileURL(pkg).href)};\n${stub}\n` +
    `const describe = (e) => ({ message: String(e?.message), cause: e?.cause?.constructor?.name ?? null });\n` +
    `const out = {};\n${body}\nprocess.stdout.write(JSON.stringify(out));\n`;
  const result = spawnSync(process.execPath, ['--input-type=module', '-e', script], { encoding: 'utf8' });
  assert.equal(result.status, 0, `the script failed: ${result.stderr}`);
  return JSON.parse(result.stdout);
}

const SIMD_MESSAGE = /subsurf needs WebAssembly SIMD \(simd128\), which this engine does not run: use Chrome 91, Edge 91, Firefox 89, Safari 16\.4, Node 16\.4 or later/;
const noSimd = run(NO_SIMD, `
try { await import(pkg + '/node.js'); out.node = 'loaded'; } catch (e) { out.node = describe(e); }
const init = await import(pkg + '/init.js');
const bytes = (await import('node:fs')).readFileSync(new URL(pkg + '/subsurf_bg.wasm'));
try { init.initSync({ module: bytes }); out.initSync = 'loaded'; } catch (e) { out.initSync = describe(e); }
try { await init.default({ module_or_path: bytes }); out.init = 'loaded'; } catch (e) { out.init = describe(e); }
const { createWorker } = await import(pkg + '/worker-node.js');
const worker = createWorker();
try { await worker.subdivide({ positions: new Float32Array(9), indices: new Uint32Array([0, 1, 2]) }); out.worker = 'ran'; }
catch (e) { out.worker = describe(e); }
worker.terminate();
`);
/** Whether `failure` (a describe()d error) says SIMD is missing, with `cause` as its cause. */
const saysSimd = (failure, cause) => SIMD_MESSAGE.test(failure?.message) && (cause === undefined || failure.cause === cause);
for (const entry of ['node', 'initSync', 'init']) {
  check(`without SIMD, ${entry} fails saying so, the engine's CompileError as the cause`,
    saysSimd(noSimd[entry], 'CompileError'), JSON.stringify(noSimd[entry]));
}
check('without SIMD, subsurf/worker in Node rejects its call saying so', saysSimd(noSimd.worker), JSON.stringify(noSimd.worker));

const noWasm = run(NO_WASM, `
try { await import(pkg + '/node.js'); out.node = 'loaded'; } catch (e) { out.node = describe(e); }
`);
check('without WebAssembly, subsurf in Node fails saying so',
  /subsurf needs WebAssembly, which this JavaScript environment does not have/.test(noWasm.node?.message), JSON.stringify(noWasm.node));

// The browser entries, in a page whose WebAssembly cannot run SIMD: subsurf's module (the only
// one over 1 MB the page compiles) fails as Safari 15 fails it.
const PAGE_NO_SIMD = `<!doctype html><meta charset="utf-8"><title>subsurf without SIMD</title><script>
const ours = (n) => n > 1000000;
const size = (x) => x?.byteLength ?? x?.length ?? 0;
const fail = () => Promise.reject(new WebAssembly.CompileError('WebAssembly.instantiate(): invalid opcode 0xfd'));
const { validate, compile, instantiate, instantiateStreaming, compileStreaming } = WebAssembly;
WebAssembly.validate = (bytes) => validate(bytes) && !new Uint8Array(bytes).includes(253);
WebAssembly.compile = (bytes) => (ours(size(bytes)) ? fail() : compile(bytes));
WebAssembly.instantiate = (bytes, imports) => (ours(size(bytes)) ? fail() : instantiate(bytes, imports));
WebAssembly.instantiateStreaming = async (response) => fail();
WebAssembly.compileStreaming = async (response) => fail();
</script>`;
const server = await serveStatic({ pages: { '/': PAGE_NO_SIMD }, routes: { '/pkg/': pkg } });
const browser = await launchChromium();
try {
  const page = await browser.newPage();
  await page.goto(`${server.origin}/`);
  const inPage = await page.evaluate(async () => {
    const describe = (e) => ({ message: String(e?.message), cause: e?.cause?.constructor?.name ?? null });
    const out = {};
    try { await import('/pkg/auto.js'); out.auto = 'loaded'; } catch (e) { out.auto = describe(e); }
    const { createWorker } = await import('/pkg/worker.js');
    const worker = createWorker();
    try { await worker.subdivide({ positions: new Float32Array(9), indices: new Uint32Array([0, 1, 2]) }); out.worker = 'ran'; }
    catch (e) { out.worker = describe(e); }
    worker.terminate();
    return out;
  });
  check('in Chromium without SIMD, importing subsurf fails saying so, the CompileError as the cause',
    saysSimd(inPage.auto, 'CompileError'), JSON.stringify(inPage.auto));
  check('in Chromium without SIMD, subsurf/worker rejects its call saying so', saysSimd(inPage.worker), JSON.stringify(inPage.worker));
} finally {
  await browser.close();
  server.close();
}

finish();
