// subsurf/webgpu: evaluates subsurf's stencil tables on the GPU with a WebGPU compute shader.
// Refine once on the CPU (BaseMesh.evaluator), upload the table once, then each frame upload the
// moved control points (or hand over a GPUBuffer) and get the refined points, and the limit
// normals when the table has tangent weights, in GPU buffers usable directly as vertex buffers.
// No dependencies; works without the wasm module (the tables are plain typed arrays).

const WORKGROUP_SIZE = 64;
const CPU_FALLBACK = 'use evaluator.evaluate(positions) on the CPU instead';

// The buffer usage flags, as numbers so that this module loads where WebGPU is missing (the
// values are fixed by the WebGPU specification).
const MAP_READ = 0x0001;
const COPY_SRC = 0x0004;
const COPY_DST = 0x0008;
const VERTEX = 0x0020;
const STORAGE = 0x0080;

/**
 * Requests a WebGPU device for the GPU evaluator, with the adapter's largest storage-buffer
 * binding and buffer sizes (the defaults, 128 MiB and 256 MiB, fit tables of a few million
 * weights only). `options.adapter` goes to requestAdapter, `options.device` to requestDevice
 * (its requiredLimits override the raised ones). Throws an Error saying why when WebGPU or an
 * adapter is missing.
 */
export async function requestGpuDevice(options = {}) {
  const gpu = typeof navigator === 'undefined' ? undefined : navigator.gpu;
  if (!gpu) {
    let why;
    if (globalThis.process?.versions?.node || typeof navigator === 'undefined') {
      why = 'navigator.gpu is missing: this is not a browser (Node.js has no WebGPU)';
    } else if (globalThis.isSecureContext === false) {
      why = `navigator.gpu is missing because this page is not a secure context (${globalThis.location?.origin ?? 'its origin'}); ` +
        'WebGPU needs https:// or http://localhost / http://127.0.0.1';
    } else {
      why = 'navigator.gpu is missing; it needs Chrome or Edge 113+, Safari 26+ or Firefox 141+ (Windows), ' +
        'in a secure context (https:// or localhost), with WebGPU not disabled';
    }
    throw new Error(`WebGPU is not available in this browser (${why}); ${CPU_FALLBACK}`);
  }
  const adapter = await gpu.requestAdapter(options.adapter);
  if (!adapter) {
    throw new Error('WebGPU is present but no GPU adapter was found (navigator.gpu.requestAdapter() returned null: ' +
      `the GPU may be blocklisted or disabled; see chrome://gpu in Chrome); ${CPU_FALLBACK}`);
  }
  const descriptor = options.device ?? {};
  const requiredLimits = {
    maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
    maxBufferSize: adapter.limits.maxBufferSize,
    ...descriptor.requiredLimits,
  };
  return adapter.requestDevice({ ...descriptor, requiredLimits });
}

/**
 * Uploads stencil tables to `device` and returns a GpuEvaluator. `source` is an Evaluator from
 * BaseMesh.evaluator() (its levelStencils(), or stencils() for an object that has only that,
 * and numControlVertices are read), the arrays of one table, `{ offsets, indices, weights,
 * tangentWeights?, numControlVertices? }`, or an array of such tables run in turn (each on the
 * one before's outputs, as levelStencils() gives them), with `numControlVertices` given here
 * when the arrays do not carry it.
 */
export function createGpuEvaluator(device, source, numControlVertices) {
  return new GpuEvaluator(device, source, numControlVertices);
}

