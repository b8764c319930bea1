// subsurf/worker in Node (worker_threads), from the built package (scripts/build-pkg.sh first):
//   node tests/js/worker_node.mjs
//   PKG_DIR=/elsewhere/pkg node tests/js/worker_node.mjs
// The same checks as tests/e2e/worker.mjs in Chromium: the main thread's result byte for byte,
// transferred results (the thread's copies detached, seen through a thread script of our own),
// copied input unless `transfer: true`, progress 1..levels, abort (running and waiting calls)
// with an AbortError and a working next call, subsurf's own error messages, terminate(); and
// that an idle worker does not keep the process alive (a child process that never calls
// terminate() must exit). Exits non-zero on failure.
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { Worker } from 'node:worker_threads';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkg = process.env.PKG_DIR ?? join(root, 'pkg');
const pkgUrl = (file) => pathToFileURL(join(pkg, file)).href;
const subsurf = await import(pkgUrl('node.js'));
const { createWorker } = await import(pkgUrl('worker-node.js'));
// The package's "node" condition must pick this file.
const exported = JSON.parse((await import('node:fs')).readFileSync(join(pkg, 'package.json'), 'utf8')).exports['./worker'];
assert.equal(exported.node, './worker-node.js');

const scratch = mkdtempSync(join(tmpdir(), 'subsurf-worker-'));
process.on('exit', () => rmSync(scratch, { recursive: true, force: true }));

let failures = 0;
async function check(name, fn) {
  try {
    const detail = await fn();
    console.log(`ok   ${name}${detail ? ` (${detail})` : ''}`);
  } catch (error) {
    failures++;
    console.error(`FAIL ${name}\n${error.stack ?? error}`);
  }
}

/** Every typed array under a result, by path, as a Buffer. */
function arrays(value, path = '', found = {}) {
  if (ArrayBuffer.isView(value)) found[path] = Buffer.from(value.buffer, value.byteOffset, value.byteLength);
  else if (value && typeof value === 'object') for (const [k, v] of Object.entries(value)) arrays(v, `${path}.${k}`, found);
  return found;
}
function assertSameBytes(a, b, what) {
  const x = arrays(a);
  const y = arrays(b);
  assert.deepEqual(Object.keys(x).sort(), Object.keys(y).sort(), `${what}: fields`);
  assert.ok(Object.keys(x).length > 0, `${what}: arrays`);
  for (const k of Object.keys(x)) assert.ok(x[k].equals(y[k]), `${what}: ${k} differs`);
}
const rejection = (promise) => promise.then((value) => assert.fail(`resolved with ${value}`), (error) => error);

const worker = createWorker();
const cube = subsurf.shape('cube');

await check('byte for byte as the main thread', async () => {
  for (const [name, options] of [
    ['cube', { levels: 3, normals: true }],
    ['icosahedron', { levels: 3, scheme: 'loop', limit: true, normals: true }],
    ['torus', { levels: 2, scheme: ['doo-sabin', 'catmull-clark'] }],
  ]) {
    const mesh = subsurf.shape(name);
    assertSameBytes(await worker.subdivide(mesh, options), subsurf.subdivide(mesh, options), `${name} ${JSON.stringify(options)}`);
  }
});

await check('results transferred; input copied unless transfer: true', async () => {
  const script = join(scratch, 'keep.js');
  writeFileSync(script, `import { parentPort } from 'node:worker_threads';
import { expose, functions } from ${JSON.stringify(pkgUrl('worker-thread.js'))};
let kept = [];
expose({
  ...functions,
  keep(args, context) {
    const result = functions.subdivide(args, context);
    kept = [result.positions, result.indices, result.faceSizes, result.triangles];
    return result;
  },
  kept: () => kept.map((array) => array.byteLength),
}, parentPort);
`);
  const custom = createWorker({ spawn: () => new Worker(pathToFileURL(script)) });
  const before = Buffer.from(cube.positions.slice().buffer);
  const result = await custom.call('keep', [cube, { levels: 2 }]);
  assert.ok([result.positions, result.indices, result.faceSizes, result.triangles].every((a) => a.byteLength > 0));
  assert.deepEqual(await custom.call('kept'), [0, 0, 0, 0], "the thread's copies are detached");
  assert.ok(Buffer.from(cube.positions.buffer).equals(before), 'the input is whole and unchanged');
  const moved = subsurf.shape('cube');
  assertSameBytes(await custom.call('keep', [moved, { levels: 2 }], { transfer: true }), result, 'transferred input');
  assert.deepEqual([moved.positions.byteLength, moved.indices.byteLength], [0, 0], 'transfer: true detaches the input');
  custom.terminate();
});

