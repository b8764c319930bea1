// subsurf/worker: subdivide in a Web Worker (browsers, bundlers) or a worker_threads thread
// (Node), with cancellation, progress, and results that come back as transferred buffers.
import type { SubdivideMesh, SubdivideOptions, SubdivideProgress, SubdivideResult } from './subsurf.js';

/** What `createWorker` starts a thread with. */
export interface CreateWorkerOptions {
  /**
   * The compiled subsurf wasm (`WebAssembly.Module`, or a promise of one: pass a Module you
   * already compiled to share it), or where to load `subsurf_bg.wasm` from (a URL; in Node a
   * path too). Default: the file beside this module, found as `new URL('./subsurf_bg.wasm',
   * import.meta.url)`, which bundlers turn into an asset. It is compiled once; every thread,
   * restarts included, instantiates the same Module.
   */
  wasm?: WebAssembly.Module | PromiseLike<WebAssembly.Module> | URL | string;
  /**
   * Starts a thread running a worker script of your own that calls `expose` of
   * 'subsurf/worker-thread' with more functions (for `call`). Browsers:
   * `() => new Worker(new URL('./my-worker.js', import.meta.url), { type: 'module' })`
   * (written so, literally, for bundlers to find the script); Node: `() => new Worker(url)`
   * of node:worker_threads. Default: subsurf's own script, whose functions are those of
   * `functions` in 'subsurf/worker-thread'.
   */
  spawn?: () => WorkerThread;
}

/** The part of a `Worker` (browsers) or a worker_threads `Worker` (Node) that is used. */
export interface WorkerThread {
  postMessage(message: unknown, transfer: any[]): void;
  terminate(): unknown;
}

/** How one call runs. */
export interface CallOptions<Progress = unknown> {
  /**
   * Aborting it rejects the call with the signal's reason (a `DOMException` named 'AbortError'
   * unless you gave another). A call still waiting is dropped; a running one has its thread
   * terminated (nothing else stops a wasm call) and a fresh thread started for the calls after.
   */
  signal?: AbortSignal;
  /**
   * Told as the call goes; for `subdivide`, after each level: `{ level, levels, faces,
   * vertices }`. What it throws stops the call and rejects it with that.
   */
  onProgress?: (progress: Progress) => void;
  /**
   * Transfer the ArrayBuffers of the arguments' typed arrays to the thread instead of copying
   * them: faster for large meshes, but the caller's arrays are detached (length 0) afterwards.
   * Default false: the arguments are copied and the caller's arrays stay as they were.
   */
  transfer?: boolean;
}

/**
 * A thread running subsurf. Calls run one at a time, in order; the result's arrays are
 * transferred from the thread, not copied. A thread error (bad input) rejects the call with an
 * `Error` carrying subsurf's message, and the worker takes the next call as before.
 */
export interface SubsurfWorker {
  /**
   * `subdivide(mesh, options)` of 'subsurf' in the thread; the same result, byte for byte.
   * `options.onProgress` works as `call.onProgress` (which wins when both are given).
   */
  subdivide(mesh: SubdivideMesh, options?: SubdivideOptions, call?: CallOptions<SubdivideProgress>): Promise<SubdivideResult>;
  /**
   * The thread's function `name` with `args`: subsurf's own (`subdivide`, `subdivideTriangles`
   * (what `subdivideGeometryAsync` of 'subsurf/three' calls), `predictCounts`, `readObj`,
   * `writeObj`, `toDrawable`, `edgeList`, `vertexNormals`, `shape`, `version`) or those your
   * `spawn` script exposes. Arguments and results go by structured clone.
   */
  call<Result = unknown>(name: string, args?: unknown[], call?: CallOptions): Promise<Result>;
  /** Stops the thread; calls not settled reject with an 'AbortError', later calls with an Error. */
  terminate(): void;
}

/**
 * Starts a worker thread for subsurf (the wasm is compiled on the way; calls made meanwhile
 * wait). In browsers a module Web Worker, in Node (the package's "node" condition) a
 * node:worker_threads thread, with the same API.
 */
export function createWorker(options?: CreateWorkerOptions): SubsurfWorker;
