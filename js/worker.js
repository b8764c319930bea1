// subsurf/worker for browsers and bundlers: subdivide in a Web Worker, so the page never
// freezes. See worker.d.ts for the API and worker-client.js for how calls run.
//
// Both URLs are written as `new URL('./file', import.meta.url)`, literally, inside the call that
// uses them: Vite and webpack 5 recognise that pattern with no configuration, bundling the
// worker script as a worker entry and the .wasm as an asset.
import { explained, moduleFile, moduleUrl } from './support.js';
import { WorkerClient } from './worker-client.js';

/** The compiled subsurf wasm from `wasm` (a Module, a promise of one, or where to fetch it). */
async function compile(wasm) {
  try {
    return await load(wasm);
  } catch (error) {
    throw explained(error);
  }
}

async function load(wasm) {
  const source = await wasm;
  if (source instanceof WebAssembly.Module) return source;
  const url = source ?? moduleUrl();
  const response = await fetch(url);
  if (!response.ok) {
    throw new Error(`subsurf/worker: could not load the wasm from ${url}: HTTP ${response.status}; pass createWorker({ wasm }) the URL where ${moduleFile()} is served`);
  }
  // Streaming compilation needs the application/wasm type; other servers get the bytes path.
  if (typeof WebAssembly.compileStreaming === 'function' && response.headers.get('content-type')?.startsWith('application/wasm')) {
    return WebAssembly.compileStreaming(response);
  }
  return WebAssembly.compile(await response.arrayBuffer());
}

/** A thread for WorkerClient from a started Worker. */
function thread(worker, listener) {
  worker.addEventListener('message', (event) => listener.message(event.data));
  worker.addEventListener('messageerror', () => listener.crash('a message from the worker could not be read'));
  worker.addEventListener('error', (event) => {
    // Handled here: the call that was running is rejected with this message.
    event.preventDefault();
    listener.crash(event.message || 'the worker script could not be loaded or threw');
  });
  return {
    post: (message, transfer) => worker.postMessage(message, transfer),
    terminate: () => worker.terminate(),
    busy() {},
  };
}

export function createWorker({ wasm, spawn } = {}) {
  if (typeof Worker !== 'function' && !spawn) {
    throw new Error('subsurf/worker: this environment has no Web Workers; in Node, import subsurf/worker through the package\'s "node" condition (it uses worker_threads)');
  }
  const start = spawn ?? (() => new Worker(new URL('./worker-script.js', import.meta.url), { type: 'module' }));
  return new WorkerClient((listener) => thread(start(), listener), compile(wasm));
}
