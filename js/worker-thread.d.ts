// subsurf/worker-thread: the thread side of subsurf/worker, for a worker script of your own.
/** What a function of the table is given besides its arguments. */
export interface CallContext {
  /**
   * Sends `value` to the call's `onProgress` on the other side, or null when the caller gave
   * none (then spend no work on progress).
   */
  progress: ((value: unknown) => void) | null;
}

/**
 * A function a worker answers: the call's arguments as an array, and the context. Its result
 * (or the promise's) goes back by structured clone, every ArrayBuffer under it transferred;
 * what it throws rejects the call with an Error of the same message.
 */
export type WorkerFunction = (args: any, context: CallContext) => unknown;

/** subsurf's own functions: spread it into your table, `{ ...functions, myJob }`. */
export const functions: {
  subdivide: WorkerFunction;
  /** subsurf/three's work on plain arrays, for `subdivideGeometryAsync` of 'subsurf/three'. */
  subdivideTriangles: WorkerFunction;
  predictCounts: WorkerFunction;
  readObj: WorkerFunction;
  writeObj: WorkerFunction;
  toDrawable: WorkerFunction;
  edgeList: WorkerFunction;
  vertexNormals: WorkerFunction;
  shape: WorkerFunction;
  version: WorkerFunction;
};

/** The part of a worker's global scope (browsers) or `parentPort` (Node) that is used. */
export type ThreadPort =
  | { postMessage(message: unknown, transfer: any[]): void; addEventListener(type: 'message', listener: (event: { data: any }) => void): void }
  | { postMessage(message: unknown, transfer: any[]): void; on(event: 'message', listener: (data: any) => void): unknown };

/**
 * Answers the calls of `createWorker({ spawn })` with the functions of `table`, on `port`
 * (default: the worker's global scope; in Node pass `parentPort` of node:worker_threads). The
 * first message initialises subsurf (the module of 'subsurf/init', which the table's functions
 * may import and call) with the client's compiled wasm.
 */
export function expose(table: Record<string, WorkerFunction>, port?: ThreadPort): void;
