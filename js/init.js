// subsurf with an explicit init (the package's './init' export, for places without top-level
// await): `import init, { subdivide } from 'subsurf/init'; await init();`. The glue itself
// (subsurf.js) plus the clear message for calls on freed objects (freed.js), with its two
// loaders' failures said plainly where the engine lacks what subsurf needs (support.js).
import './freed.js';
import glueInit, { initSync as glueInitSync } from './subsurf.js';
import { explained, moduleUrl } from './support.js';

export * from './subsurf.js';

/**
 * The glue's `init`: loads and instantiates the module (see subsurf.d.ts). Given no module, it
 * loads support.js's `moduleUrl()`: subsurf_nosimd.wasm on an engine without WebAssembly SIMD.
 */
export default async function init(...args) {
  const given = args[0] !== null && typeof args[0] === 'object' && Object.getPrototypeOf(args[0]) === Object.prototype
    ? args[0].module_or_path
    : args[0];
  if (given === undefined) {
    args = [{ ...args[0], module_or_path: moduleUrl() }];
  }
  try {
    return await glueInit(...args);
  } catch (error) {
    throw explained(error);
  }
}

/** The glue's `initSync`: instantiates the module from its bytes or a compiled Module. */
export function initSync(...args) {
  try {
    return glueInitSync(...args);
  } catch (error) {
    throw explained(error);
  }
}
