// subsurf/webgpu: stencil tables evaluated by a WebGPU compute shader.
//
// The WebGPU types (GPUDevice, GPUBuffer, GPUCommandEncoder) come from the consumer's own
// typings when it has them (@webgpu/types, or a TypeScript lib.dom that declares WebGPU);
// otherwise the minimal shapes below stand in, so this file compiles either way.

type WebGpuGlobal<Name extends string, Fallback> =
  typeof globalThis extends { [K in Name]: { prototype: infer T } } ? T : Fallback;

/** What this module uses of a GPUDevice, when no WebGPU typings are loaded. */
interface MinimalGPUDevice {
  readonly limits: Record<string, number>;
  readonly queue: object;
  readonly lost: Promise<{ readonly reason: string; readonly message: string }>;
  createBuffer(descriptor: object): MinimalGPUBuffer;
}
/** What this module uses of a GPUBuffer, when no WebGPU typings are loaded. */
interface MinimalGPUBuffer {
  readonly size: number;
  readonly usage: number;
  mapAsync(mode: number, offset?: number, size?: number): Promise<undefined>;
  destroy(): undefined | void;
}
/** What this module uses of a GPUCommandEncoder, when no WebGPU typings are loaded. */
interface MinimalGPUCommandEncoder {
  beginComputePass(descriptor?: object): object;
}

export type GPUDeviceType = WebGpuGlobal<'GPUDevice', MinimalGPUDevice>;
export type GPUBufferType = WebGpuGlobal<'GPUBuffer', MinimalGPUBuffer>;
export type GPUCommandEncoderType = WebGpuGlobal<'GPUCommandEncoder', MinimalGPUCommandEncoder>;

/**
 * A stencil table as flat arrays (what `Evaluator.stencils()` returns): output vertex i is the
 * sum over k in `offsets[i]` .. `offsets[i + 1]` of `weights[k] * control[indices[k]]`.
 */
export interface StencilArrays {
  /** numVertices + 1 entries, from 0 to indices.length, never decreasing. */
  offsets: Uint32Array;
  /** The control (base-mesh) vertex of each entry, each below numControlVertices. */
  indices: Uint32Array;
  weights: Float32Array;
  /**
   * The weights of the two limit tangents, parallel to `weights`, summing to 0 in each row (as
   * a derivative's do; every table of `Evaluator.stencils()` and OpenSubdiv's
   * `LimitStencilTable` are so). When present, the evaluator also computes normals:
   * cross(t1, t2) normalised, (0, 0, 0) where that length is 0 or not finite. Each tangent is
   * summed as sum(w * (v - v0)), v0 the row's first control point: equal to sum(w * v) for
   * such weights, and f32 keeps the digits the normal needs. `createGpuEvaluator` throws, naming
   * the row, when a row's sum passes 1e-4 of its weights' size.
   */
  tangentWeights?: [Float32Array, Float32Array];
  /** The base mesh's vertex count (Evaluator.stencils() gives it). */
  numControlVertices?: number;
}

/**
 * What createGpuEvaluator reads of an `Evaluator` from `BaseMesh.evaluator()`: its
 * `levelStencils()` (the tables level by level, one GPU pass each) when it has no normals and
 * has left its composed table out (`hasStencilTable` false), else its `stencils()` (normals
 * through several f32 levels keep fewer digits than the 1e-5 the GPU evaluator promises).
 */
export interface EvaluatorLike {
  readonly numControlVertices: number;
  readonly hasNormals?: boolean;
  readonly hasStencilTable?: boolean;
  stencils(): StencilArrays;
  levelStencils?(): StencilArrays[];
}

export interface RequestGpuDeviceOptions {
  /** Passed to navigator.gpu.requestAdapter(). */
  adapter?: object;
  /**
   * Passed to adapter.requestDevice(); its `requiredLimits` override the raised
   * maxStorageBufferBindingSize and maxBufferSize.
   */
  device?: { requiredLimits?: Record<string, number>; [key: string]: unknown };
}

