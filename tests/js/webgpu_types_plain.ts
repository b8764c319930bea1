// subsurf/webgpu's declarations in a project without WebGPU typings (TypeScript's lib.dom has
// none yet): they must compile on their own (strict, no skipLibCheck), with stand-in types for
// the device and buffers. tests/js/pkg_smoke.mjs type-checks this file with types_check.ts.
import { createGpuEvaluator, requestGpuDevice } from 'subsurf/webgpu';

const device = await requestGpuDevice();
const gpu = createGpuEvaluator(device, { offsets: new Uint32Array([0, 0]), indices: new Uint32Array(0), weights: new Float32Array(0) }, 1);
gpu.evaluate(new Float32Array(3));
const size: number = gpu.positions.size;
const positions: Float32Array = (await gpu.readBack()).positions;
gpu.destroy();

// @ts-expect-error: control must be a Float32Array or a GPUBuffer
gpu.evaluate([0, 0, 0]);

export const used = [size, positions];
