// subsurf with an explicit init (the package's './init' export, for places without top-level
// await): `import init, { subdivide } from 'subsurf/init'; await init();`. The glue itself
// (subsurf.js) plus the clear message for calls on freed objects (freed.js), with its two
// loaders' failures said plainly where the engine lacks what subsurf needs (support.js).
import './freed.js';
import glueInit, { initSync as glueInitSync } from './subsurf.js';
import { explained } from './support.js';

export * from './subsurf.js';

/** The glue's `init`: loads and instantiates the module (see subsurf.d.ts). */
export default async function init(...args) {
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
