// The demo's animate mode: the control cage is deformed every frame (a twist about the vertical
// axis and a wave travelling along it) and the surface follows through one subsurf Evaluator
// (BaseMesh.evaluator with the options of the result on screen), built on this page once per
// mesh and options, never per frame:
//
// - CPU path: evaluator.evaluateView(deformedCage) in WebAssembly on the main thread, its
//   positions and normals (views of wasm memory, no copy out) written over the WebGL2 vertex
//   buffers at once (renderer.js updateRefined; the index buffers were uploaded once). With UVs the surface is toDrawable's, whose vertices
//   are split along seams: the frame is gathered through its origins.
// - GPU path: subsurf/webgpu's createGpuEvaluator(device, evaluator) runs the same stencil table
//   in a WebGPU compute shader and gpu-renderer.js draws its positions and normals buffers
//   directly (no read-back) on a canvas of its own.
//
// Timings, a running mean over the last TIMING_WINDOW frames: CPU is evaluateView() alone
// (performance.now() around the call). GPU is the GPU's own time for the evaluation when the
// adapter has 'timestamp-query' (two timestamps around the evaluator's compute pass, written by
// two empty compute passes that bracket it, since the evaluator records its own pass; Chrome
// quantizes them to 100 µs unless its WebGPU developer features are on, which the mean
// smooths), else from queue.onSubmittedWorkDone(): from when the work queued before the frame's
// upload and evaluation is done (or the upload, if later) to when they are done. That is coarser
// (it counts the upload and the callbacks' delivery, which Chrome polls for) but it does not
// count the earlier frames' drawing queued ahead of the evaluation.

import { GpuRenderer } from './gpu-renderer.js';

const TIMING_WINDOW = 60;
/** The largest stencil table the page builds (BaseMesh.evaluator's maxBytes). */
const MAX_STENCIL_BYTES = 512 * 1024 * 1024;

/** Mean of the last `size` values added. */
class RunningMean {
  constructor(size = TIMING_WINDOW) {
    this.values = [];
    this.size = size;
  }

  add(value) {
    this.values.push(value);
    if (this.values.length > this.size) this.values.shift();
  }

  get mean() {
    return this.values.length ? this.values.reduce((a, b) => a + b, 0) / this.values.length : null;
  }

  clear() {
    this.values.length = 0;
  }
}

/** Bounds of `positions`: centre, half extents, and the largest of those (never 0). */
function extentOf(positions) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], positions[i + k]);
      hi[k] = Math.max(hi[k], positions[i + k]);
    }
  }
  if (!(lo[0] <= hi[0])) return { center: [0, 0, 0], half: [1, 1, 1], size: 1 };
  const half = hi.map((h, k) => Math.max((h - lo[k]) / 2, 1e-6));
  return { center: hi.map((h, k) => (h + lo[k]) / 2), half, size: Math.max(...half) };
}

/**
 * Writes the cage `rest` deformed at time `t` (seconds) into `out`: a twist about the vertical
 * (y) axis through the centre, up to ±0.6 rad at the top and bottom, swinging back and forth,
 * and a wave travelling along x that lifts the points by up to 8 % of the mesh's size.
 */
export function deformCage(rest, out, extent, t) {
  const { center, half, size } = extent;
  const swing = 0.6 * Math.sin(1.3 * t);
  const amplitude = 0.08 * size;
  for (let i = 0; i < rest.length; i += 3) {
    const x = rest[i] - center[0];
    const y = rest[i + 1] - center[1];
    const z = rest[i + 2] - center[2];
    const angle = swing * (y / half[1]);
    const [c, s] = [Math.cos(angle), Math.sin(angle)];
    const wave = amplitude * Math.sin(Math.PI * (x / half[0]) - 2.4 * t);
    out[i] = center[0] + c * x + s * z;
    out[i + 1] = center[1] + y + wave;
    out[i + 2] = center[2] - s * x + c * z;
  }
  return out;
}

/**
 * What the GPU toggle can do: { available, note, device?, webgpu?, timestamps? }, found once per
 * page. `timestamps: false` leaves timestamp queries out even where the adapter has them.
 */
export async function probeWebGpu({ timestamps: wantTimestamps = true } = {}) {
  let webgpu;
  try {
    webgpu = await import('./pkg/webgpu.js');
  } catch (error) {
    return { available: false, note: `WebGPU not available: the subsurf/webgpu module did not load (${error.message ?? error})` };
  }
  try {
    // requestGpuDevice says why when navigator.gpu or an adapter is missing.
    const adapter = navigator.gpu ? await navigator.gpu.requestAdapter() : null;
    const timestamps = wantTimestamps && Boolean(adapter?.features.has('timestamp-query'));
    const device = await webgpu.requestGpuDevice(timestamps ? { device: { requiredFeatures: ['timestamp-query'] } } : {});
    return { available: true, note: '', device, webgpu, timestamps };
  } catch (error) {
    const message = String(error.message ?? error).replace(/; use evaluator\.evaluate.*$/, '');
    return { available: false, note: `WebGPU not available: ${message}; the CPU path runs.` };
  }
}

