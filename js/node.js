import { readFileSync } from 'node:fs';
import { initSync } from './subsurf.js';

initSync({ module: readFileSync(new URL('./subsurf_bg.wasm', import.meta.url)) });

export * from './subsurf.js';
