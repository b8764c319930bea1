// A TypeScript consumer of subsurf/three: tests/js/three.mjs copies it beside the installed
// package, three and @types/three, and type-checks it with the pinned tsc (strict, no
// skipLibCheck). Each `@ts-expect-error` marks a misuse the types must refuse.
import * as THREE from 'three';
import { subdivideGeometry, type SubdivideGeometryOptions } from 'subsurf/three';

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

// @ts-expect-error normals is true, false or 'faces'
subdivideGeometry(geometry, { normals: 'limit' });
// @ts-expect-error a Mesh is not a BufferGeometry
subdivideGeometry(mesh);
// @ts-expect-error levels is a number
subdivideGeometry(geometry, { levels: '2' });