export class GpuEvaluator {
  constructor(device, source, numControlVertices) {
    if (!device || typeof device.createBuffer !== 'function' || !device.queue) {
      throw new Error(`createGpuEvaluator: the first argument must be a GPUDevice (got ${describe(device)}); ` +
        'get one with await requestGpuDevice()');
    }
    let tables = source;
    if (source && typeof source.levelStencils === 'function' && !source.hasNormals && source.hasStencilTable === false) {
      // The levels' own tables, where the evaluator left its composed table out: none to
      // build, and less to upload. Not with normals: tangents of points that went through
      // several f32 levels keep fewer digits (5e-5 apart from the CPU's on the torus at level
      // 6, past the 1e-5 promised here).
      if (numControlVertices === undefined) numControlVertices = source.numControlVertices;
      tables = source.levelStencils();
    } else if (source && typeof source.stencils === 'function') {
      if (numControlVertices === undefined) numControlVertices = source.numControlVertices;
      tables = source.stencils();
    }
    if (!Array.isArray(tables)) tables = [tables];
    if (tables.length === 0) {
      throw new Error('createGpuEvaluator: the list of stencil tables is empty; pass evaluator.levelStencils() or evaluator.stencils()');
    }
    // Evaluator.stencils() and levelStencils() say it too.
    if (numControlVertices === undefined && tables[0]) numControlVertices = tables[0].numControlVertices;
    const checked = [];
    let inputs = numControlVertices;
    tables.forEach((stencils, k) => {
      const table = checkTable(stencils, inputs, tableLabel(k, tables.length));
      if (table.tangentWeights !== undefined && k + 1 < tables.length) {
        throw new Error(`createGpuEvaluator: table ${k} of ${tables.length} has tangentWeights; only the last table's give normals`);
      }
      checked.push(table);
      inputs = table.numVertices;
    });
    const last = checked[checked.length - 1];
    this.device = device;
    this.numControlVertices = numControlVertices;
    this.numVertices = last.numVertices;
    this.hasNormals = last.tangentWeights !== undefined;
    this._lost = null;
    this._destroyed = false;
    this._owned = [];
    device.lost.then((info) => { this._lost = info; });
    this._control = this._buffer('control points', 12 * numControlVertices, STORAGE | COPY_DST);
    this.positions = this._buffer('positions', 12 * this.numVertices, VERTEX | STORAGE | COPY_SRC);
    this.normals = this.hasNormals
      ? this._buffer('normals', 12 * this.numVertices, VERTEX | STORAGE | COPY_SRC)
      : undefined;
    try {
      this._stages = checked.map((table, k) => this._stage(table, k, checked.length));
    } catch (error) {
      // A table past the device's limits: free what was made before it.
      for (const buffer of this._owned) buffer.destroy();
      throw error;
    }
  }

