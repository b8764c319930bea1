// The thread side of subsurf/worker: `expose(functions)` answers the calls of createWorker()'s
// worker (worker-client.js) with the functions of a table. worker-script.js (browsers) and
// worker-script-node.js (Node) expose `functions`, subsurf's own; a worker script of your own can
// expose more (see worker-thread.d.ts), as the demo's www/worker.js does.
//
// Protocol (one call at a time; ids are the client's):
//   in:  { type: 'init', module }                 → nothing, or { type: 'init-error', message }
//   in:  { type: 'call', id, name, args, progress }
//   out: { type: 'progress', id, value }           zero or more, only when `progress` is true
//   out: { type: 'result', id, value }             every ArrayBuffer under value transferred
//     or { type: 'error', id, name, message, fatal }
// A table function is called as fn(args, { progress }), `progress` a function posting a
// progress message, or null when the caller asked for none (so no work is spent on it); it may
// return a promise.
import * as subsurf from './subsurf.js';
import { subdivideTriangles } from './geometry.js';
import { buffersOf } from './worker-client.js';

const isOptionsObject = (value) => value !== null && typeof value === 'object' && !Array.isArray(value);

/** `options` with `progress` as its onProgress; anything but an object is left for the callee to refuse. */
const withProgress = (options, progress) =>
  (progress && (options === undefined || isOptionsObject(options)) ? { ...options, onProgress: progress } : options);

/**
 * subsurf's functions for a worker: `subdivide` (progress after each level),
 * `subdivideTriangles` (subsurf/three's work, for subdivideGeometryAsync: plain arrays, no
 * three.js; progress after each level of its subdivide) and the other functions that take and
 * return plain data. Spread it into a table of your own to add more.
 */
export const functions = {
  subdivide: ([mesh, options], { progress }) => subsurf.subdivide(mesh, withProgress(options, progress)),
  subdivideTriangles: ([input, options], { progress }) => subdivideTriangles(input, withProgress(options, progress)),
  predictCounts: ([mesh, options]) => subsurf.predictCounts(mesh, options),
  readObj: ([text]) => subsurf.readObj(text),
  writeObj: ([mesh]) => subsurf.writeObj(mesh),
  toDrawable: ([mesh]) => subsurf.toDrawable(mesh),
  edgeList: ([mesh]) => subsurf.edgeList(mesh),
  vertexNormals: ([mesh]) => subsurf.vertexNormals(mesh),
  shape: ([name]) => subsurf.shape(name),
  version: () => subsurf.version(),
};

/**
 * Answers calls on `port` (the worker's global scope in a browser, `parentPort` of
 * node:worker_threads in Node) with the functions of `table`. The first message initialises
 * subsurf with the WebAssembly.Module the client compiled.
 */
export function expose(table, port = globalThis) {
  const post = (message, transfer) => port.postMessage(message, transfer);
  const names = Object.keys(table);
  const handle = (data) => {
    if (data?.type === 'init') {
      try {
        subsurf.initSync({ module: data.module });
      } catch (error) {
        post({ type: 'init-error', message: `subsurf could not start in the worker: ${error?.message ?? error}` }, []);
      }
    } else if (data?.type === 'call') {
      run(table, names, data, post);
    }
  };
  if (typeof port.on === 'function') port.on('message', handle);
  else port.addEventListener('message', (event) => handle(event.data));
}

async function run(table, names, { id, name, args, progress }, post) {
  const fn = Object.hasOwn(table, name) ? table[name] : undefined;
  if (typeof fn !== 'function') {
    const message = `subsurf/worker: this worker has no function '${name}'; it has ${names.map((n) => `'${n}'`).join(', ')}`;
    post({ type: 'error', id, name: 'TypeError', message, fatal: false }, []);
    return;
  }
  const tell = progress ? (value) => post({ type: 'progress', id, value }, []) : null;
  let value;
  try {
    // Awaited, so that a function of your own may be async.
    value = await fn(args, { progress: tell });
  } catch (error) {
    // A trap (RuntimeError) leaves the instance in no known state; RangeError is what running
    // out of memory looks like. The client replaces the thread after either.
    const fatal = error instanceof WebAssembly.RuntimeError || error instanceof RangeError;
    const name = typeof error?.name === 'string' ? error.name : 'Error';
    post({ type: 'error', id, name, message: String(error?.message ?? error), fatal }, []);
    return;
  }
  try {
    post({ type: 'result', id, value }, [...buffersOf(value)]);
  } catch {
    // A buffer that cannot be transferred (a view of a wasm memory, of a shared buffer) is
    // copied instead; what cannot even be copied is an error.
    try {
      post({ type: 'result', id, value }, []);
    } catch (error) {
      post({ type: 'error', id, name: 'TypeError', message: `subsurf/worker: ${name}'s result cannot be sent back: ${error.message}`, fatal: false }, []);
    }
  }
}