export class Animator {
  /**
   * `renderer`: the WebGL2 Renderer; `gpuCanvas`: the canvas for the GPU path; `loadSubsurf`:
   * resolves to the subsurf module initialised on this page (BaseMesh). Set `gpu` to
   * probeWebGpu()'s answer once known.
   */
  constructor({ renderer, gpuCanvas, loadSubsurf }) {
    this.renderer = renderer;
    this.gpuCanvas = gpuCanvas;
    this.loadSubsurf = loadSubsurf;
    this.gpu = null; // probeWebGpu()'s answer, once known
    this.prepared = null; // { display, evaluator, rest, deformed, extent, frame, origins, surfacePositions, surfaceNormals }
    this.gpuState = null; // { evaluator, control, renderer, queries? }
    this.cpuTime = new RunningMean();
    this.gpuTime = new RunningMean();
    this.frames = 0;
    this.started = null;
  }

  get ready() {
    return this.prepared !== null;
  }

  get onGpu() {
    return this.gpuState !== null;
  }

  /**
   * Builds the evaluator for `display` (what main.js shows: its cage, result, surface and the
   * worker's subdivide options): one BaseMesh and one evaluator, kept until the next prepare or
   * release. Throws the library's message when the evaluator cannot be built.
   */
  async prepare(display) {
    const subsurf = await this.loadSubsurf();
    this.release();
    const { cage, result, surface, options } = display;
    const base = new subsurf.BaseMesh({ positions: cage.positions, indices: cage.indices, faceSizes: cage.faceSizes });
    let evaluator;
    try {
      evaluator = base.evaluator({ ...options, maxBytes: MAX_STENCIL_BYTES });
    } finally {
      base.free();
    }
    const vertices = result.positions.length / 3;
    if (evaluator.numVertices !== vertices) {
      evaluator.free();
      throw new Error(`the evaluator gives ${evaluator.numVertices} vertices, the result on screen has ${vertices}`);
    }
    const origins = surface.origins ?? null;
    this.prepared = {
      display,
      evaluator,
      rest: cage.positions,
      deformed: new Float32Array(cage.positions.length),
      extent: extentOf(cage.positions),
      frame: undefined,
      origins,
      surfacePositions: origins ? new Float32Array(3 * origins.length) : null,
      surfaceNormals: origins ? new Float32Array(3 * origins.length) : null,
    };
    this.cpuTime.clear();
    this.gpuTime.clear();
    this.started = null;
  }

  /** Frees the evaluators and GPU buffers; the caller puts the still result back on screen. */
  release() {
    this.stopGpu();
    this.prepared?.evaluator.free();
    this.prepared = null;
  }

  /**
   * Runs the GPU path from now on: uploads the evaluator's stencil table with
   * createGpuEvaluator. Throws when the GPU is unavailable or the table does not fit the device.
   */
  startGpu() {
    if (this.gpuState) return;
    if (!this.gpu?.available) throw new Error(this.gpu?.note ?? 'WebGPU has not been probed yet');
    if (!this.prepared) throw new Error('nothing to animate yet');
    const { device, webgpu, timestamps } = this.gpu;
    const { evaluator, display, rest } = this.prepared;
    const gpuEvaluator = webgpu.createGpuEvaluator(device, evaluator);
    // The deformed cage: the evaluator's input (STORAGE) and the cage lines' vertices (VERTEX).
    const control = device.createBuffer({
      label: 'demo control points', size: Math.max(4, rest.byteLength), usage: 0x80 /* STORAGE */ | 0x20 /* VERTEX */ | 0x08, /* COPY_DST */
    });
    this.gpuRenderer ??= new GpuRenderer(device, this.gpuCanvas);
    this.gpuRenderer.setMesh({ evaluator: gpuEvaluator, triangles: display.result.triangles, cageBuffer: control, cageEdges: display.cageEdges });
    let queries = null;
    if (timestamps) {
      queries = {
        set: device.createQuerySet({ type: 'timestamp', count: 2 }),
        resolve: device.createBuffer({ size: 16, usage: 0x200 /* QUERY_RESOLVE */ | 0x04 /* COPY_SRC */ }),
        read: device.createBuffer({ size: 16, usage: 0x01 /* MAP_READ */ | 0x08 /* COPY_DST */ }),
      };
    }
    this.gpuState = { evaluator: gpuEvaluator, control, queries, pending: false };
    this.gpuTime.clear();
  }