  /** One table on the device: its buffers, its output (the next one's input), its pipeline and dispatch. */
  _stage(table, k, count) {
    const device = this.device;
    const limits = device.limits;
    const lastStage = k + 1 === count;
    const normals = lastStage && this.hasNormals;
    const which = tableLabel(k, count);
    const maxBinding = Math.min(limits.maxStorageBufferBindingSize, limits.maxBufferSize);
    const nnz = table.indices.length;
    // With normals, the three weights of an entry go to one buffer, interleaved, when it fits:
    // one binding instead of three and one read per entry. Otherwise three bindings.
    const merged = normals && 12 * nnz <= maxBinding;
    const storageBuffers = 5 + (normals ? 1 : 0) + (normals && !merged ? 2 : 0);
    if (storageBuffers > limits.maxStorageBuffersPerShaderStage) {
      throw new Error(`createGpuEvaluator: the shader needs ${storageBuffers} storage buffers, more than this device's ` +
        `maxStorageBuffersPerShaderStage (${limits.maxStorageBuffersPerShaderStage}); request a device with ` +
        `requiredLimits: { maxStorageBuffersPerShaderStage: ${storageBuffers} } (a core WebGPU device has 8), or ${CPU_FALLBACK}`);
    }
    const sizes = [
      ['offsets', 4 * (table.numVertices + 1)],
      ['indices', 4 * nnz],
      [merged ? 'weights and tangent weights (interleaved)' : 'weights', (merged ? 12 : 4) * nnz],
      ['control points', 12 * table.numInputs],
      [lastStage ? 'positions' : 'level points', 12 * table.numVertices],
    ];
    for (const [what, bytes] of sizes) {
      if (bytes > maxBinding) {
        throw new Error(`createGpuEvaluator: ${which}the table's ${what} need ${bytes} bytes, more than this device allows in one ` +
          `storage buffer (maxStorageBufferBindingSize ${limits.maxStorageBufferBindingSize}, maxBufferSize ` +
          `${limits.maxBufferSize}); request the device with requestGpuDevice(), which raises both to the adapter's ` +
          `maximum, or use fewer levels, or ${CPU_FALLBACK}`);
      }
    }
    // `input` is the buffer the bind group was made for: the caller's control for the first
    // table, which may change between frames; the table before's output for the others.
    const stage = { numVertices: table.numVertices, numInputs: table.numInputs, merged, normals, bindGroup: null, input: null };
    stage.offsets = this._upload('offsets', table.offsets);
    stage.indices = this._upload('indices', table.indices);
    if (merged) {
      const [t1, t2] = table.tangentWeights;
      stage.weights = this._upload('weights', null, 12 * nnz, (mapped) => {
        const out = new Float32Array(mapped);
        const w = table.weights;
        for (let i = 0, j = 0; i < nnz; i++, j += 3) {
          out[j] = w[i];
          out[j + 1] = t1[i];
          out[j + 2] = t2[i];
        }
      });
    } else {
      stage.weights = this._upload('weights', table.weights);
      if (normals) {
        stage.tangents1 = this._upload('tangent weights 1', table.tangentWeights[0]);
        stage.tangents2 = this._upload('tangent weights 2', table.tangentWeights[1]);
      }
    }
    stage.output = lastStage ? this.positions : this._buffer(`level ${k + 1} points`, 12 * table.numVertices, STORAGE);
    stage.pipeline = pipeline(device, normals, merged);
    // The dispatch: one invocation per output vertex, 2D when one dimension is not enough.
    const groups = Math.ceil(table.numVertices / WORKGROUP_SIZE);
    const maxPerDimension = limits.maxComputeWorkgroupsPerDimension;
    const x = Math.min(groups, maxPerDimension);
    stage.groups = [x, groups === 0 ? 0 : Math.ceil(groups / x)];
    if (stage.groups[1] > maxPerDimension) {
      throw new Error(`createGpuEvaluator: ${which}${table.numVertices} output vertices need more workgroups than this device can ` +
        `dispatch (${maxPerDimension} x ${maxPerDimension} of ${WORKGROUP_SIZE}); use fewer levels, or ${CPU_FALLBACK}`);
    }
    return stage;
  }

  /** Whether destroy() was called. */
  get destroyed() {
    return this._destroyed;
  }

