// End-to-end test of subsurf/worker in headless Chromium:
//   node tests/e2e/worker.mjs                    (after scripts/build-pkg.sh)
//   PKG_DIR=/elsewhere/pkg node tests/e2e/worker.mjs
//   node tests/e2e/worker.mjs --no-torus         (leaves out the 1M-quad timing)
//
// Serves the built package (/pkg/), bench/torus.mjs (/bench/) and a test worker script of its
// own (/test-worker.js: subsurf's functions plus two that let the page see the thread's side of
// a transfer), and in the page checks that
//   - worker.subdivide gives the main thread's subdivide result byte for byte (every array,
//     attributes and normals included) for several meshes and schemes;
//   - the result's buffers are transferred: the page's arrays are whole and the thread's copies
//     detached; the input arrays are copied (whole and unchanged afterwards) unless
//     `transfer: true`, which detaches them;
//   - progress arrives after each level, 1..levels, with subdivide's counts;
//   - an abort (running call) rejects with an AbortError, stops the progress, and the next call
//     succeeds on a fresh thread; an aborted waiting call is dropped while the running one
//     finishes; an already aborted signal rejects at once;
//   - a bad input rejects with subsurf's own message (the main thread's, word for word) and the
//     next call succeeds; an unknown function is named;
//   - terminate() rejects what is pending and later calls; arguments not in an array, a worker
//     script or .wasm that does not load reject with errors that say so.
// Then prints the figures: the 1M-quad torus at level 1 on the main thread and through the
// worker (copied and transferred input), and the thread's own time, whose difference is the
// cost of getting the input there and the result back. Exits non-zero on failure.
import { join } from 'node:path';
import { checks, collectErrors, launchChromium, pkg, root, serveStatic } from './harness.mjs';

const torusTiming = !process.argv.includes('--no-torus');
const PAGE = '<!doctype html><meta charset="utf-8"><title>subsurf/worker test</title><body></body>';
// A worker script of a user's: subsurf's functions, plus `keep` (subdivide, keeping the result's
// arrays to look at after they went back) and `kept` (their byteLengths now), and `timed`
// (subdivide's time inside the thread).
const TEST_WORKER = `import { expose, functions } from '/pkg/worker-thread.js';
let kept = [];
expose({
  ...functions,
  keep(args, context) {
    const result = functions.subdivide(args, context);
    kept = [result.positions, result.indices, result.faceSizes, result.triangles];
    return result;
  },
  kept: () => kept.map((array) => array.byteLength),
  timed(args, context) {
    const start = performance.now();
    functions.subdivide(args, context);
    return performance.now() - start;
  },
  async later([value]) {
    await new Promise((resolve) => setTimeout(resolve, 10));
    return value;
  },
});
`;

