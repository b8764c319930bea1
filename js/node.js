import { readFileSync } from 'node:fs';
import { initSync } from './subsurf.js';
import './freed.js';
import { explained, hasSimd } from './support.js';

try {
  // Without WebAssembly SIMD, the same library built without it (support.js).
  const file = hasSimd() ? './subsurf_bg.wasm' : './subsurf_nosimd.wasm';
  initSync({ module: readFileSync(new URL(file, import.meta.url)) });
} catch (error) {
  throw explained(error);
}

export * from './subsurf.js';
// Code written for browsers (`import init from 'subsurf'; await init();`) runs unchanged: the
// module is initialised already, and init() then returns at once.
export { default } from './subsurf.js';