  /**
   * Computes the refined positions (and normals) from `control`: a Float32Array of x, y, z per
   * base-mesh vertex, uploaded with queue.writeBuffer, or a GPUBuffer with STORAGE usage holding
   * them (read in place). Records a compute pass into `encoder` when given (you submit it),
   * otherwise submits its own. Nothing is read back.
   */
  evaluate(control, encoder) {
    // (A Float32Array's values are checked as the wasm evaluator checks them; a GPUBuffer's are
    // the caller's: reading them back would cost the frame.)
    this._checkUsable('evaluate');
    const expected = 3 * this.numControlVertices;
    let buffer;
    if (control instanceof Float32Array) {
      if (control.length !== expected) {
        throw new Error(`GpuEvaluator.evaluate: control has ${control.length} floats, but this table needs ${expected} ` +
          `(x, y, z for each of its ${this.numControlVertices} base-mesh vertices); pass the base mesh's positions`);
      }
      checkCoordinates(control);
      if (expected > 0) this.device.queue.writeBuffer(this._control, 0, control.buffer, control.byteOffset, control.byteLength);
      buffer = this._control;
    } else if (isGpuBuffer(control)) {
      if ((control.usage & STORAGE) === 0) {
        throw new Error('GpuEvaluator.evaluate: the control GPUBuffer was not created with GPUBufferUsage.STORAGE; ' +
          'add STORAGE to its usage, or pass a Float32Array');
      }
      if (control.size < 4 * expected) {
        throw new Error(`GpuEvaluator.evaluate: the control GPUBuffer has ${control.size} bytes, but this table needs ` +
          `${4 * expected} (3 f32 for each of its ${this.numControlVertices} base-mesh vertices)`);
      }
      buffer = control;
    } else {
      throw new Error(`GpuEvaluator.evaluate: control must be a Float32Array of ${expected} floats (x, y, z per base-mesh ` +
        `vertex) or a GPUBuffer with STORAGE usage, got ${describe(control)}` +
        (ArrayBuffer.isView(control) || Array.isArray(control) ? '; convert it with new Float32Array(control)' : ''));
    }
    if (this.numVertices === 0) return;
    const own = !encoder;
    const commands = own ? this.device.createCommandEncoder({ label: 'subsurf GpuEvaluator' }) : encoder;
    const pass = commands.beginComputePass({ label: 'subsurf stencils' });
    // One dispatch per table, each reading the one before's points (WebGPU orders the
    // dispatches of a pass and makes each one's writes visible to the next).
    let input = buffer;
    for (const stage of this._stages) {
      if (stage.numVertices > 0) {
        pass.setPipeline(stage.pipeline);
        pass.setBindGroup(0, this._bindGroupFor(stage, input));
        pass.dispatchWorkgroups(stage.groups[0], stage.groups[1]);
      }
      input = stage.output;
    }
    pass.end();
    if (own) this.device.queue.submit([commands.finish()]);
  }

  /**
   * Copies the current positions (and normals) back to the CPU, after the work submitted so far
   * (for tests and debugging: a frame should draw from the buffers instead).
   */
  async readBack() {
    this._checkUsable('readBack');
    const bytes = 12 * this.numVertices;
    const sources = this.hasNormals ? [this.positions, this.normals] : [this.positions];
    if (bytes === 0) {
      return this.hasNormals ? { positions: new Float32Array(0), normals: new Float32Array(0) } : { positions: new Float32Array(0) };
    }
    const staging = sources.map(() => this.device.createBuffer({ label: 'subsurf read-back', size: bytes, usage: MAP_READ | COPY_DST }));
    try {
      const commands = this.device.createCommandEncoder({ label: 'subsurf read-back' });
      sources.forEach((source, i) => commands.copyBufferToBuffer(source, 0, staging[i], 0, bytes));
      this.device.queue.submit([commands.finish()]);
      const arrays = [];
      for (const buffer of staging) {
        try {
          await buffer.mapAsync(MAP_READ);
        } catch (error) {
          // A device lost while waiting: say so (the lost promise settles about now).
          await new Promise((resolve) => setTimeout(resolve, 0));
          this._checkUsable('readBack');
          throw new Error(`GpuEvaluator.readBack: mapping the results failed (${error.message ?? error})`);
        }
        arrays.push(new Float32Array(buffer.getMappedRange().slice(0)));
        buffer.unmap();
      }
      return this.hasNormals ? { positions: arrays[0], normals: arrays[1] } : { positions: arrays[0] };
    } finally {
      for (const buffer of staging) buffer.destroy();
    }
  }

  /** Frees the GPU buffers (positions and normals included; a caller's control buffer is kept). */
  destroy() {
    if (this._destroyed) return;
    this._destroyed = true;
    for (const buffer of this._owned) buffer.destroy();
    this._owned = [];
    for (const stage of this._stages) Object.assign(stage, { bindGroup: null, input: null });
  }

