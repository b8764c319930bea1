// subsurf for browsers and bundlers (the "default" condition of the package's "." export):
// initialises the WebAssembly module with a top-level `await init()`, so that
//   import { subdivide } from 'subsurf';
// works with no init call in Vite, webpack 5 and a plain <script type="module"> page. The glue
// finds its .wasm as `new URL('subsurf_bg.wasm', import.meta.url)`, which bundlers turn into an
// asset; an engine without WebAssembly SIMD gets subsurf_nosimd.wasm instead, written the same
// way here (support.js). Code written for the explicit form (`import init from 'subsurf'; await
// init();`) runs unchanged: init() then returns the module at once. Where top-level await is not
// available, the explicit entry is 'subsurf/init' (init.js).
import init from './subsurf.js';
import './freed.js';
import { explained, hasSimd } from './support.js';

try {
  await init(hasSimd() ? undefined : { module_or_path: new URL('./subsurf_nosimd.wasm', import.meta.url) });
} catch (error) {
  throw explained(error);
}

export * from './subsurf.js';
export { default } from './subsurf.js';
