// A TypeScript consumer of subsurf/webgpu with the WebGPU typings a WebGPU app has
// (@webgpu/types, pinned in package.json): tests/js/pkg_smoke.mjs type-checks it with the pinned
// `tsc` (strict, no skipLibCheck). The evaluator's buffers must be the real GPUBuffer type (they
// go straight into a render pass) and its device the real GPUDevice. Each `@ts-expect-error`
// marks a misuse the types must refuse.
/// <reference types="@webgpu/types" />
import { BaseMesh } from 'subsurf';
import { createGpuEvaluator, requestGpuDevice, stencilShader, type GpuEvaluator, type GpuReadBack, type StencilArrays } from 'subsurf/webgpu';

const device: GPUDevice = await requestGpuDevice({ adapter: { powerPreference: 'high-performance' } });
const stencils: StencilArrays = {
  offsets: new Uint32Array([0, 1]),
  indices: new Uint32Array([0]),
  weights: new Float32Array([1]),
  tangentWeights: [new Float32Array([1]), new Float32Array([0])],
};
const gpu: GpuEvaluator = createGpuEvaluator(device, stencils, 1);
// What BaseMesh.evaluator() returns has stencils() and numControlVertices.
const fromEvaluator = createGpuEvaluator(device, { numControlVertices: 1, stencils: () => stencils });
// What Evaluator.stencils() returns carries numControlVertices.
const fromArrays = createGpuEvaluator(device, { ...stencils, numControlVertices: 1 });
// The wasm Evaluator itself, and its arrays.
const base = new BaseMesh({ positions: new Float32Array(9), indices: new Uint32Array([0, 1, 2]) });
const evaluator = base.evaluator({ levels: 2, limit: true, normals: true });
const fromWasm: GpuEvaluator = createGpuEvaluator(device, evaluator);
const fromWasmArrays: GpuEvaluator = createGpuEvaluator(device, evaluator.stencils());
// The tables level by level: a list, run in turn.
const levels: StencilArrays[] = evaluator.levelStencils();
const fromLevels: GpuEvaluator = createGpuEvaluator(device, levels, evaluator.numControlVertices);

gpu.evaluate(new Float32Array(3));
const control: GPUBuffer = device.createBuffer({ size: 12, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
const encoder: GPUCommandEncoder = device.createCommandEncoder();
gpu.evaluate(control, encoder);
const pass = encoder.beginRenderPass({ colorAttachments: [] });
pass.setVertexBuffer(0, gpu.positions);
if (gpu.normals) pass.setVertexBuffer(1, gpu.normals);
pass.end();
device.queue.submit([encoder.finish()]);
const back: GpuReadBack = await gpu.readBack();
const normals: Float32Array | undefined = back.normals;
const counts: number = gpu.numVertices + gpu.numControlVertices;
const same: GPUDevice = gpu.device;
const wgsl: string = stencilShader({ normals: true });
gpu.destroy();
fromEvaluator.destroy();
fromArrays.destroy();
fromWasm.destroy();
fromWasmArrays.destroy();
fromLevels.destroy();

// @ts-expect-error: control must be a Float32Array or a GPUBuffer
gpu.evaluate(new Float64Array(3));
// @ts-expect-error: a table needs numControlVertices
createGpuEvaluator(device, stencils);
// @ts-expect-error: the output buffers are read-only
gpu.positions = control;
// @ts-expect-error: weights must be a Float32Array
createGpuEvaluator(device, { ...stencils, weights: [1] }, 1);

export const used = [back, normals, counts, same, wgsl];
