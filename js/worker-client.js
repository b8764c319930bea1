// The calling side of subsurf/worker, shared by worker.js (Web Workers) and worker-node.js
// (worker_threads); they differ only in how a thread is started and the wasm compiled.
//
// One call runs at a time; the others wait here, not in the thread's message queue, so that an
// aborted call that has not started is simply dropped. A running wasm call cannot be
// interrupted, so aborting it terminates its thread; the next thread is started at once from the
// same compiled WebAssembly.Module (instantiating takes milliseconds), and waiting calls go on
// there. Protocol: worker-thread.js.

const NAME = 'subsurf/worker';

/** The error an abort rejects with when the signal gives no reason of its own, or terminate(). */
function abortError(message) {
  return new DOMException(`${NAME}: ${message}`, 'AbortError');
}

/**
 * Every ArrayBuffer under `value` (typed arrays and DataViews in plain objects and arrays), each
 * once. SharedArrayBuffers are shared, not transferred, and are left out.
 */
export function buffersOf(value, found = new Set(), depth = 0) {
  if (value === null || typeof value !== 'object' || depth > 8) return found;
  if (ArrayBuffer.isView(value)) {
    if (value.buffer instanceof ArrayBuffer) found.add(value.buffer);
  } else if (value instanceof ArrayBuffer) {
    found.add(value);
  } else if (Array.isArray(value) || Object.getPrototypeOf(value) === Object.prototype) {
    for (const item of Object.values(value)) buffersOf(item, found, depth + 1);
  }
  return found;
}

const ERRORS = { Error, TypeError, RangeError, SyntaxError, ReferenceError };

/** The thread's error as an Error of the same kind and message, for the caller. */
function rebuild({ name, message }) {
  if (name === 'AbortError') return new DOMException(message, 'AbortError');
  return new (ERRORS[name] ?? Error)(message);
}

/**
 * The client. `start(listener)` starts a thread and returns `{ post(message, transfer),
 * terminate(), busy(running) }`; the thread's messages go to `listener.message(data)`, its
 * failure to `listener.crash(message)`. `module` is a promise of the compiled subsurf wasm.
 */
export class WorkerClient {
  #start;
  #module;
  #thread = null;
  #queue = [];
  #running = null;
  #nextId = 1;
  #closed = false;

  constructor(start, module) {
    this.#start = start;
    this.#module = module;
    // An unused rejection would be reported as unhandled; calls see it when they await it.
    module.catch(() => {});
  }

  /** `subdivide(mesh, options)` in the thread; `options.onProgress` is honoured as `call.onProgress`. */
  subdivide(mesh, options, call = {}) {
    if (options !== null && typeof options === 'object' && typeof options.onProgress === 'function') {
      const { onProgress, ...rest } = options;
      return this.call('subdivide', [mesh, rest], { onProgress, ...call });
    }
    return this.call('subdivide', [mesh, options], call);
  }

