// What subsurf needs of the JavaScript engine, said plainly when it is missing. The module is
// built with WebAssembly SIMD (simd128): an engine without it (Safari before 16.4, as on
// iPhones that stay on iOS 15) fails the compilation with a message about an opcode, which
// tells a user nothing. The entries that load the module pass their error through
// `explained`, so the failure names what is missing and which engines have it.

/** The smallest module that uses a v128: `(func (result v128) (v128.const i32x4 0 0 0 0))`. */
const SIMD_PROBE = new Uint8Array([
  0, 97, 115, 109, 1, 0, 0, 0, // magic, version
  1, 5, 1, 96, 0, 1, 123, // one type: () -> v128
  3, 2, 1, 0, // one function of it
  10, 22, 1, 20, 0, 253, 12, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 11, // v128.const 0
]);

const ENGINES = 'Chrome 91, Edge 91, Firefox 89, Safari 16.4, Node 16.4 or later';

/** What this engine lacks of what subsurf needs, or null when it has it all. */
export function missingSupport() {
  if (typeof WebAssembly !== 'object' || typeof WebAssembly.validate !== 'function') {
    return `subsurf needs WebAssembly, which this JavaScript environment does not have: use ${ENGINES}`;
  }
  if (!WebAssembly.validate(SIMD_PROBE)) {
    return `subsurf needs WebAssembly SIMD (simd128), which this engine does not run: use ${ENGINES}`;
  }
  return null;
}

/**
 * The error to throw for `error`, raised while loading subsurf's module: one that says what
 * the engine lacks (with `error` as its cause) when it lacks something, else `error` itself.
 */
export function explained(error) {
  const missing = missingSupport();
  return missing ? new Error(missing, { cause: error }) : error;
}