await check('progress after each level, 1..levels, with subdivide\'s counts', async () => {
  const expected = [];
  subsurf.subdivide(cube, { levels: 4, onProgress: (p) => expected.push(p) });
  const told = [];
  await worker.subdivide(cube, { levels: 4 }, { onProgress: (p) => told.push(p) });
  assert.deepEqual(told, expected);
  assert.deepEqual(told.map((p) => p.level), [1, 2, 3, 4]);
  return told.map((p) => `${p.level}/${p.levels}: ${p.faces} faces`).join(', ');
});

await check('what onProgress throws rejects the call; the next call succeeds', async () => {
  const error = await rejection(worker.subdivide(cube, { levels: 9 }, { onProgress: ({ level }) => { if (level === 3) throw new RangeError('enough'); } }));
  assert.equal(error.message, 'enough');
  assert.equal((await worker.subdivide(cube, { levels: 1 })).faceSizes.length, 24);
});

await check('abort: AbortError, progress stops, the next call succeeds on a fresh thread', async () => {
  const controller = new AbortController();
  const seen = [];
  const error = await rejection(worker.subdivide(cube, { levels: 9 }, {
    signal: controller.signal,
    onProgress: ({ level }) => {
      seen.push(level);
      if (level === 5) controller.abort();
    },
  }));
  assert.ok(error instanceof DOMException && error.name === 'AbortError', `${error}`);
  const start = performance.now();
  assert.equal((await worker.subdivide(cube, { levels: 1 })).faceSizes.length, 24);
  const restart = performance.now() - start;
  await new Promise((resolve) => setTimeout(resolve, 200));
  assert.deepEqual(seen, [1, 2, 3, 4, 5]);
  // A waiting call is dropped, the running one finishes.
  const waiting = new AbortController();
  const first = worker.subdivide(cube, { levels: 5 });
  const second = rejection(worker.subdivide(cube, { levels: 1 }, { signal: waiting.signal }));
  waiting.abort();
  assert.equal((await second).name, 'AbortError');
  assert.equal((await first).faceSizes.length, 6144);
  assert.equal((await rejection(worker.subdivide(cube, {}, { signal: AbortSignal.abort() }))).name, 'AbortError');
  return `next call ${restart.toFixed(1)} ms, thread start included`;
});

await check('bad input: subsurf\'s message, and the worker goes on', async () => {
  const bad = { ...cube, indices: cube.indices.map((i, k) => (k === 5 ? 99 : i)) };
  let main = '';
  try { subsurf.subdivide(bad, { levels: 1 }); } catch (error) { main = error.message; }
  const error = await rejection(worker.subdivide(bad, { levels: 1 }));
  assert.ok(error instanceof Error);
  assert.equal(error.message, main);
  assert.match(error.message, /refers to vertex 99/);
  assert.equal((await worker.subdivide(cube, { levels: 2 })).faceSizes.length, 96);
  assert.match((await rejection(worker.call('nope'))).message, /no function 'nope'/);
});

await check('misuse and failures to start are errors that say what happened', async () => {
  const error = await rejection(worker.call('readObj', 'v 0 0 0'));
  assert.ok(error instanceof TypeError && /args must be an array/.test(error.message), `${error}`);
  const broken = createWorker({ spawn: () => { throw new Error('no threads here'); } });
  assert.match((await rejection(broken.subdivide(cube))).message, /could not start a worker for subdivide: no threads here/);
  broken.terminate();
  const crashing = createWorker({ spawn: () => new Worker('process.exit(3)', { eval: true }) });
  assert.match((await rejection(crashing.subdivide(cube))).message, /the worker stopped during subdivide: it exited with code 3/);
  crashing.terminate();
  const missing = createWorker({ wasm: join(scratch, 'missing.wasm') });
  assert.match((await rejection(missing.subdivide(cube))).message, /missing\.wasm/);
  missing.terminate();
});

await check('terminate(): pending and later calls reject', async () => {
  const pending = rejection(worker.subdivide(cube, { levels: 7 }));
  worker.terminate();
  assert.equal((await pending).name, 'AbortError');
  assert.match((await rejection(worker.subdivide(cube))).message, /terminated/);
});

await check('an idle worker does not keep the process alive', () => {
  const script = join(scratch, 'idle.mjs');
  writeFileSync(script, `import { createWorker } from ${JSON.stringify(pkgUrl('worker-node.js'))};
const worker = createWorker();
const out = await worker.subdivide({ positions: new Float32Array(9), indices: new Uint32Array([0, 1, 2]) }, { levels: 1, scheme: 'loop' }).catch((e) => e.message);
console.log(JSON.stringify(out.faceSizes?.length ?? out));
`);
  const child = spawnSync(process.execPath, [script], { encoding: 'utf8', timeout: 20000 });
  assert.equal(child.status, 0, `exit ${child.status} ${child.signal ?? ''}: ${child.stderr}`);
  assert.equal(child.stdout.trim(), '4');
});

console.log(failures === 0 ? 'worker (node): ok' : `worker (node): ${failures} FAILED`);
process.exit(failures === 0 ? 0 : 1);