const { check, finish } = checks('worker e2e');
const server = await serveStatic({
  pages: { '/': PAGE, '/test-worker.js': TEST_WORKER },
  routes: { '/pkg/': pkg, '/bench/': join(root, 'bench') },
});
const browser = await launchChromium();
try {
  const page = await browser.newPage();
  // The missing script and .wasm are requested on purpose; their 404s are no page errors.
  const errors = collectErrors(page, { except: /404 \(Not Found\)/ });
  await page.goto(`${server.origin}/`);
  const results = await page.evaluate(async (torusTiming) => {
    const subsurf = await import('/pkg/subsurf.js');
    await subsurf.default();
    const { createWorker } = await import('/pkg/worker.js');
    const out = {};

    /** Every typed array under a result, by path, as bytes. */
    const arrays = (value, path = '', found = {}) => {
      if (ArrayBuffer.isView(value)) found[path] = new Uint8Array(value.buffer, value.byteOffset, value.byteLength);
      else if (value && typeof value === 'object') for (const [k, v] of Object.entries(value)) arrays(v, `${path}.${k}`, found);
      return found;
    };
    const sameBytes = (a, b) => {
      const x = arrays(a), y = arrays(b);
      const keys = Object.keys(x).sort();
      if (keys.join() !== Object.keys(y).sort().join()) return `fields ${keys} vs ${Object.keys(y).sort()}`;
      for (const k of keys) {
        if (x[k].length !== y[k].length) return `${k}: ${x[k].length} vs ${y[k].length} bytes`;
        for (let i = 0; i < x[k].length; i++) if (x[k][i] !== y[k][i]) return `${k}: byte ${i} differs`;
      }
      return keys.length ? '' : 'no arrays';
    };
    const failure = async (promise) => promise.then((value) => ({ resolved: value }), (error) => ({
      name: error?.name, message: error?.message, isError: error instanceof Error, isDomException: error instanceof DOMException,
    }));
    const messageOf = (fn) => { try { fn(); return ''; } catch (error) { return error.message; } };

    const worker = createWorker();

    // Byte for byte, several meshes and schemes (the built-in shapes carry UVs).
    const cases = [
      ['cube', { levels: 3, normals: true }],
      ['cube', { levels: 2, scheme: ['doo-sabin', 'catmull-clark'], limit: true, normals: true, fvarLinear: 'none' }],
      ['icosahedron', { levels: 3, scheme: 'loop', limit: true, normals: true }],
      ['torus', { levels: 2, scheme: 'quad-triangle' }],
      ['icosahedron', { levels: 2, scheme: 'sqrt3' }],
    ];
    out.same = [];
    for (const [name, options] of cases) {
      const mesh = subsurf.shape(name);
      const inWorker = await worker.subdivide(mesh, options);
      out.same.push([`${name} ${JSON.stringify(options)}`, sameBytes(inWorker, subsurf.subdivide(mesh, options))]);
    }

    // Transfers, seen from both sides (a worker script of our own keeps the thread's arrays).
    const custom = createWorker({ spawn: () => new Worker(new URL('/test-worker.js', location.href), { type: 'module' }) });
    const cube = subsurf.shape('cube');
    const before = cube.positions.slice();
    const kept = await custom.call('keep', [cube, { levels: 2 }]);
    out.resultLengths = [kept.positions, kept.indices, kept.faceSizes, kept.triangles].map((a) => a.byteLength);
    out.threadLengths = await custom.call('kept');
    out.inputKept = cube.positions.byteLength === before.byteLength && cube.positions.every((x, i) => x === before[i]);
    const moved = subsurf.shape('cube');
    const movedResult = await custom.call('keep', [moved, { levels: 2 }], { transfer: true });
    out.transferredInput = [moved.positions.byteLength, moved.indices.byteLength, moved.faceSizes.byteLength];
    out.transferredSame = sameBytes(movedResult, subsurf.subdivide(subsurf.shape('cube'), { levels: 2 }));
    out.asyncFunction = await custom.call('later', ['done']);
    out.unknown = await failure(custom.call('nope', []));
    out.notCloneable = await failure(worker.subdivide(cube, { levels: 1, creases: { edges: new Uint32Array(2), sharpness: () => 1 } }));
    out.argsNotArray = await failure(worker.call('readObj', 'v 0 0 0'));
    const missing = createWorker({ spawn: () => new Worker(new URL('/missing.js', location.href), { type: 'module' }) });
    out.missingScript = await failure(missing.subdivide(cube));
    missing.terminate();
    const noWasm = createWorker({ wasm: new URL('/missing.wasm', location.href) });
    out.missingWasm = await failure(noWasm.subdivide(cube));
    noWasm.terminate();

    // Progress: after each level, with the main thread's counts; also through options.onProgress.
    const told = [];
    const expected = [];
    subsurf.subdivide(cube, { levels: 4, onProgress: (p) => expected.push(p) });
    await worker.subdivide(cube, { levels: 4 }, { onProgress: (p) => told.push(p) });
    out.progress = told;
    out.progressExpected = expected;
    const viaOptions = [];
    await worker.subdivide(cube, { levels: 2, onProgress: (p) => viaOptions.push(p.level) });
    out.progressViaOptions = viaOptions;

    // Abort a running call: level 9 of the cube (1.6M quads, seconds) stopped after level 5.
    const controller = new AbortController();
    const levelsSeen = [];
    const started = performance.now();
    const aborted = failure(worker.subdivide(cube, { levels: 9 }, {
      signal: controller.signal,
      onProgress: ({ level }) => {
        levelsSeen.push(level);
        if (level === 5) controller.abort();
      },
    }));
    out.aborted = await aborted;
    out.abortAfterMs = performance.now() - started;
    let restart = performance.now();
    const next = await worker.subdivide(cube, { levels: 1 });
    out.restartMs = performance.now() - restart;
    out.afterAbort = next.faceSizes.length;
    // The thread after an abort is started at once: a call a little later finds it ready.
    {
      const again = new AbortController();
      const stopped = failure(worker.subdivide(cube, { levels: 9 }, { signal: again.signal }));
      await new Promise((resolve) => setTimeout(resolve, 100));
      again.abort();
      await stopped;
      await new Promise((resolve) => setTimeout(resolve, 300));
      restart = performance.now();
      await worker.subdivide(cube, { levels: 1 });
      out.warmRestartMs = performance.now() - restart;
    }
    out.levelsSeen = levelsSeen;
    // Aborting a call still waiting drops it; the running one finishes.
    const second = new AbortController();
    const first = worker.subdivide(cube, { levels: 6 });
    const waiting = failure(worker.subdivide(cube, { levels: 1 }, { signal: second.signal }));
    second.abort();
    out.waitingAborted = await waiting;
    out.runningFinished = (await first).faceSizes.length;
    out.preAborted = await failure(worker.subdivide(cube, { levels: 1 }, { signal: AbortSignal.abort() }));
    out.customReason = await failure(worker.subdivide(cube, { levels: 8 }, { signal: AbortSignal.timeout(5) }));

    // Bad input: subsurf's message, and the worker goes on.
    const bad = { ...cube, indices: cube.indices.map((i, k) => (k === 5 ? 99 : i)) };
    out.badInput = await failure(worker.subdivide(bad, { levels: 1 }));
    out.badInputMain = messageOf(() => subsurf.subdivide(bad, { levels: 1 }));
    out.badOption = await failure(worker.subdivide(cube, { level: 2 }));
    out.badOptionMain = messageOf(() => subsurf.subdivide(cube, { level: 2 }));
    out.afterBad = (await worker.subdivide(cube, { levels: 2 })).faceSizes.length;
    out.callReadObj = (await worker.call('readObj', ['v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'])).indices.length;

    // terminate(): what is pending rejects, and later calls too.
    const pending = failure(worker.subdivide(cube, { levels: 7 }));
    worker.terminate();
    out.terminatedPending = await pending;
    out.afterTerminate = await failure(worker.subdivide(cube, { levels: 1 }));
    custom.terminate();

    if (torusTiming) {
      // The 1M-quad torus at level 1: main thread, worker (input copied / transferred), and the
      // thread's own subdivide time. Best of 3 each.
      const { quadTorus } = await import('/bench/torus.mjs');
      const torus = quadTorus();
      const timer = createWorker({ spawn: () => new Worker(new URL('/test-worker.js', location.href), { type: 'module' }) });
      await timer.subdivide(subsurf.shape('cube'), { levels: 1 });
      // The least of 3 times: of the call, or (`reported`) that the call returns.
      const best = async (fn, reported = false) => {
        let min = Infinity;
        for (let i = 0; i < 3; i++) {
          const start = performance.now();
          const value = await fn();
          min = Math.min(min, reported ? value : performance.now() - start);
        }
        return min;
      };
      const inputs = [quadTorus(), quadTorus(), quadTorus()]; // one per transfer
      const torusResult = await timer.subdivide(torus, { levels: 1 });
      out.torusSame = sameBytes(torusResult, subsurf.subdivide(torus, { levels: 1 }));
      out.torus = {
        mainMs: await best(() => subsurf.subdivide(torus, { levels: 1 })),
        workerMs: await best(() => timer.subdivide(torus, { levels: 1 })),
        workerTransferMs: await best(() => timer.subdivide(inputs.pop(), { levels: 1 }, { transfer: true })),
        threadMs: await best(() => timer.call('timed', [torus, { levels: 1 }]), true),
        resultBytes: Object.values(arrays(torusResult)).reduce((sum, a) => sum + a.length, 0),
      };
      timer.terminate();
    }
    return out;
  }, torusTiming);

  for (const [name, difference] of results.same) check(`byte for byte as the main thread: ${name}`, difference === '', difference);
  check('result buffers transferred: the page\'s arrays are whole', results.resultLengths.every((n) => n > 0), JSON.stringify(results.resultLengths));
  check('result buffers transferred: the thread\'s copies are detached', results.threadLengths.every((n) => n === 0), JSON.stringify(results.threadLengths));
  check('input copied by default: the caller\'s arrays are whole and unchanged', results.inputKept);
  check('transfer: true detaches the input arrays', results.transferredInput.every((n) => n === 0), JSON.stringify(results.transferredInput));
  check('transfer: true gives the same result', results.transferredSame === '', results.transferredSame);
  check('a script\'s async function is awaited', results.asyncFunction === 'done', JSON.stringify(results.asyncFunction));
  check('an unknown function is named, with the ones there are', results.unknown.name === 'TypeError' &&
    /no function 'nope'.*'subdivide'/.test(results.unknown.message), JSON.stringify(results.unknown));
  check('arguments that cannot be cloned reject with a TypeError saying so', results.notCloneable.name === 'TypeError' &&
    results.notCloneable.message.includes('cannot be sent to a worker'), JSON.stringify(results.notCloneable));
  check('call() with arguments not in an array: a TypeError', results.argsNotArray.name === 'TypeError' &&
    results.argsNotArray.message.includes('args must be an array'), JSON.stringify(results.argsNotArray));
  check('a worker script that does not load rejects the call, saying so', /the worker stopped during subdivide/.test(results.missingScript.message ?? ''),
    JSON.stringify(results.missingScript));
  check('a .wasm that does not load rejects the call, saying where and what to do', /missing\.wasm: HTTP 404; pass createWorker\(\{ wasm \}\) the URL where subsurf_bg\.wasm is served/.test(results.missingWasm.message ?? ''),
    JSON.stringify(results.missingWasm));
  const levels = results.progress.map((p) => p.level).join(',');
  check('progress after each level, in order 1..4', levels === '1,2,3,4', levels);
  check('progress counts are subdivide\'s', JSON.stringify(results.progress) === JSON.stringify(results.progressExpected), JSON.stringify(results.progress));
  check('options.onProgress works as call.onProgress', results.progressViaOptions.join(',') === '1,2', results.progressViaOptions.join(','));
  check('abort rejects with a DOMException named AbortError', results.aborted.name === 'AbortError' && results.aborted.isDomException, JSON.stringify(results.aborted));
  check('abort stops the thread: no progress after level 5', results.levelsSeen.join(',') === '1,2,3,4,5', results.levelsSeen.join(','));
  check('the call after an abort succeeds', results.afterAbort === 24,
    `${results.afterAbort} faces; ${results.restartMs.toFixed(1)} ms at once, thread start included; ${results.warmRestartMs.toFixed(1)} ms 0.3 s later`);
  check('an aborted waiting call is dropped', results.waitingAborted.name === 'AbortError', JSON.stringify(results.waitingAborted));
  check('the running call finishes meanwhile', results.runningFinished === 24576, String(results.runningFinished));
  check('an already aborted signal rejects', results.preAborted.name === 'AbortError', JSON.stringify(results.preAborted));
  check('the signal\'s own reason is the rejection (AbortSignal.timeout: TimeoutError)', results.customReason.name === 'TimeoutError', JSON.stringify(results.customReason));
  check('bad mesh: an Error with subsurf\'s message', results.badInput.isError && results.badInput.message === results.badInputMain,
    JSON.stringify(results.badInput));
  check('bad option: an Error with subsurf\'s message', results.badOption.isError && results.badOption.message === results.badOptionMain,
    JSON.stringify(results.badOption));
  check('the call after an error succeeds', results.afterBad === 96, String(results.afterBad));
  check('call() runs other functions (readObj)', results.callReadObj === 3, String(results.callReadObj));
  check('terminate() rejects the pending call with an AbortError', results.terminatedPending.name === 'AbortError', JSON.stringify(results.terminatedPending));
  check('calls after terminate() reject', /terminated/.test(results.afterTerminate.message ?? ''), JSON.stringify(results.afterTerminate));
  check('no page errors', errors.length === 0, errors.join('; '));
  if (torusTiming) {
    const t = results.torus;
    check('1M-quad torus: byte for byte as the main thread', results.torusSame === '', results.torusSame);
    console.log(`worker e2e: 1M-quad torus, level 1 (${(t.resultBytes / 1e6).toFixed(0)} MB of result), best of 3:` +
      ` main thread ${t.mainMs.toFixed(0)} ms; worker ${t.workerMs.toFixed(0)} ms (input copied),` +
      ` ${t.workerTransferMs.toFixed(0)} ms (input transferred); inside the thread ${t.threadMs.toFixed(0)} ms`);
  }
} finally {
  await browser.close();
  server.close();
}
finish();
