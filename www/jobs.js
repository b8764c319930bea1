// Runs subdivision jobs through subsurf/worker, one at a time, latest wins.
//
// The worker is the package's (createWorker) running the demo's own script (worker.js, which
// exposes `job`, `info` and `objBlob`). A job still running when a new one arrives is
// superseded, not queued: its call is aborted, which terminates that worker (the only way to
// stop a wasm call in progress) and starts a fresh one from the WebAssembly.Module the page
// compiled, which takes milliseconds. A superseded job's handlers are never called again.
import { moduleUrl } from './pkg/support.js';
import { createWorker } from './pkg/worker.js';

const spawn = () => new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });

/**
 * Compiles the subsurf wasm once; the Module is shared by the workers and the page's animation.
 * A browser without WebAssembly SIMD gets the package's build without it (`moduleUrl()`).
 */
export async function compileSubsurf(url = moduleUrl()) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`could not load ${url.pathname}: HTTP ${response.status}`);
  // compileStreaming needs the application/wasm content type; fall back to bytes otherwise.
  if (WebAssembly.compileStreaming && response.headers.get('content-type')?.startsWith('application/wasm')) {
    return WebAssembly.compileStreaming(response);
  }
  return WebAssembly.compile(await response.arrayBuffer());
}

export class JobRunner {
  /** Resolves once the first worker has answered, with the library's names (schemes, shapes, ...). */
  static async create(module) {
    const runner = new JobRunner(module);
    const info = await runner.worker.call('info');
    return { runner, info };
  }

  constructor(module) {
    this.module = module;
    this.worker = createWorker({ wasm: module, spawn });
    this.running = null; // { id, controller }
    this.nextId = 1;
    this.superseded = 0;
  }

  /** True while a job has been sent and its result or error has not come back. */
  get busy() {
    return this.running !== null;
  }

  /**
   * Runs `job` (see worker.js for its fields), superseding any job still running. `handlers`:
   * plan(message), progress({ level, levels, faces, vertices }) after each level, result(message),
   * error({ stage, message }); none is called for a superseded job. Returns the job id.
   */
  run(job, handlers) {
    if (this.running) {
      this.superseded++;
      this.running.controller.abort();
    }
    const id = this.nextId++;
    const running = { id, controller: new AbortController() };
    this.running = running;
    const current = () => this.running === running;
    const onProgress = (message) => {
      if (!current()) return;
      if (message.type === 'plan') handlers.plan?.({ ...message, id });
      else handlers.progress?.(message);
    };
    this.worker.call('job', [job], { signal: running.controller.signal, onProgress }).then(
      (message) => {
        if (!current()) return;
        this.running = null;
        (message.type === 'error' ? handlers.error : handlers.result)?.({ ...message, id });
      },
      (error) => {
        if (!current()) return; // superseded: its abort lands here
        this.running = null;
        // A trap in wasm or a worker that stopped; subsurf/worker has started a fresh one.
        handlers.error?.({ id, stage: 'worker', message: `the worker stopped: ${error?.message ?? error}` });
      },
    );
    return id;
  }

  /** Writes `mesh` as OBJ text in a worker of its own, so that no job is disturbed. */
  async writeObj(mesh) {
    const writer = createWorker({ wasm: this.module, spawn });
    try {
      return await writer.call('objBlob', [mesh]);
    } finally {
      writer.terminate();
    }
  }
}