  _checkUsable(method) {
    if (this._destroyed) {
      throw new Error(`GpuEvaluator.${method}: this evaluator was destroyed (destroy() was called); ` +
        'create a new one with createGpuEvaluator(device, evaluator)');
    }
    if (this._lost) {
      const why = this._lost.reason === 'destroyed' ? 'device.destroy() was called' : this._lost.message || 'no reason given';
      throw new Error(`GpuEvaluator.${method}: the GPU device was lost (reason '${this._lost.reason}': ${why}); ` +
        'request a new device with requestGpuDevice() and create a new GpuEvaluator on it, ' +
        `or ${CPU_FALLBACK}`);
    }
  }

  _buffer(label, size, usage, mappedAtCreation = false) {
    // Bindings cannot be empty: an empty table still gets 4 bytes.
    const buffer = this.device.createBuffer({ label: `subsurf ${label}`, size: Math.max(4, size), usage, mappedAtCreation });
    this._owned.push(buffer);
    return buffer;
  }

  _upload(label, array, size = array.byteLength, fill = (mapped) => new array.constructor(mapped).set(array)) {
    const buffer = this._buffer(label, size, STORAGE, true);
    fill(buffer.getMappedRange(0, size));
    buffer.unmap();
    return buffer;
  }

  _bindGroupFor(stage, input) {
    if (stage.bindGroup && stage.input === input) return stage.bindGroup;
    const entries = [
      { binding: 0, resource: { buffer: stage.offsets } },
      { binding: 1, resource: { buffer: stage.indices } },
      { binding: 2, resource: { buffer: stage.weights } },
      { binding: 3, resource: { buffer: input, size: Math.max(4, 12 * stage.numInputs) } },
      { binding: 4, resource: { buffer: stage.output } },
    ];
    if (stage.normals) {
      entries.push({ binding: 5, resource: { buffer: this.normals } });
      if (!stage.merged) {
        entries.push({ binding: 6, resource: { buffer: stage.tangents1 } });
        entries.push({ binding: 7, resource: { buffer: stage.tangents2 } });
      }
    }
    stage.bindGroup = this.device.createBindGroup({
      label: 'subsurf stencils',
      layout: stage.pipeline.getBindGroupLayout(0),
      entries,
    });
    stage.input = input;
    return stage.bindGroup;
  }
}

/** The WGSL of the stencil sum; exported for reading, not needed to use the evaluator. */
export function stencilShader({ normals = false, mergedWeights = true } = {}) {
  const merged = normals && mergedWeights;
  const weight = merged ? 'weights[3u * k]' : 'weights[k]';
  return /* wgsl */ `// subsurf: output vertex i = sum of weights[k] * control[indices[k]], k in offsets[i]..offsets[i+1]
@group(0) @binding(0) var<storage, read> offsets: array<u32>;
@group(0) @binding(1) var<storage, read> indices: array<u32>;
@group(0) @binding(2) var<storage, read> weights: array<f32>;${merged ? ' // w, t1, t2 per entry' : ''}
@group(0) @binding(3) var<storage, read> control: array<f32>;
@group(0) @binding(4) var<storage, read_write> positions: array<f32>;
${normals ? '@group(0) @binding(5) var<storage, read_write> normals: array<f32>;\n' : ''}${normals && !merged ? `@group(0) @binding(6) var<storage, read> tangents1: array<f32>;
@group(0) @binding(7) var<storage, read> tangents2: array<f32>;
` : ''}
@compute @workgroup_size(${WORKGROUP_SIZE})
fn main(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
  let i = id.x + id.y * groups.x * ${WORKGROUP_SIZE}u;
  if (i + 1u >= arrayLength(&offsets)) {
    return;
  }
  let end = offsets[i + 1u];
  var p = vec3<f32>(0.0);
${normals ? `  var t1 = vec3<f32>(0.0);
  var t2 = vec3<f32>(0.0);
  // A tangent's weights sum to 0, so sum(w * v) = sum(w * (v - origin)) for any point origin:
  // with the row's first control point, each term is a local difference and f32 keeps the
  // digits the normal needs (as the CPU evaluator sums them).
  var origin = vec3<f32>(0.0);
  if (offsets[i] < end) {
    let c0 = 3u * indices[offsets[i]];
    origin = vec3<f32>(control[c0], control[c0 + 1u], control[c0 + 2u]);
  }
` : ''}  for (var k = offsets[i]; k < end; k++) {
    let c = 3u * indices[k];
    let v = vec3<f32>(control[c], control[c + 1u], control[c + 2u]);
    p += ${weight} * v;
${normals ? (merged
    ? '    let w1 = weights[3u * k + 1u];\n    let w2 = weights[3u * k + 2u];\n'
    : '    let w1 = tangents1[k];\n    let w2 = tangents2[k];\n')
    + '    t1 += w1 * (v - origin);\n    t2 += w2 * (v - origin);\n' : ''}  }
  positions[3u * i] = p.x;
  positions[3u * i + 1u] = p.y;
  positions[3u * i + 2u] = p.z;
${normals ? `  // cross(t1, t2) normalised; (0, 0, 0) when its length is 0 or not finite (tested on the bits:
  // a compiler may assume floats are finite).
  let n = cross(t1, t2);
  let len = sqrt(dot(n, n));
  var unit = vec3<f32>(0.0);
  if (len > 0.0 && (bitcast<u32>(len) & 0x7f800000u) != 0x7f800000u) {
    unit = n / len;
  }
  normals[3u * i] = unit.x;
  normals[3u * i + 1u] = unit.y;
  normals[3u * i + 2u] = unit.z;
` : ''}}
`;
}

