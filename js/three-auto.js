// subsurf/three for browsers and bundlers (the "default" condition of the package's "./three"
// export): initialises the WebAssembly module first (auto.js, a top-level `await init()`), so
// subdivideGeometry works with no init call. Node takes three-node.js; 'subsurf/three/init'
// (three.js) is the entry that leaves init() to the caller.
import './auto.js';

export * from './three.js';
