// A TypeScript consumer of subsurf/three: tests/js/three.mjs copies it beside the installed
// package, three and @types/three, and type-checks it with the pinned tsc (strict, no
// skipLibCheck). Each `@ts-expect-error` marks a misuse the types must refuse.
import * as THREE from 'three';
import type { SubdivideProgress } from 'subsurf';
import { subdivideGeometry, subdivideGeometryAsync, type SubdivideGeometryCall, type SubdivideGeometryOptions } from 'subsurf/three';
import { createWorker } from 'subsurf/worker';

const geometry = new THREE.TorusKnotGeometry(1, 0.3, 64, 8);
const smooth: THREE.BufferGeometry = subdivideGeometry(geometry, { levels: 2 });
const options: SubdivideGeometryOptions = {
  scheme: 'catmull-clark',
  levels: 2,
  quads: { faceAngle: 0.7 },
  weld: 1e-5,
  creaseAngle: Math.PI / 6,
  sharpNormalSplits: true,
  normals: 'faces',
  limit: true,
  fvarLinear: 'boundaries',
  creases: { edges: new Uint32Array([0, 1]), sharpness: new Float32Array([10]) },
};
const mesh = new THREE.Mesh(subdivideGeometry(smooth, options), new THREE.MeshStandardMaterial());
subdivideGeometry(mesh.geometry, { quads: true, normals: false });

const worker = createWorker();
const controller = new AbortController();
const call: SubdivideGeometryCall = { worker, signal: controller.signal, onProgress: (p: SubdivideProgress) => console.log(p.level, p.levels) };
const later: Promise<THREE.BufferGeometry> = subdivideGeometryAsync(geometry, options, call);
subdivideGeometryAsync(geometry, undefined, { worker }).then((g) => g.dispose());
void later;
worker.terminate();

// @ts-expect-error the worker is required
subdivideGeometryAsync(geometry, { levels: 2 });
// @ts-expect-error the worker is a SubsurfWorker, not a Worker's script URL
subdivideGeometryAsync(geometry, { levels: 2 }, { worker: 'worker.js' });
// @ts-expect-error normals is true, false or 'faces'
subdivideGeometry(geometry, { normals: 'limit' });
// @ts-expect-error a Mesh is not a BufferGeometry
subdivideGeometry(mesh);
// @ts-expect-error levels is a number
subdivideGeometry(geometry, { levels: '2' });