// One pipeline per device and shader variant, shared by its evaluators.
const pipelines = new WeakMap();

function pipeline(device, normals, mergedWeights) {
  let cache = pipelines.get(device);
  if (!cache) pipelines.set(device, (cache = new Map()));
  const key = `${normals}/${mergedWeights}`;
  let result = cache.get(key);
  if (!result) {
    const module = device.createShaderModule({ label: 'subsurf stencils', code: stencilShader({ normals, mergedWeights }) });
    result = device.createComputePipeline({ label: 'subsurf stencils', layout: 'auto', compute: { module, entryPoint: 'main' } });
    cache.set(key, result);
  }
  return result;
}

/** How messages name table `k` of a list of `count`: not at all when it is the only one. */
function tableLabel(k, count) {
  return count > 1 ? `table ${k} of ${count}: ` : '';
}

/** Checks a table's arrays once, so that the shader never reads outside them. */
function checkTable(stencils, numControlVertices, which = '') {
  const where = `createGpuEvaluator: ${which}`.replace(/: $/, '');
  if (!stencils || typeof stencils !== 'object') {
    throw new Error(`${where}: the second argument must be an Evaluator (BaseMesh.evaluator()) or its stencils() ` +
      `{ offsets, indices, weights, tangentWeights? }, got ${describe(stencils)}`);
  }
  if (!Number.isInteger(numControlVertices) || numControlVertices < 0) {
    throw new Error(`${where}: numControlVertices must be a whole number >= 0 (the base mesh's vertex count), ` +
      `got ${describe(numControlVertices)}`);
  }
  const { offsets, indices, weights, tangentWeights } = stencils;
  const typed = (name, value, type) => {
    if (!(value instanceof type)) {
      throw new Error(`${where}: stencils.${name} must be a ${type.name}, got ${describe(value)}`);
    }
  };
  typed('offsets', offsets, Uint32Array);
  typed('indices', indices, Uint32Array);
  typed('weights', weights, Float32Array);
  if (offsets.length === 0) throw new Error(`${where}: stencils.offsets is empty; it needs numVertices + 1 entries starting at 0`);
  const numVertices = offsets.length - 1;
  const nnz = indices.length;
  if (weights.length !== nnz) {
    throw new Error(`${where}: stencils.weights has ${weights.length} entries and stencils.indices ${nnz}; they must be parallel`);
  }
  if (offsets[0] !== 0 || offsets[numVertices] !== nnz) {
    throw new Error(`${where}: stencils.offsets must start at 0 and end at indices.length (${nnz}), ` +
      `but runs from ${offsets[0]} to ${offsets[numVertices]}`);
  }
  for (let i = 0; i < numVertices; i++) {
    if (offsets[i + 1] < offsets[i]) {
      throw new Error(`${where}: stencils.offsets decreases at vertex ${i} (${offsets[i]} then ${offsets[i + 1]}); it must not`);
    }
  }
  for (let k = 0; k < nnz; k++) {
    if (indices[k] >= numControlVertices) {
      throw new Error(`${where}: stencils.indices[${k}] is ${indices[k]}, but there are only ${numControlVertices} ` +
        'control vertices; is numControlVertices right?');
    }
  }
  if (tangentWeights !== undefined) {
    if (!Array.isArray(tangentWeights) || tangentWeights.length !== 2) {
      throw new Error(`${where}: stencils.tangentWeights must be two Float32Arrays [du, dv], got ${describe(tangentWeights)}`);
    }
    tangentWeights.forEach((array, j) => {
      typed(`tangentWeights[${j}]`, array, Float32Array);
      if (array.length !== nnz) {
        throw new Error(`${where}: stencils.tangentWeights[${j}] has ${array.length} entries and stencils.indices ${nnz}; ` +
          'they must be parallel');
      }
    });
    tangentWeights.forEach((array, j) => {
      // The shader sums w * (v - v0), v0 the row's first control point: sum(w * v) only for
      // weights that sum to 0, as a derivative's do (to rounding: 1e-6 of their size in our
      // tables and OpenSubdiv's).
      for (let i = 0; i < numVertices; i++) {
        let sum = 0;
        let size = 0;
        for (let k = offsets[i]; k < offsets[i + 1]; k++) {
          sum += array[k];
          size += Math.abs(array[k]);
        }
        if (Math.abs(sum) > 1e-4 * size) {
          throw new Error(`${where}: stencils.tangentWeights[${j}] sums to ${sum} in row ${i} (entries ${offsets[i]}..${offsets[i + 1]}); ` +
            "tangent weights must sum to 0 in each row, as a limit tangent's do (Evaluator.stencils() and OpenSubdiv's LimitStencilTable are so)");
        }
      }
    });
  }
  return { numVertices, numInputs: numControlVertices, offsets, indices, weights, tangentWeights };
}

