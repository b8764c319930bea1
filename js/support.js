// What subsurf needs of the JavaScript engine. The module (subsurf_bg.wasm) is built with
// WebAssembly SIMD (simd128); for engines without it (Safari before 16.4, the last Safari of
// some iPhones among them) the package has the same library built without SIMD
// (subsurf_nosimd.wasm, same glue, slower), which the entries load where `hasSimd()` says no
// (`moduleUrl()`).
// Where loading still fails, the entries pass the error through `explained`, so that it says
// what the engine lacks instead of naming an opcode.

/** The smallest module that uses a v128: `(func (result v128) (v128.const i32x4 0 0 0 0))`. */
const SIMD_PROBE = new Uint8Array([
  0, 97, 115, 109, 1, 0, 0, 0, // magic, version
  1, 5, 1, 96, 0, 1, 123, // one type: () -> v128
  3, 2, 1, 0, // one function of it
  10, 22, 1, 20, 0, 253, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 11, // v128.const 0
]);

/** The engines that run subsurf_bg.wasm, and those that run subsurf_nosimd.wasm. */
const SIMD_ENGINES = 'Chrome 91, Edge 91, Firefox 89, Safari 16.4, Node 16.4 or later';
const ENGINES = 'Chrome 75, Edge 79, Firefox 79, Safari 15 or later';

function hasWebAssembly() {
  return typeof WebAssembly === 'object' && typeof WebAssembly.validate === 'function';
}

/** Whether this engine runs WebAssembly SIMD: which of the package's two modules it loads. */
export function hasSimd() {
  return hasWebAssembly() && WebAssembly.validate(SIMD_PROBE);
}

/** The file name of the module this engine loads, as the package ships it (a bundler may rename the asset). */
export function moduleFile() {
  return hasSimd() ? 'subsurf_bg.wasm' : 'subsurf_nosimd.wasm';
}

/**
 * The URL of the module this engine loads: subsurf_bg.wasm, or subsurf_nosimd.wasm without
 * SIMD. Each URL is written literally, `new URL('./file', import.meta.url)`, so that Vite and
 * webpack emit both files as assets.
 */
export function moduleUrl() {
  return hasSimd() ? new URL('./subsurf_bg.wasm', import.meta.url) : new URL('./subsurf_nosimd.wasm', import.meta.url);
}

/**
 * The error to throw for `error`, raised while loading subsurf's module: one that says what the
 * engine lacks (with `error` as its cause) when it lacks something, else `error` itself.
 */
export function explained(error) {
  if (!hasWebAssembly()) {
    return new Error(`subsurf needs WebAssembly, which this JavaScript environment does not have: use ${ENGINES}`, { cause: error });
  }
  // Only a module that does not compile or link is the engine's doing; a fetch that failed (an
  // HTTP 404) keeps its own message, which says where and what to do.
  const fromModule = error instanceof WebAssembly.CompileError || error instanceof WebAssembly.LinkError;
  if (fromModule && !hasSimd()) {
    return new Error('subsurf could not load its module on this engine, which does not run WebAssembly SIMD. ' +
      'Such engines need subsurf_nosimd.wasm (the entries load it by themselves; pass its URL or bytes where you ' +
      `give init() or initSync() a module), which runs on ${ENGINES}; subsurf_bg.wasm needs ${SIMD_ENGINES}`, { cause: error });
  }
  return error;
}
