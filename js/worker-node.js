// subsurf/worker in Node: the same API as worker.js (see worker.d.ts), on node:worker_threads.
import { readFile } from 'node:fs/promises';
import { Worker } from 'node:worker_threads';
import { explained, moduleUrl } from './support.js';
import { WorkerClient } from './worker-client.js';

async function compile(wasm) {
  try {
    const source = await wasm;
    if (source instanceof WebAssembly.Module) return source;
    return await WebAssembly.compile(await readFile(source ?? moduleUrl()));
  } catch (error) {
    throw explained(error);
  }
}

/** A thread for WorkerClient from a started worker_threads Worker. */
function thread(worker, listener) {
  worker.on('message', (data) => listener.message(data));
  worker.on('messageerror', () => listener.crash('a message from the worker could not be read'));
  worker.on('error', (error) => listener.crash(error?.message ?? String(error)));
  worker.on('exit', (code) => listener.crash(`it exited with code ${code}`));
  // An idle thread must not keep the process alive; a running call must.
  worker.unref();
  return {
    post: (message, transfer) => worker.postMessage(message, transfer),
    terminate: () => {
      worker.removeAllListeners('exit');
      worker.terminate();
    },
    busy: (running) => (running ? worker.ref() : worker.unref()),
  };
}

export function createWorker({ wasm, spawn } = {}) {
  const start = spawn ?? (() => new Worker(new URL('./worker-script-node.js', import.meta.url)));
  return new WorkerClient((listener) => thread(start(), listener), compile(wasm));
}