  /** Runs the thread's function `name` with `args`. See worker.d.ts. */
  call(name, args = [], { signal, onProgress, transfer = false } = {}) {
    if (this.#closed) {
      return Promise.reject(new Error(`${NAME}: ${name}: this worker was terminated; create another with createWorker()`));
    }
    if (!Array.isArray(args)) {
      return Promise.reject(new TypeError(`${NAME}: call('${name}', args): args must be an array of the function's arguments, got ${typeof args}`));
    }
    if (signal?.aborted) return Promise.reject(signal.reason ?? abortError(`${name} was aborted`));
    return new Promise((resolve, reject) => {
      const job = { id: this.#nextId++, name, args, transfer, onProgress, signal, resolve, reject, onAbort: null };
      if (signal) {
        job.onAbort = () => this.#abort(job, signal.reason ?? abortError(`${name} was aborted`));
        signal.addEventListener('abort', job.onAbort, { once: true });
      }
      this.#queue.push(job);
      this.#pump();
    });
  }

  /** Stops the thread and rejects every call not settled yet; the worker takes no more calls. */
  terminate() {
    if (this.#closed) return;
    this.#closed = true;
    this.#stopThread();
    const jobs = [this.#running, ...this.#queue].filter(Boolean);
    this.#running = null;
    this.#queue = [];
    for (const job of jobs) this.#settle(job, false, abortError(`terminated before ${job.name} finished`));
  }

  async #pump() {
    if (this.#closed || this.#running || this.#queue.length === 0) return;
    const job = this.#queue.shift();
    this.#running = job;
    let module;
    try {
      module = await this.#module;
    } catch (error) {
      if (this.#running === job) this.#fail(job, error);
      return;
    }
    // Aborted or terminated while the wasm was being compiled.
    if (this.#running !== job) return;
    let thread;
    try {
      thread = this.#thread ??= this.#open(module);
    } catch (error) {
      // `new Worker` refused (a script from another origin, a spawn of the caller's that threw).
      this.#fail(job, new Error(`${NAME}: could not start a worker for ${job.name}: ${error?.message ?? error}`));
      return;
    }
    const message = { type: 'call', id: job.id, name: job.name, args: job.args, progress: Boolean(job.onProgress) };
    try {
      thread.post(message, job.transfer ? [...buffersOf(job.args)] : []);
    } catch (error) {
      // Structured clone refused the arguments (a function, a detached buffer, ...).
      this.#fail(job, new TypeError(`${NAME}: ${job.name}: the arguments cannot be sent to a worker: ${error.message}`));
      return;
    }
    thread.busy(true);
  }

  /** Rejects the running call before it reached a thread, and goes on with the next. */
  #fail(job, error) {
    this.#running = null;
    this.#settle(job, false, error);
    this.#pump();
  }

  #open(module) {
    const thread = this.#start({
      message: (data) => this.#receive(thread, data),
      crash: (message) => this.#crashed(thread, message),
    });
    thread.post({ type: 'init', module }, []);
    return thread;
  }

  #receive(thread, data) {
    const job = this.#running;
    if (thread !== this.#thread) return; // a terminated thread's last words
    if (data.type === 'init-error') {
      this.#crashed(thread, data.message);
      return;
    }
    if (!job || data.id !== job.id) return;
    if (data.type === 'progress') {
      try {
        job.onProgress?.(data.value);
      } catch (error) {
        // As with subdivide on the page: what the callback throws stops the call.
        this.#abort(job, error);
      }
      return;
    }
    this.#running = null;
    thread.busy(false);
    if (data.type === 'result') {
      this.#settle(job, true, data.value);
    } else {
      // A trap leaves the wasm instance in no known state: the next call gets a fresh one.
      if (data.fatal) this.#replaceThread();
      this.#settle(job, false, rebuild(data));
    }
    this.#pump();
  }

  #crashed(thread, message) {
    if (thread !== this.#thread) return;
    this.#stopThread();
    const job = this.#running;
    this.#running = null;
    if (job) this.#settle(job, false, new Error(`${NAME}: the worker stopped during ${job.name}: ${message}`));
    this.#pump();
  }

  #abort(job, reason) {
    const queued = this.#queue.indexOf(job);
    if (queued >= 0) {
      this.#queue.splice(queued, 1);
    } else if (job === this.#running) {
      this.#running = null;
      // Terminating is the only way to stop a wasm call; the next thread starts now, so that
      // it is ready (or nearly) when the next call comes.
      this.#replaceThread();
    } else {
      return;
    }
    this.#settle(job, false, reason);
    this.#pump();
  }

  #replaceThread() {
    this.#stopThread();
    if (this.#closed) return;
    this.#module.then((module) => {
      // A thread that cannot start now is started (and its error reported) by the next call.
      if (!this.#closed && !this.#thread) this.#thread = this.#open(module);
    }).catch(() => {});
  }

  #stopThread() {
    this.#thread?.terminate();
    this.#thread = null;
  }

  #settle(job, ok, value) {
    job.signal?.removeEventListener('abort', job.onAbort);
    if (ok) job.resolve(value);
    else job.reject(value);
  }
}
