// subsurf/three in Node (the "node" condition of the package's "./three" export): loads the
// .wasm synchronously first, as subsurf/node does, so no init() call is needed.
import './node.js';

export * from './three.js';