function isGpuBuffer(value) {
  if (typeof GPUBuffer === 'function') return value instanceof GPUBuffer;
  return !!value && typeof value === 'object' && typeof value.mapAsync === 'function' && typeof value.usage === 'number';
}

function describe(value) {
  if (value === null) return 'null';
  if (Array.isArray(value)) return `an Array of length ${value.length}`;
  if (ArrayBuffer.isView(value)) return `a ${value.constructor.name} of length ${value.length}`;
  if (typeof value === 'object') return `an object (${value.constructor?.name ?? 'Object'})`;
  if (value === undefined) return 'undefined';
  if (typeof value === 'string') return `the string ${JSON.stringify(value)}`;
  return `the ${typeof value} ${String(value)}`;
}

/** The largest coordinate the evaluators take: subsurf's `MAX_COORDINATE`, the f32 nearest 1e30 (f32 sums of larger ones overflow). */
const MAX_COORDINATE = Math.fround(1e30);

/** Throws, naming the first, on a control value that is NaN, infinite or beyond ±1e30 (the wasm evaluator's rule). */
function checkCoordinates(control) {
  for (let i = 0; i < control.length; i++) {
    const x = control[i];
    if (Math.abs(x) <= MAX_COORDINATE) continue;
    const why = Number.isFinite(x)
      ? 'every coordinate must be within ±1e30, as larger ones overflow f32 in the sums; scale them down'
      : 'every coordinate must be a finite number';
    throw new Error(`GpuEvaluator.evaluate: control[${i}] (vertex ${Math.floor(i / 3)}, ${'xyz'[i % 3]}) is ${x}; ${why}`);
  }
}
