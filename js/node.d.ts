/* The subsurf API, already initialised: no init() call needed in Node. */
export * from './subsurf.js';
