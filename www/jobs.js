// Runs subdivision jobs in a module worker, one at a time, latest wins.
//
// A job still running when a new one arrives is superseded, not queued: its worker is
// terminated (the only way to stop a wasm call in progress) and the job goes to a spare worker
// that was started ahead of time (whenever no job was running), so the switch costs nothing.
// Every worker instantiates the one WebAssembly.Module the page compiled, which takes
// milliseconds. Messages of a superseded job are dropped by id, in case one was already queued.

const WORKER_URL = new URL('./worker.js', import.meta.url);

/** Compiles the subsurf wasm once; the Module can then be posted to any number of workers. */
export async function compileSubsurf(url = new URL('./pkg/subsurf_bg.wasm', import.meta.url)) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`could not load ${url.pathname}: HTTP ${response.status}`);
  // compileStreaming needs the application/wasm content type; fall back to bytes otherwise.
  if (WebAssembly.compileStreaming && response.headers.get('content-type')?.startsWith('application/wasm')) {
    return WebAssembly.compileStreaming(response);
  }
  return WebAssembly.compile(await response.arrayBuffer());
}

/** A started worker and the promise of its 'ready' message. */
function startWorker(module, onMessage, onCrash) {
  const worker = new Worker(WORKER_URL, { type: 'module' });
  const ready = new Promise((resolve, reject) => {
    worker.addEventListener('message', function first({ data }) {
      if (data.type !== 'ready') return;
      worker.removeEventListener('message', first);
      resolve(data);
    });
    worker.addEventListener('error', (event) => reject(new Error(event.message || 'the worker failed to start')), { once: true });
  });
  worker.addEventListener('message', ({ data }) => data.type !== 'ready' && onMessage(worker, data));
  worker.addEventListener('error', (event) => {
    event.preventDefault();
    onCrash(worker, event.message || 'the worker stopped');
  });
  worker.postMessage({ type: 'init', module });
  return { worker, ready };
}

export class JobRunner {
  /** Resolves once the first worker is ready, with the library's names (schemes, shapes, ...). */
  static async create(module) {
    const runner = new JobRunner(module);
    const info = await runner.current.ready;
    return { runner, info };
  }

  constructor(module) {
    this.module = module;
    this.current = this.start();
    this.spare = null;
    this.running = null; // { id, handlers }
    this.nextId = 1;
    this.superseded = 0;
  }

  start() {
    return startWorker(this.module, (worker, data) => this.receive(worker, data), (worker, message) => this.crashed(worker, message));
  }

  /** True while a job has been sent and its result or error has not come back. */
  get busy() {
    return this.running !== null;
  }

  /**
   * Runs `job` (see worker.js for its fields), superseding any job still running. `handlers`:
   * plan(message), result(message), error(message); none is called for a superseded job.
   * Returns the job id.
   */
  run(job, handlers) {
    if (this.running) {
      this.superseded++;
      this.replaceCurrent();
    }
    const id = this.nextId++;
    this.running = { id, handlers };
    this.current.worker.postMessage({ ...job, type: 'job', id });
    return id;
  }

  replaceCurrent() {
    this.current.worker.terminate();
    this.current = this.spare ?? this.start();
    this.spare = null;
  }

  receive(worker, data) {
    if (worker !== this.current.worker || !this.running || data.id !== this.running.id) return; // stale
    const { handlers } = this.running;
    if (data.type === 'plan') {
      handlers.plan?.(data);
      return;
    }
    this.running = null;
    if (data.type === 'error' && data.fatal) this.replaceCurrent();
    (data.type === 'error' ? handlers.error : handlers.result)?.(data);
    // A spare is started when nothing runs, so that it never slows a job down.
    if (!this.spare) this.spare = this.start();
  }

  crashed(worker, message) {
    if (worker === this.spare?.worker) {
      this.spare = null;
      return;
    }
    if (worker !== this.current.worker) return;
    const running = this.running;
    this.running = null;
    this.replaceCurrent();
    running?.handlers.error?.({ id: running.id, stage: 'worker', message: `the worker stopped: ${message}`, fatal: true });
  }

  /** Writes `mesh` as OBJ text in a worker of its own, so that no job is disturbed. */
  writeObj(mesh) {
    const { worker } = startWorker(this.module, () => {}, () => {});
    return new Promise((resolve, reject) => {
      worker.addEventListener('message', ({ data }) => {
        if (data.type === 'ready') return;
        worker.terminate();
        if (data.type === 'obj') resolve(data.blob);
        else reject(new Error(data.message));
      });
      worker.addEventListener('error', (event) => {
        worker.terminate();
        reject(new Error(event.message || 'the OBJ writer stopped'));
      });
      worker.postMessage({ type: 'writeObj', id: 0, mesh });
    });
  }
}