  stopGpu() {
    if (!this.gpuState) return;
    const state = this.gpuState;
    const { evaluator, control, queries } = state;
    this.gpuRenderer?.releaseMesh();
    evaluator.destroy();
    control.destroy();
    if (queries) {
      queries.set.destroy();
      queries.resolve.destroy();
      // A read buffer still mapping is destroyed when its mapping settles.
      if (!state.pending) queries.read.destroy();
    }
    state.stopped = true;
    this.gpuState = null;
  }

  /**
   * One frame at `now` (ms, the animation frame's time): deforms the cage, evaluates, and
   * either uploads the result to the WebGL2 renderer (CPU; the caller draws) or draws it with
   * WebGPU (GPU). Returns the deformed cage.
   */
  step(now, camera, { cage = true } = {}) {
    const p = this.prepared;
    this.started ??= now;
    deformCage(p.rest, p.deformed, p.extent, (now - this.started) / 1000);
    if (this.gpuState) this.stepGpu(camera, cage);
    else this.stepCpu();
    this.frames++;
    return p.deformed;
  }

  stepCpu() {
    const p = this.prepared;
    const started = performance.now();
    // Views of the evaluator's output, uploaded below before any other call into subsurf (one
    // that grows wasm memory would empty them); kept as `frame` until the next one.
    p.frame = p.evaluator.evaluateView(p.deformed);
    this.cpuTime.add(performance.now() - started);
    const { positions, normals } = p.frame;
    let surfacePositions = positions;
    let surfaceNormals = normals ?? null;
    if (p.origins) {
      const { origins } = p;
      surfacePositions = p.surfacePositions;
      surfaceNormals = normals ? p.surfaceNormals : null;
      for (let i = 0; i < origins.length; i++) {
        const [to, from] = [3 * i, 3 * origins[i]];
        surfacePositions[to] = positions[from];
        surfacePositions[to + 1] = positions[from + 1];
        surfacePositions[to + 2] = positions[from + 2];
        if (surfaceNormals) {
          surfaceNormals[to] = normals[from];
          surfaceNormals[to + 1] = normals[from + 1];
          surfaceNormals[to + 2] = normals[from + 2];
        }
      }
    }
    this.renderer.updateRefined({ positions, surfacePositions, surfaceNormals });
    this.renderer.updateCage(this.prepared.deformed);
  }

  stepGpu(camera, cage) {
    const { device } = this.gpu;
    const state = this.gpuState;
    const { evaluator, control, queries } = state;
    const { deformed } = this.prepared;
    // One measurement at a time: frames whose timing would queue behind it go unmeasured.
    const measure = !state.pending;
    const started = performance.now();
    // Without timestamps: when the work already queued (earlier frames' drawing) is done, the
    // evaluation starts; when the work submitted next is done, it has ended.
    const queueDone = measure && !queries ? device.queue.onSubmittedWorkDone().then(() => performance.now()) : null;
    device.queue.writeBuffer(control, 0, deformed);
    const encoder = device.createCommandEncoder({ label: 'demo evaluate' });
    const stamp = (index) => {
      const pass = encoder.beginComputePass({ timestampWrites: { querySet: queries.set, [index === 0 ? 'beginningOfPassWriteIndex' : 'endOfPassWriteIndex']: index } });
      pass.end();
    };
    if (measure && queries) stamp(0);
    evaluator.evaluate(control, encoder);
    if (measure && queries) {
      stamp(1);
      encoder.resolveQuerySet(queries.set, 0, 2, queries.resolve, 0);
      encoder.copyBufferToBuffer(queries.resolve, 0, queries.read, 0, 16);
    }
    device.queue.submit([encoder.finish()]);
    if (measure) {
      state.pending = true;
      const done = queries
        ? queries.read.mapAsync(0x01 /* READ */).then(() => {
          const [begin, end] = new BigUint64Array(queries.read.getMappedRange());
          queries.read.unmap();
          if (!state.stopped) this.gpuTime.add(Number(end - begin) / 1e6);
        })
        : Promise.all([queueDone, device.queue.onSubmittedWorkDone()]).then(([before]) => {
          if (!state.stopped) this.gpuTime.add(performance.now() - Math.max(before, started));
        });
      done.catch(() => {}).finally(() => {
        state.pending = false;
        if (state.stopped) queries?.read.destroy();
      });
    }
    this.gpuRenderer.draw(camera, { cage });
  }

  /** How the GPU time is measured: 'timestamp-query' or 'submitted-work-done'. */
  get gpuTiming() {
    return this.gpu?.timestamps ? 'timestamp-query' : 'submitted-work-done';
  }
}
