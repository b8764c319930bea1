import { readFileSync } from 'node:fs';
import { initSync } from './subsurf.js';
import './freed.js';
import { explained, moduleUrl } from './support.js';

try {
  initSync({ module: readFileSync(moduleUrl()) });
} catch (error) {
  throw explained(error);
}

export * from './subsurf.js';
// Code written for browsers (`import init from 'subsurf'; await init();`) runs unchanged: the
// module is initialised already, and init() then returns at once.
export { default } from './subsurf.js';
