// subsurf with an explicit init (the package's './init' export, for places without top-level
// await): `import init, { subdivide } from 'subsurf/init'; await init();`. The glue itself
// (subsurf.js) plus the clear message for calls on freed objects (freed.js).
import './freed.js';

export * from './subsurf.js';
export { default } from './subsurf.js';