/**
 * Requests a WebGPU device, with the adapter's largest maxStorageBufferBindingSize and
 * maxBufferSize (the defaults, 128 MiB and 256 MiB, hold tables of a few million weights
 * only). Rejects with an Error saying why and what to do when `navigator.gpu` is missing (an
 * old browser, or a page that is not a secure context) or no adapter is found.
 */
export function requestGpuDevice(options?: RequestGpuDeviceOptions): Promise<GPUDeviceType>;

/**
 * Uploads stencil tables to the device: `source` is an Evaluator (`BaseMesh.evaluator()`; its
 * `levelStencils()`, or `stencils()` when it has only that, and `numControlVertices` are read),
 * a table's arrays, or a list of tables run in turn, each on the outputs of the one before (as
 * `Evaluator.levelStencils()` gives them; only the last may have tangent weights), with
 * `numControlVertices`, the base mesh's vertex count (a field of the arrays or an argument).
 * The arrays are checked once (parallel lengths, offsets rising, indices in range) and copied;
 * throws an Error naming the problem (and the table, in a list), or the device limit a table
 * exceeds. A list runs as one compute pass with a dispatch per table.
 */
export function createGpuEvaluator(device: GPUDeviceType, source: EvaluatorLike | (StencilArrays & { numControlVertices: number }) | (StencilArrays & { numControlVertices: number })[]): GpuEvaluator;
export function createGpuEvaluator(device: GPUDeviceType, source: StencilArrays | StencilArrays[], numControlVertices: number): GpuEvaluator;

export interface GpuReadBack {
  /** x, y, z per output vertex. */
  positions: Float32Array;
  /** Unit normals, x, y, z per output vertex, when the table has tangent weights. */
  normals?: Float32Array;
}

/** A stencil table on the GPU, with its output buffers. */
export class GpuEvaluator {
  /** The same as createGpuEvaluator. */
  constructor(device: GPUDeviceType, source: EvaluatorLike | (StencilArrays & { numControlVertices: number }) | (StencilArrays & { numControlVertices: number })[]);
  constructor(device: GPUDeviceType, source: StencilArrays | StencilArrays[], numControlVertices: number);
  readonly device: GPUDeviceType;
  readonly numControlVertices: number;
  /** The number of output vertices. */
  readonly numVertices: number;
  /** Whether the table has tangent weights, so that `normals` exists. */
  readonly hasNormals: boolean;
  /** Whether destroy() was called. */
  readonly destroyed: boolean;
  /**
   * 3 f32 per output vertex, tightly packed (a vertex buffer with arrayStride 12, format
   * 'float32x3'); usage VERTEX | STORAGE | COPY_SRC.
   */
  readonly positions: GPUBufferType;
  /** Unit normals laid out as `positions`; present when `hasNormals`. */
  readonly normals: GPUBufferType | undefined;
  /**
   * Computes the output from `control`: a Float32Array of 3 * numControlVertices floats,
   * uploaded with queue.writeBuffer, or a GPUBuffer with STORAGE usage holding them (read in
   * place). Records a compute pass into `encoder` when given (submit it yourself; the upload of
   * a Float32Array happens at the next submit, so two calls into one encoder both see the
   * later array), otherwise submits its own. Reads nothing back. Throws when the control has
   * the wrong type or length, a Float32Array holds a NaN, an infinity or a value beyond ±1e30
   * (a GPUBuffer's values are not read), the device was lost, or the evaluator was destroyed.
   */
  evaluate(control: Float32Array | GPUBufferType, encoder?: GPUCommandEncoderType): void;
  /**
   * Copies the outputs back to the CPU once the work submitted so far is done: for tests and
   * debugging, not for every frame.
   */
  readBack(): Promise<GpuReadBack>;
  /** Frees the evaluator's GPU buffers, `positions` and `normals` included. */
  destroy(): void;
}

/** The WGSL source the evaluator runs, for reading. */
export function stencilShader(options?: { normals?: boolean; mergedWeights?: boolean }): string;
