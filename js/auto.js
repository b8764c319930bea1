// subsurf for browsers and bundlers (the "default" condition of the package's "." export):
// initialises the WebAssembly module with a top-level `await init()`, so that
//   import { subdivide } from 'subsurf';
// works with no init call in Vite, webpack 5 and a plain <script type="module"> page. The glue
// is given its .wasm by support.js's `moduleUrl()`, written `new URL('./file', import.meta.url)`,
// which bundlers turn into an asset: subsurf_bg.wasm, or subsurf_nosimd.wasm on an engine
// without WebAssembly SIMD. Code written for the explicit form (`import init from 'subsurf'; await
// init();`) runs unchanged: init() then returns the module at once. Where top-level await is not
// available, the explicit entry is 'subsurf/init' (init.js).
import init from './subsurf.js';
import './freed.js';
import { explained, moduleUrl } from './support.js';

try {
  await init({ module_or_path: moduleUrl() });
} catch (error) {
  throw explained(error);
}

export * from './subsurf.js';
export { default } from './subsurf.js';
