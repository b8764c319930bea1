// Tests of subsurf/three (subdivideGeometry) with real three.js, on the built package in pkg/
// (run scripts/build-pkg.sh first):   node tests/js/three.mjs
// Installs pkg/'s `files` into a temporary node_modules/subsurf beside the pinned three (a
// devDependency, symlinked), imports 'subsurf/three' as a Node user would (its "node" export
// condition loads the wasm), and checks: glTF-style seam-split shapes (as BufferGeometry, and
// written as .glb files read back by three's GLTFLoader) against `subdivide` on the original
// indexed meshes (positions, UVs, normals; position-keyed), quads recovered from
// triangulated quad meshes, watertightness, non-indexed and interleaved input, welding by
// distance, skin weights, morph targets, groups, creases, errors, input left unchanged, and
// the TypeScript declarations (tsc on tests/js/three_types_check.ts with @types/three).
// Exits non-zero on the first failure.
//   node tests/js/three.mjs --three node_modules/three-r150   runs it with another three (the
//   oldest of the peer range, a devDependency alias), without the tsc check (@types/three follows
//   the current three).

import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { cpSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { checks, installPackage, root, triangulated } from './common.mjs';

const { check, finish } = checks('three');

// ---- install the package beside three, as a user's project has them
const threeArg = process.argv.indexOf('--three');
const threeDir = threeArg > 0 ? join(root, process.argv[threeArg + 1]) : join(root, 'node_modules', 'three');
const { scratch, installed, manifest: pkg, consumer } = await installPackage({
  prefix: 'subsurf-three-',
  links: { three: threeDir, '@types/three': join(root, 'node_modules', '@types', 'three') },
  consumer: "export * as THREE from 'three';\nexport { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';\n" +
    "export { subdivideGeometry, subdivideGeometryAsync } from 'subsurf/three';\nexport * as subsurf from 'subsurf/node';\n" +
    "export { createWorker } from 'subsurf/worker';\n",
});
const { THREE, GLTFLoader, subdivideGeometry, subdivideGeometryAsync, createWorker, subsurf } = consumer;
const { shape, subdivide, toDrawable } = subsurf;
const threeVersion = JSON.parse(readFileSync(join(threeDir, 'package.json'), 'utf8')).version;

await check('package.json: ./three export, peer dependency', () => {
  assert.deepEqual(pkg.exports['./three'], { types: './three.d.ts', node: './three-node.js', default: './three-auto.js' });
  assert.deepEqual(pkg.exports['./three/init'], { types: './three.d.ts', default: './three.js' });
  assert.ok(pkg.peerDependencies.three, 'three is a peer dependency');
  assert.equal(pkg.peerDependenciesMeta.three.optional, true);
});

// ---- helpers

/**
 * A polygon mesh with a face-varying uv channel as glTF stores it: triangles, one vertex per
 * distinct (vertex, uv index) corner. `diagonal(f)` picks 0 (corners 0-2) or 1 (1-3) per quad;
 * other polygons are fans.
 */
function gltfGeometry(mesh, { diagonal = () => 0 } = {}) {
  const uv = mesh.attributes.uv;
  const vertexOf = new Map();
  const positions = [], uvs = [], index = [];
  const vertex = (c) => {
    const v = mesh.indices[c], t = uv.indices[c];
    const key = `${v}/${t}`;
    if (!vertexOf.has(key)) {
      vertexOf.set(key, positions.length / 3);
      positions.push(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
      uvs.push(uv.array[2 * t], uv.array[2 * t + 1]);
    }
    return vertexOf.get(key);
  };
  let c = 0;
  for (let f = 0; f < mesh.faceSizes.length; f++) {
    const n = mesh.faceSizes[f];
    const ids = [];
    for (let i = 0; i < n; i++) ids.push(vertex(c + i));
    const r = n === 4 ? diagonal(f) : 0;
    for (let i = 1; i + 1 < n; i++) index.push(ids[r], ids[(r + i) % n], ids[(r + i + 1) % n]);
    c += n;
  }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
  g.setAttribute('uv', new THREE.Float32BufferAttribute(uvs, 2));
  g.setIndex(index);
  return g;
}

/** subdivide's result made drawable: per drawn vertex, position, uv and (with normals) normal. */
function reference(mesh, options) {
  const out = subdivide(mesh, options);
  const draw = toDrawable(out);
  const result = { positions: draw.positions, uv: draw.attributes.uv?.array, triangles: draw.triangles.length / 3 };
  if (out.normals) {
    result.normals = new Float32Array(draw.positions.length);
    draw.origins.forEach((o, d) => result.normals.set(out.normals.subarray(3 * o, 3 * o + 3), 3 * d));
  }
  return result;
}

function extent(positions) {
  let m = 0;
  for (const x of positions) m = Math.max(m, Math.abs(x));
  return m;
}

/**
 * Position-keyed comparison: every drawn vertex of `a` has one in `b` at the same position
 * (within eps) with the same values of each channel named in `fields` (within eps), and the
 * counts agree. Returns the largest difference seen.
 */
function sameVertices(a, b, fields, eps) {
  const n = a.positions.length / 3;
  assert.equal(b.positions.length / 3, n, 'vertex counts');
  const cell = 4 * eps;
  const grid = new Map();
  const key = (x, y, z) => `${Math.floor(x / cell)},${Math.floor(y / cell)},${Math.floor(z / cell)}`;
  for (let i = 0; i < n; i++) {
    const k = key(b.positions[3 * i], b.positions[3 * i + 1], b.positions[3 * i + 2]);
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(i);
  }
  let worst = 0;
  const used = new Uint8Array(n);
  for (let i = 0; i < n; i++) {
    const [x, y, z] = a.positions.subarray(3 * i, 3 * i + 3);
    let best = -1, bestD = Infinity;
    const cx = Math.floor(x / cell), cy = Math.floor(y / cell), cz = Math.floor(z / cell);
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      for (const j of grid.get(`${cx + dx},${cy + dy},${cz + dz}`) ?? []) {
        if (used[j]) continue;
        let d = Math.max(Math.abs(b.positions[3 * j] - x), Math.abs(b.positions[3 * j + 1] - y), Math.abs(b.positions[3 * j + 2] - z));
        for (const [field, size] of fields) {
          for (let k = 0; k < size; k++) d = Math.max(d, Math.abs(a[field][size * i + k] - b[field][size * j + k]));
        }
        if (d < bestD) {
          best = j;
          bestD = d;
        }
      }
    }
    assert.ok(best >= 0 && bestD <= eps, `vertex ${i} at (${x}, ${y}, ${z}) has no match (closest differs by ${bestD})`);
    used[best] = 1;
    worst = Math.max(worst, bestD);
  }
  return worst;
}

function drawn(geometry) {
  const result = {
    positions: geometry.getAttribute('position').array,
    triangles: geometry.index.count / 3,
  };
  if (geometry.getAttribute('uv')) result.uv = geometry.getAttribute('uv').array;
  if (geometry.getAttribute('normal')) result.normals = geometry.getAttribute('normal').array;
  return result;
}

/** Edges by position (bit patterns): every one used by exactly two triangles, opposite ways. */
function assertWatertight(geometry) {
  const p = geometry.getAttribute('position').array;
  const bits = new Uint32Array(p.buffer, p.byteOffset, p.length);
  const ids = new Map();
  const id = (v) => {
    const k = `${bits[3 * v]},${bits[3 * v + 1]},${bits[3 * v + 2]}`;
    if (!ids.has(k)) ids.set(k, ids.size);
    return ids.get(k);
  };
  const index = geometry.index.array;
  const uses = new Map();
  for (let t = 0; t < index.length; t += 3) {
    for (let j = 0; j < 3; j++) {
      const a = id(index[t + j]), b = id(index[t + ((j + 1) % 3)]);
      assert.notEqual(a, b, `triangle ${t / 3} is degenerate`);
      const k = a < b ? `${a},${b}` : `${b},${a}`;
      uses.set(k, (uses.get(k) ?? 0) + (a < b ? 1 : 16));
    }
  }
  let bad = 0;
  for (const count of uses.values()) if (count !== 17) bad++;
  assert.equal(bad, 0, `${bad} of ${uses.size} edges are not used once each way`);
  return uses.size;
}

function snapshot(geometry) {
  const arrays = [geometry.index?.array, ...Object.values(geometry.attributes).map((a) => a.array ?? a.data.array)];
  for (const list of Object.values(geometry.morphAttributes)) for (const a of list) arrays.push(a.array);
  return {
    arrays: arrays.filter(Boolean).map((a) => a.slice()),
    live: arrays.filter(Boolean),
    names: Object.keys(geometry.attributes).join(),
    groups: JSON.stringify(geometry.groups),
  };
}
function assertUnchanged(geometry, before) {
  const now = snapshot(geometry);
  assert.equal(now.names, before.names, 'attribute names unchanged');
  assert.equal(now.groups, before.groups, 'groups unchanged');
  now.live.forEach((a, i) => assert.deepEqual(a, before.arrays[i], `array ${i} unchanged`));
}

/** A binary glTF (.glb) of one triangle primitive: POSITION, TEXCOORD_0 and 32-bit indices. */
function glb(positions, uvs, indices) {
  const views = [positions, uvs, indices];
  const bin = new Uint8Array(views.reduce((n, a) => n + a.byteLength, 0));
  let offset = 0;
  const bufferViews = views.map((a, i) => {
    bin.set(new Uint8Array(a.buffer, a.byteOffset, a.byteLength), offset);
    offset += a.byteLength;
    return { buffer: 0, byteOffset: offset - a.byteLength, byteLength: a.byteLength, target: i < 2 ? 34962 : 34963 };
  });
  const min = [0, 1, 2].map((k) => Math.min(...positions.filter((_, i) => i % 3 === k)));
  const max = [0, 1, 2].map((k) => Math.max(...positions.filter((_, i) => i % 3 === k)));
  const json = {
    asset: { version: '2.0' }, scene: 0, scenes: [{ nodes: [0] }], nodes: [{ mesh: 0 }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2 }] }],
    buffers: [{ byteLength: bin.byteLength }],
    bufferViews,
    accessors: [
      { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5126, count: uvs.length / 2, type: 'VEC2' },
      { bufferView: 2, componentType: 5125, count: indices.length, type: 'SCALAR' },
    ],
  };
  const pad = (bytes, fill) => {
    const out = new Uint8Array(Math.ceil(bytes.length / 4) * 4).fill(fill);
    out.set(bytes);
    return out;
  };
  const text = pad(new TextEncoder().encode(JSON.stringify(json)), 0x20), body = pad(bin, 0);
  const file = new Uint8Array(28 + text.length + body.length);
  const view = new DataView(file.buffer);
  view.setUint32(0, 0x46546c67, true); // 'glTF'
  view.setUint32(4, 2, true);
  view.setUint32(8, file.length, true);
  view.setUint32(12, text.length, true);
  view.setUint32(16, 0x4e4f534a, true); // 'JSON'
  file.set(text, 20);
  view.setUint32(20 + text.length, body.length, true);
  view.setUint32(24 + text.length, 0x004e4942, true); // 'BIN'
  file.set(body, 28 + text.length);
  return file.buffer;
}

/** The geometry of a .glb's first mesh, as GLTFLoader reads it. */
function loadGlb(buffer) {
  return new Promise((resolve, reject) => new GLTFLoader().parse(buffer, '', (gltf) => resolve(gltf.scene.children[0].geometry), reject));
}

// ---- glTF-style seam-split shapes against subdivide on the original meshes
for (const name of ['cube', 'torus', 'house']) {
  await check(`${name}: written as a .glb (seams split), read by GLTFLoader, = subdivide on the original`, async () => {
    const mesh = shape(name);
    const split = gltfGeometry(mesh);
    const geometry = await loadGlb(glb(split.getAttribute('position').array, split.getAttribute('uv').array, Uint32Array.from(split.index.array)));
    assert.ok(geometry.isBufferGeometry && geometry.getAttribute('uv'));
    const quads = name !== 'house'; // the house's triangles are its own, not halves of quads
    const out = subdivideGeometry(geometry, { levels: 2, quads, limit: true });
    const ref = reference(quads ? mesh : triangulated(mesh), { levels: 2, limit: true, normals: true });
    sameVertices(ref, drawn(out), [['uv', 2], ['normals', 3]], 2e-5 * extent(mesh.positions));
    assertWatertight(out);
  });
}

const quadShapes = ['cube', 'torus'];
for (const name of quadShapes) {
  const mesh = shape(name);
  const eps = 2e-6 * extent(mesh.positions) * 8;
  for (const [label, diagonal] of [['diagonals 0-2', () => 0], ['alternating diagonals', (f) => f % 2]]) {
    await check(`${name}, ${label}, quads: true, level 2 = Catmull-Clark on the quad mesh`, () => {
      const geometry = gltfGeometry(mesh, { diagonal });
      const before = snapshot(geometry);
      const out = subdivideGeometry(geometry, { levels: 2, quads: true, normals: false });
      assertUnchanged(geometry, before);
      assert.equal(out.index.count / 3, 2 * 16 * mesh.faceSizes.length, 'triangles: 2 per level-2 quad');
      const ref = reference(mesh, { levels: 2 });
      sameVertices(ref, drawn(out), [['uv', 2]], eps);
      assertWatertight(out);
      assert.equal(out.getAttribute('normal'), undefined, 'normals: false');
    });
  }
  await check(`${name}: quads, limit and limit normals = subdivide's`, () => {
    const out = subdivideGeometry(gltfGeometry(mesh), { levels: 3, quads: true, limit: true });
    const ref = reference(mesh, { levels: 3, limit: true, normals: true });
    sameVertices(ref, drawn(out), [['uv', 2], ['normals', 3]], eps);
    assertWatertight(out);
  });
  await check(`${name}: non-indexed input = indexed`, () => {
    const indexed = gltfGeometry(mesh);
    const plain = indexed.toNonIndexed();
    assert.equal(plain.index, null);
    const a = subdivideGeometry(indexed, { levels: 2, quads: true });
    const b = subdivideGeometry(plain, { levels: 2, quads: true });
    sameVertices(drawn(a), drawn(b), [['uv', 2], ['normals', 3]], eps);
  });
}

for (const name of subsurf.shapeNames()) {
  const mesh = shape(name);
  const eps = 2e-6 * extent(mesh.positions) * 8;
  await check(`${name}: triangles (no quads), Catmull-Clark level 2, fvarLinear 'none' and 'all' = subdivide on the triangulated mesh`, () => {
    const geometry = gltfGeometry(mesh);
    for (const fvarLinear of ['none', 'corners-plus1', 'all']) {
      const out = subdivideGeometry(geometry, { levels: 2, fvarLinear });
      const ref = reference(triangulated(mesh), { levels: 2, fvarLinear, normals: true });
      sameVertices(ref, drawn(out), [['uv', 2], ['normals', 3]], eps);
      assert.equal(drawn(out).triangles, ref.triangles);
    }
  });
  await check(`${name}: Loop level 2 = subdivide on the triangulated mesh`, () => {
    const out = subdivideGeometry(gltfGeometry(mesh), { scheme: 'loop', levels: 2, limit: true });
    const ref = reference(triangulated(mesh), { scheme: 'loop', levels: 2, limit: true, normals: true });
    sameVertices(ref, drawn(out), [['uv', 2], ['normals', 3]], eps);
  });
  await check(`${name}: watertight where the input is closed by position`, () => {
    const open = name === 'sheet-with-holes';
    const out = subdivideGeometry(gltfGeometry(mesh), { levels: 2, quads: true });
    if (!open) assertWatertight(out);
    else assert.throws(() => assertWatertight(out), /edges are not used once each way/);
  });
}

// A hub with a UV per face: three.js's ConeGeometry gives its apex a copy per segment, each with
// its own u. subdivideGeometry groups a welded vertex's copies by value; with more than a few
// copies it sorts them (pairwise, a cone of 100k segments took two minutes). Our mesh of that
// layout (tests/meshes/own_cone_uv.obj, 80 segments; OpenSubdiv fixtures in tests/fixtures/osd*)
// split as glTF splits it, against subdivide on the original mesh triangulated.
await check('a cone with a UV per face at its 80-face apex (as ConeGeometry lays them): Catmull-Clark and Loop level 2 = subdivide on the triangulated mesh', () => {
  const mesh = subsurf.readObj(readFileSync(join(root, 'tests/meshes/own_cone_uv.obj'), 'utf8'));
  const apexUvs = new Set();
  mesh.indices.forEach((v, c) => { if (v === 0) apexUvs.add(mesh.attributes.uv.indices[c]); });
  assert.equal(apexUvs.size, 80, 'a UV per face at the apex');
  const eps = 2e-6 * extent(mesh.positions) * 8;
  for (const scheme of ['catmull-clark', 'loop']) {
    const out = subdivideGeometry(gltfGeometry(mesh), { scheme, levels: 2, limit: true });
    const ref = reference(triangulated(mesh), { scheme, levels: 2, limit: true, normals: true });
    sameVertices(ref, drawn(out), [['uv', 2], ['normals', 3]], eps);
    assertWatertight(out);
  }
});

// three's own geometries: seams (UV splits), poles and, for the cylinder, caps. TorusKnotGeometry
// repeats its seam positions bit for bit; SphereGeometry and CylinderGeometry compute theirs with
// sin(2 pi) != 0 and so on, a few 1e-16 apart: they need `weld`.
await check('TorusKnotGeometry watertight as it is; SphereGeometry and CylinderGeometry with weld: 1e-6', () => {
  assertWatertight(subdivideGeometry(new THREE.TorusKnotGeometry(1, 0.3, 64, 8), { levels: 2 }));
  const sphere = new THREE.SphereGeometry(1, 16, 12);
  assert.throws(() => assertWatertight(subdivideGeometry(sphere, { levels: 1 })), /edges are not used once each way/);
  assertWatertight(subdivideGeometry(sphere, { levels: 2, weld: 1e-6 }));
  assertWatertight(subdivideGeometry(new THREE.CylinderGeometry(1, 1, 2, 12, 1), { levels: 1, weld: 1e-6, creaseAngle: 1 }));
});

// ---- welding by distance
await check('weld: positions a little apart crack without it, close with it', () => {
  const mesh = shape('torus');
  const geometry = gltfGeometry(mesh);
  const p = geometry.getAttribute('position').array;
  // Every seam copy after the first moved by up to 1e-5 (as an exporter's rounding would).
  const seen = new Set();
  for (let v = 0; v < p.length / 3; v++) {
    const k = `${p[3 * v]},${p[3 * v + 1]},${p[3 * v + 2]}`;
    if (seen.has(k)) p[3 * v] += 1e-5 * (1 + (v % 3));
    seen.add(k);
  }
  const cracked = subdivideGeometry(geometry, { levels: 1 });
  assert.throws(() => assertWatertight(cracked), /edges are not used once each way/);
  const welded = subdivideGeometry(geometry, { levels: 2, quads: true, weld: 1e-4 });
  assertWatertight(welded);
  sameVertices(reference(mesh, { levels: 2 }), drawn(welded), [['uv', 2]], 1e-4);
  assert.throws(() => subdivideGeometry(geometry, { weld: -1 }), /weld must be a distance >= 0/);
});

// ---- interleaved and normalized attributes
await check('interleaved position/uv and a normalized Uint8 color', () => {
  const mesh = shape('cube');
  const plain = gltfGeometry(mesh);
  const n = plain.getAttribute('position').count;
  const buffer = new THREE.InterleavedBuffer(new Float32Array(5 * n), 5);
  const interleaved = new THREE.BufferGeometry();
  interleaved.setIndex(plain.index);
  interleaved.setAttribute('position', new THREE.InterleavedBufferAttribute(buffer, 3, 0));
  interleaved.setAttribute('uv', new THREE.InterleavedBufferAttribute(buffer, 2, 3));
  for (let v = 0; v < n; v++) {
    buffer.array.set(plain.getAttribute('position').array.subarray(3 * v, 3 * v + 3), 5 * v);
    buffer.array.set(plain.getAttribute('uv').array.subarray(2 * v, 2 * v + 2), 5 * v + 3);
  }
  const color = new Uint8Array(3 * n);
  for (let v = 0; v < n; v++) color.set([255, 0, 51], 3 * v);
  interleaved.setAttribute('color', new THREE.BufferAttribute(color, 3, true));
  const a = subdivideGeometry(interleaved, { levels: 2 });
  const b = subdivideGeometry(plain, { levels: 2 });
  sameVertices(drawn(a), drawn(b), [['uv', 2], ['normals', 3]], 1e-6);
  const c = a.getAttribute('color');
  assert.equal(c.itemSize, 3);
  for (let v = 0; v < c.count; v++) {
    assert.ok(Math.abs(c.getX(v) - 1) < 1e-6 && Math.abs(c.getY(v)) < 1e-6 && Math.abs(c.getZ(v) - 0.2) < 1e-6);
  }
});

// ---- attribute rules: tangent dropped, normals modes
await check("tangent is dropped; normals 'faces' and false", () => {
  const geometry = new THREE.SphereGeometry(1, 12, 8);
  geometry.computeTangents();
  assert.ok(geometry.getAttribute('tangent'));
  const out = subdivideGeometry(geometry, { levels: 1 });
  assert.deepEqual(Object.keys(out.attributes).sort(), ['normal', 'position', 'uv']);
  const faces = subdivideGeometry(geometry, { levels: 1, normals: 'faces' });
  const n = faces.getAttribute('normal');
  const p = faces.getAttribute('position');
  for (let v = 0; v < n.count; v++) {
    // On a sphere the face normals around a vertex point roughly outward.
    const dot = n.getX(v) * p.getX(v) + n.getY(v) * p.getY(v) + n.getZ(v) * p.getZ(v);
    assert.ok(dot / Math.hypot(p.getX(v), p.getY(v), p.getZ(v)) > 0.95, `vertex ${v}`);
    assert.ok(Math.abs(Math.hypot(n.getX(v), n.getY(v), n.getZ(v)) - 1) < 1e-5);
  }
  assert.equal(subdivideGeometry(geometry, { levels: 1, normals: false }).getAttribute('normal'), undefined);
});

await check('degenerate triangles are dropped; instanced attributes and userData are copied', () => {
  const box = new THREE.BoxGeometry(2, 2, 2);
  const n = box.getAttribute('position').count;
  const grown = new THREE.BufferGeometry();
  for (const name of ['position', 'normal', 'uv']) {
    const a = box.getAttribute(name);
    const array = new Float32Array((n + 3) * a.itemSize);
    array.set(a.array);
    array.fill(0.5, n * a.itemSize); // three more vertices, two of them at one position
    if (name === 'position') array.set([3, 3, 3, 3, 3, 3, 4, 4, 4], 3 * n);
    grown.setAttribute(name, new THREE.BufferAttribute(array, a.itemSize));
  }
  const skinWeight = new Float32Array(4 * (n + 3)).fill(0.25);
  grown.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(new Uint16Array(4 * (n + 3)).fill(1), 4));
  grown.setAttribute('skinWeight', new THREE.BufferAttribute(skinWeight, 4));
  grown.setIndex([...box.index.array, n, n + 1, n + 2]);
  grown.setAttribute('offset', new THREE.InstancedBufferAttribute(new Float32Array([0, 0, 0, 1, 1, 1]), 3));
  grown.userData = { source: 'test' };
  const out = subdivideGeometry(grown, { levels: 1 });
  assert.equal(out.index.count, subdivideGeometry(box, { levels: 1 }).index.count);
  for (const a of Object.values(out.attributes)) assert.ok(a.array.every(Number.isFinite));
  assert.equal(out.getAttribute('offset').count, 2);
  assert.deepEqual(out.userData, { source: 'test' });
});

// ---- creases
await check('BoxGeometry: creaseAngle and sharpNormalSplits keep the cube, with one normal per side', () => {
  const box = new THREE.BoxGeometry(2, 2, 2);
  const round = subdivideGeometry(box, { levels: 2 });
  const inside = (g) => {
    const p = g.getAttribute('position').array;
    let min = Infinity, max = 0;
    for (let i = 0; i < p.length; i += 3) {
      const m = Math.max(Math.abs(p[i]), Math.abs(p[i + 1]), Math.abs(p[i + 2]));
      min = Math.min(min, m);
      max = Math.max(max, m);
    }
    return [min, max];
  };
  assert.ok(inside(round)[0] < 0.8, 'without creases the box is rounded');
  for (const options of [{ creaseAngle: Math.PI / 6 }, { sharpNormalSplits: true }, { creaseAngle: 0.5, quads: true }, { sharpNormalSplits: true, normals: 'faces' }]) {
    const out = subdivideGeometry(box, { levels: 2, ...options });
    const [min, max] = inside(out);
    assert.ok(Math.abs(min - 1) < 1e-6 && Math.abs(max - 1) < 1e-6, `${JSON.stringify(options)}: every point on the cube (${min}, ${max})`);
    assertWatertight(out);
    // Each triangle's three normals are its face's axis, outward.
    const p = out.getAttribute('position'), n = out.getAttribute('normal'), index = out.index.array;
    for (let t = 0; t < index.length; t += 3) {
      const c = [0, 1, 2].map((k) => (p.getX(index[t]) + p.getX(index[t + 1]) + p.getX(index[t + 2])) / 3 * (k === 0) +
        (p.getY(index[t]) + p.getY(index[t + 1]) + p.getY(index[t + 2])) / 3 * (k === 1) +
        (p.getZ(index[t]) + p.getZ(index[t + 1]) + p.getZ(index[t + 2])) / 3 * (k === 2));
      const axis = c.map((x) => (Math.abs(Math.abs(x) - 1) < 1e-6 ? Math.sign(x) : 0));
      for (let j = 0; j < 3; j++) {
        const v = index[t + j];
        assert.ok(Math.abs(n.getX(v) - axis[0]) < 1e-5 && Math.abs(n.getY(v) - axis[1]) < 1e-5 && Math.abs(n.getZ(v) - axis[2]) < 1e-5,
          `${JSON.stringify(options)}: triangle ${t / 3} normal (${n.getX(v)}, ${n.getY(v)}, ${n.getZ(v)}) should be ${axis}`);
      }
    }
  }
  // A smooth sphere's UV seam splits vertices with equal normals: no crease from it.
  const sphere = new THREE.SphereGeometry(1, 16, 12);
  const a = drawn(subdivideGeometry(sphere, { levels: 1, weld: 1e-6 }));
  const b = drawn(subdivideGeometry(sphere, { levels: 1, weld: 1e-6, sharpNormalSplits: true }));
  sameVertices(a, b, [['uv', 2], ['normals', 3]], 1e-6);
  assert.throws(() => subdivideGeometry(box, { creaseAngle: 30 }), /creaseAngle is in radians.*30 \* Math\.PI \/ 180/);
});

// ---- skinning
await check('skinIndex/skinWeight: the four largest of the refined weights, renormalised', () => {
  const mesh = shape('torus');
  const geometry = gltfGeometry(mesh);
  const p = geometry.getAttribute('position');
  const n = p.count;
  const BONES = 7;
  const skinIndex = new Uint16Array(4 * n), skinWeight = new Float32Array(4 * n);
  const dense = new Float32Array(BONES * (mesh.positions.length / 3));
  const weightsAt = (x, y, z) => {
    // Up to four bones by angle around the torus axis, some vertices with one only.
    const a = ((Math.atan2(z, x) / (2 * Math.PI)) + 1) % 1 * BONES;
    const b0 = Math.floor(a) % BONES, f = a - Math.floor(a);
    if (f < 0.2) return [[b0, 1]];
    const list = [[b0, 1 - f], [(b0 + 1) % BONES, f]];
    if (y > 0) list.push([(b0 + 3) % BONES, 0.3], [(b0 + 5) % BONES, 0.2]);
    const sum = list.reduce((s, [, w]) => s + w, 0);
    return list.map(([bone, w]) => [bone, w / sum]);
  };
  for (let v = 0; v < n; v++) {
    weightsAt(p.getX(v), p.getY(v), p.getZ(v)).forEach(([bone, w], k) => {
      skinIndex[4 * v + k] = bone;
      skinWeight[4 * v + k] = w;
    });
  }
  for (let v = 0; v < mesh.positions.length / 3; v++) {
    for (const [bone, w] of weightsAt(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2])) dense[BONES * v + bone] += w;
  }
  geometry.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(skinIndex, 4));
  geometry.setAttribute('skinWeight', new THREE.Float32BufferAttribute(skinWeight, 4));
  const out = subdivideGeometry(geometry, { levels: 2, quads: true });
  const oi = out.getAttribute('skinIndex'), ow = out.getAttribute('skinWeight');
  assert.ok(oi.array instanceof Uint16Array && ow.array instanceof Float32Array);
  // The reference: every bone's weight as a vertex-varying channel of subdivide, top four kept.
  const ref = subdivide({ ...mesh, attributes: { ...mesh.attributes, bones: { array: dense, itemSize: BONES } } }, { levels: 2 });
  const refDraw = toDrawable(ref);
  const expected = new Float32Array(BONES * refDraw.positions.length / 3);
  let truncated = 0;
  for (let d = 0; d < refDraw.positions.length / 3; d++) {
    const w = [...refDraw.attributes.bones.array.subarray(BONES * d, BONES * d + BONES)].map((x, b) => [Math.max(0, x), b]);
    w.sort((x, y) => y[0] - x[0] || x[1] - y[1]);
    if (w[4][0] > 0) truncated++;
    const sum = w.slice(0, 4).reduce((s, [x]) => s + x, 0);
    for (const [x, b] of w.slice(0, 4)) expected[BONES * d + b] = x / sum;
  }
  assert.ok(truncated > 0, 'some refined vertices have more than four influences');
  const got = new Float32Array(BONES * oi.count);
  for (let v = 0; v < oi.count; v++) {
    let sum = 0, count = 0;
    for (let k = 0; k < 4; k++) {
      const w = ow.array[4 * v + k];
      sum += w;
      if (w > 0) count++;
      got[BONES * v + oi.array[4 * v + k]] += w;
    }
    assert.ok(Math.abs(sum - 1) < 1e-5, `vertex ${v}: weights sum to ${sum}`);
    assert.ok(count <= 4);
  }
  sameVertices({ positions: refDraw.positions, w: expected, uv: refDraw.attributes.uv.array },
    { positions: out.getAttribute('position').array, w: got, uv: out.getAttribute('uv').array }, [['w', BONES], ['uv', 2]], 1e-5);
});

// ---- morph targets
await check('morph targets: a relative translation stays a translation; absolute ones stay absolute', () => {
  const mesh = shape('torus');
  for (const relative of [true, false]) {
    const geometry = gltfGeometry(mesh);
    const p = geometry.getAttribute('position');
    const t = [0.25, -0.5, 1];
    const move = new Float32Array(p.array.length), scale = new Float32Array(p.array.length);
    for (let v = 0; v < p.count; v++) {
      for (let k = 0; k < 3; k++) {
        move[3 * v + k] = relative ? t[k] : p.array[3 * v + k] + t[k];
        scale[3 * v + k] = relative ? p.array[3 * v + k] : 2 * p.array[3 * v + k];
      }
    }
    geometry.morphAttributes.position = [new THREE.BufferAttribute(move, 3), new THREE.BufferAttribute(scale, 3)];
    geometry.morphAttributes.position[0].name = 'move';
    geometry.morphAttributes.normal = [new THREE.BufferAttribute(new Float32Array(p.array.length), 3), new THREE.BufferAttribute(new Float32Array(p.array.length), 3)];
    geometry.morphTargetsRelative = relative;
    const before = snapshot(geometry);
    const out = subdivideGeometry(geometry, { levels: 2, quads: true });
    assertUnchanged(geometry, before);
    assert.equal(out.morphTargetsRelative, relative);
    const [m0, m1] = out.morphAttributes.position;
    const [n0, n1] = out.morphAttributes.normal;
    assert.equal(m0.name, 'move');
    const op = out.getAttribute('position').array, on = out.getAttribute('normal').array;
    assert.equal(m0.count, op.length / 3);
    let worst = 0;
    for (let i = 0; i < op.length; i++) {
      const k = i % 3;
      worst = Math.max(worst,
        Math.abs(m0.array[i] - (relative ? t[k] : op[i] + t[k])),
        Math.abs(m1.array[i] - (relative ? op[i] : 2 * op[i])),
        // Moving or scaling the surface leaves its normals: zero deltas, or the base normals.
        Math.abs(n0.array[i] - (relative ? 0 : on[i])),
        Math.abs(n1.array[i] - (relative ? 0 : on[i])));
    }
    assert.ok(worst < 1e-5, `relative ${relative}: off by ${worst}`);
  }
});

// ---- groups
await check('groups: every refined face in its parent face\'s group (BoxGeometry, 6 materials)', () => {
  const box = new THREE.BoxGeometry(2, 2, 2, 2, 2, 2);
  for (const options of [{ levels: 2 }, { levels: 2, quads: true }, { levels: 1, scheme: 'loop' }, { levels: 2, scheme: 'sqrt3' }, { levels: 1, scheme: 'doo-sabin' }]) {
    const out = subdivideGeometry(box, options);
    assert.deepEqual(out.groups.map((g) => g.materialIndex), [0, 1, 2, 3, 4, 5]);
    assert.equal(out.groups[0].start, 0);
    for (let g = 1; g < 6; g++) assert.equal(out.groups[g].start, out.groups[g - 1].start + out.groups[g - 1].count);
    assert.equal(out.groups[5].start + out.groups[5].count, out.index.count);
    // Groups that leave faces out: those come last, in no group (three draws them not, as before).
    const partial = box.clone();
    partial.groups.pop();
    const cut = subdivideGeometry(partial, options);
    assert.deepEqual(cut.groups.map((g) => [g.start, g.count, g.materialIndex]), out.groups.slice(0, 5).map((g) => [g.start, g.count, g.materialIndex]));
    assert.equal(cut.index.count, out.index.count);
    // BoxGeometry's groups are +x, -x, +y, -y, +z, -z; a child's centroid lies on its parent's side.
    const p = out.getAttribute('position'), index = out.index.array;
    for (const [g, { start, count }] of out.groups.entries()) {
      const axis = g >> 1, sign = g % 2 ? -1 : 1;
      for (let t = start; t < start + count; t += 3) {
        const c = [0, 0, 0];
        for (let j = 0; j < 3; j++) {
          c[0] += p.getX(index[t + j]) / 3;
          c[1] += p.getY(index[t + j]) / 3;
          c[2] += p.getZ(index[t + j]) / 3;
        }
        const a = c.map(Math.abs);
        // Exactly so with quads (the cube's symmetry); triangulated faces bend the borders a little;
        // √3 and Doo-Sabin make faces across parent edges, which take one side's group.
        const slack = options.quads ? 1e-6 : ['sqrt3', 'doo-sabin'].includes(options.scheme) ? 0.5 : 0.05;
        assert.ok(sign * c[axis] > 0 && a[axis] >= Math.max(...a) - slack, `${JSON.stringify(options)}: triangle at ${c} in group ${g}`);
      }
    }
  }
});

// ---- errors
await check('bad input: clear errors', () => {
  const noPosition = new THREE.BufferGeometry();
  noPosition.setAttribute('uv', new THREE.Float32BufferAttribute([0, 0, 1, 0, 0, 1], 2));
  assert.throws(() => subdivideGeometry(noPosition), /no 'position' attribute; it has 'uv'/);
  const box = new THREE.BoxGeometry();
  assert.throws(() => subdivideGeometry(box, { quads: true, scheme: 'loop' }), /quads: true.*'loop' takes triangles only.*'catmull-clark'/);
  assert.throws(() => subdivideGeometry({ attributes: {} }), /must be a THREE\.BufferGeometry, got an object/);
  assert.throws(() => subdivideGeometry(new THREE.Mesh(box)), /a Mesh: pass mesh\.geometry/);
  assert.throws(() => subdivideGeometry(undefined), /must be a THREE\.BufferGeometry, got undefined/);
  assert.throws(() => subdivideGeometry(box, 2), /options must be an object/);
  assert.throws(() => subdivideGeometry(box, { level: 2 }), /unknown option 'level'.*'levels'/);
  assert.throws(() => subdivideGeometry(box, { normals: 'limit' }), /normals must be true.*'faces' or false/);
  const odd = new THREE.BufferGeometry();
  odd.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0], 3));
  assert.throws(() => subdivideGeometry(odd), /triangle list; its position count 4 is not a multiple of 3/);
  odd.setIndex([0, 1, 7]);
  assert.throws(() => subdivideGeometry(odd), /index\[2\] is 7, but the geometry has only 4 vertices/);
  const nan = new THREE.BufferGeometry();
  nan.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, 0, NaN, 0, 1, 0], 3));
  assert.throws(() => subdivideGeometry(nan), /position of vertex 1 is not finite/);
  const skinOnly = new THREE.BoxGeometry();
  skinOnly.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(new Uint16Array(4 * 24), 4));
  assert.throws(() => subdivideGeometry(skinOnly), /'skinIndex' without 'skinWeight'/);
  assert.throws(() => subdivideGeometry(box, { scheme: 'loop', levels: 1, limit: true, creaseAngle: 'sharp' }), /creaseAngle must be an angle in radians/);
  // After errors the module works on.
  assert.ok(subdivideGeometry(box, { levels: 1 }).index.count > 0);
});

await check('the web entry without init() says to call init()', () => {
  const script = `import(${JSON.stringify(pathToFileURL(join(installed, 'three.js')).href)}).then(async (m) => {
    const THREE = await import('three');
    try { m.subdivideGeometry(new THREE.BoxGeometry()); console.log('no error'); } catch (e) { console.log(e.message); }
  });`;
  const run = spawnSync(process.execPath, ['--input-type=module', '-e', script], { cwd: scratch, encoding: 'utf8' });
  assert.match(run.stdout, /not initialised: in a browser call `await init\(\)`/, run.stdout + run.stderr);
});

// ---- subdivideGeometryAsync: the same work in a worker_threads thread (subsurf/worker)

/**
 * Asserts that two BufferGeometries are the same: name, userData, every attribute (kind,
 * itemSize, normalized, name, array type and bytes), index, groups, morph targets.
 */
function assertSameGeometry(a, b, what) {
  const bytes = (array) => Buffer.from(array.buffer, array.byteOffset, array.byteLength);
  const sameAttribute = (x, y, where) => {
    assert.ok(x && y, `${where}: present in both`);
    assert.equal(x.itemSize, y.itemSize, `${where}: itemSize`);
    assert.equal(x.normalized, y.normalized, `${where}: normalized`);
    assert.equal(x.name, y.name, `${where}: name`);
    assert.equal(Boolean(x.isInstancedBufferAttribute), Boolean(y.isInstancedBufferAttribute), `${where}: instanced`);
    assert.equal(x.array.constructor, y.array.constructor, `${where}: array type`);
    assert.ok(x.array.length > 0, `${where}: not empty`);
    assert.ok(bytes(x.array).equals(bytes(y.array)), `${where}: bytes differ`);
  };
  assert.equal(a.name, b.name, `${what}: name`);
  assert.deepEqual(a.userData, b.userData, `${what}: userData`);
  assert.deepEqual(Object.keys(a.attributes).sort(), Object.keys(b.attributes).sort(), `${what}: attribute names`);
  for (const name of Object.keys(a.attributes)) sameAttribute(a.attributes[name], b.attributes[name], `${what}: attribute '${name}'`);
  sameAttribute(a.index, b.index, `${what}: index`);
  assert.deepEqual(a.groups, b.groups, `${what}: groups`);
  assert.equal(a.morphTargetsRelative, b.morphTargetsRelative, `${what}: morphTargetsRelative`);
  assert.deepEqual(Object.keys(a.morphAttributes).sort(), Object.keys(b.morphAttributes).sort(), `${what}: morph attribute names`);
  for (const [name, list] of Object.entries(a.morphAttributes)) {
    assert.equal(list.length, b.morphAttributes[name].length, `${what}: morph ${name} targets`);
    list.forEach((target, i) => sameAttribute(target, b.morphAttributes[name][i], `${what}: morph ${name}[${i}]`));
  }
}

/** A torus with seams split as glTF does, a skin of three bones and two named morph targets. */
function skinnedMorphedTorus(relative) {
  const geometry = gltfGeometry(shape('torus'));
  const p = geometry.getAttribute('position');
  const skinIndex = new Uint16Array(4 * p.count), skinWeight = new Float32Array(4 * p.count);
  const grow = new Float32Array(3 * p.count), lift = new Float32Array(3 * p.count);
  for (let v = 0; v < p.count; v++) {
    const a = (Math.atan2(p.getZ(v), p.getX(v)) / Math.PI + 1) * 1.5; // 0..3 around the axis
    const bone = Math.min(2, Math.floor(a)), f = a - bone;
    skinIndex.set([bone, (bone + 1) % 3, 0, 0], 4 * v);
    skinWeight.set([1 - f, f, 0, 0], 4 * v);
    for (let k = 0; k < 3; k++) grow[3 * v + k] = (relative ? 0 : p.array[3 * v + k]) + 0.2 * p.array[3 * v + k];
    lift.set(relative ? [0, 0.5, 0] : [p.getX(v), p.getY(v) + 0.5, p.getZ(v)], 3 * v);
  }
  geometry.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(skinIndex, 4));
  geometry.setAttribute('skinWeight', new THREE.Float32BufferAttribute(skinWeight, 4));
  geometry.morphAttributes.position = [new THREE.BufferAttribute(grow, 3), new THREE.BufferAttribute(lift, 3)];
  geometry.morphAttributes.position[0].name = 'grow';
  geometry.morphAttributes.position[1].name = 'lift';
  geometry.morphAttributes.normal = [new THREE.BufferAttribute(new Float32Array(3 * p.count), 3), new THREE.BufferAttribute(new Float32Array(3 * p.count), 3)];
  geometry.morphAttributes.normal[1].name = 'lift normals';
  geometry.morphTargetsRelative = relative;
  geometry.name = 'torus';
  geometry.userData = { source: 'test', nested: { list: [1, 2] } };
  return geometry;
}

/** Cube positions and UVs in one interleaved buffer, a normalized Uint8 colour, an instanced offset. */
function interleavedCube() {
  const plain = gltfGeometry(shape('cube'));
  const n = plain.getAttribute('position').count;
  const buffer = new THREE.InterleavedBuffer(new Float32Array(5 * n), 5);
  for (let v = 0; v < n; v++) {
    buffer.array.set(plain.getAttribute('position').array.subarray(3 * v, 3 * v + 3), 5 * v);
    buffer.array.set(plain.getAttribute('uv').array.subarray(2 * v, 2 * v + 2), 5 * v + 3);
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setIndex(new THREE.Uint16BufferAttribute(plain.index.array, 1));
  geometry.setAttribute('position', new THREE.InterleavedBufferAttribute(buffer, 3, 0));
  geometry.setAttribute('uv', new THREE.InterleavedBufferAttribute(buffer, 2, 3));
  const color = new Uint8Array(3 * n);
  for (let v = 0; v < n; v++) color.set([255, (40 * v) % 256, 51], 3 * v);
  geometry.setAttribute('color', new THREE.BufferAttribute(color, 3, true));
  geometry.setAttribute('offset', new THREE.InstancedBufferAttribute(new Float32Array([0, 0, 0, 1, 1, 1]), 3));
  return geometry;
}

/** A view into a larger buffer, as a glTF file's accessors are: only the view may be copied. */
function viewGeometry() {
  const box = new THREE.BoxGeometry(2, 2, 2, 2, 2, 2);
  const p = box.getAttribute('position').array;
  const big = new Float32Array(p.length + 1000);
  big.set(p, 500);
  box.setAttribute('position', new THREE.BufferAttribute(big.subarray(500, 500 + p.length), 3));
  return box;
}

const worker = createWorker();
const rejection = (promise) => promise.then((value) => assert.fail(`resolved with ${value}`), (error) => error);

await check('subdivideGeometryAsync = subdivideGeometry, byte for byte (seams, groups, morphs, skin, interleaved, views, options)', async () => {
  const box = new THREE.BoxGeometry(2, 2, 2, 2, 2, 2);
  const knot = new THREE.TorusKnotGeometry(1, 0.3, 64, 8);
  const creases = { edges: new Uint32Array([0, 1, 1, 2]), sharpness: new Float32Array([10, 2]) };
  const cases = [
    ['torus, glTF seams, quads', gltfGeometry(shape('torus')), { levels: 2, quads: true }],
    ['house, glTF seams, Loop, limit', gltfGeometry(shape('house')), { scheme: 'loop', levels: 2, limit: true, fvarLinear: 'none' }],
    ['BoxGeometry, 6 groups', box, { levels: 2 }],
    ['BoxGeometry, groups, sharpNormalSplits, faces normals', box, { levels: 2, sharpNormalSplits: true, normals: 'faces' }],
    ['BoxGeometry, sqrt3 with groups', box, { scheme: 'sqrt3', levels: 2 }],
    ['BoxGeometry non-indexed, creaseAngle', new THREE.BoxGeometry().toNonIndexed(), { levels: 1, creaseAngle: 0.5 }],
    ['TorusKnotGeometry, creases and holes in the options', knot, { levels: 1, creases, holes: new Uint32Array([3, 4]) }],
    ['skinned, morphed torus (relative)', skinnedMorphedTorus(true), { levels: 2, quads: true }],
    ['skinned, morphed torus (absolute)', skinnedMorphedTorus(false), { levels: 1, scheme: 'loop' }],
    ['interleaved, normalized, instanced, Uint16 index', interleavedCube(), { levels: 2 }],
    ['a view into a larger buffer', viewGeometry(), { levels: 1, normals: false }],
  ];
  for (const [what, geometry, options] of cases) {
    const before = snapshot(geometry);
    const optionsBefore = structuredClone(options);
    const sync = subdivideGeometry(geometry, options);
    const async = await subdivideGeometryAsync(geometry, options, { worker });
    assertSameGeometry(async, sync, what);
    // Nothing of the caller's was detached by the transfer or written: the input's arrays and
    // the options' arrays are whole and unchanged.
    assertUnchanged(geometry, before);
    assert.deepEqual(options, optionsBefore, `${what}: options unchanged`);
  }
  assert.ok(creases.edges.length === 4 && creases.sharpness.length === 2, 'the options\' arrays are not detached');
  return `${cases.length} geometries`;
});

await check('subdivideGeometryAsync: progress after each level, in order, as subdivideGeometry\'s onProgress tells it', async () => {
  const geometry = skinnedMorphedTorus(true); // morph normals: extra subdivide passes, which tell nothing
  const expected = [];
  subdivideGeometry(geometry, { levels: 3, quads: true, onProgress: (p) => expected.push(p) });
  assert.deepEqual(expected.map((p) => `${p.level}/${p.levels}`), ['1/3', '2/3', '3/3'], 'sync: once per level');
  const told = [];
  const out = await subdivideGeometryAsync(geometry, { levels: 3, quads: true }, { worker, onProgress: (p) => told.push(p) });
  assert.deepEqual(told, expected);
  assert.ok(out.morphAttributes.normal.length === 2);
  // options.onProgress works too (functions cannot be posted: it stays here).
  const fromOptions = [];
  await subdivideGeometryAsync(geometry, { levels: 2, onProgress: (p) => fromOptions.push(p.level) }, { worker });
  assert.deepEqual(fromOptions, [1, 2]);
});

await check('subdivideGeometryAsync: abort rejects with an AbortError, the next call works', async () => {
  const big = new THREE.TorusKnotGeometry(1, 0.3, 256, 32);
  const controller = new AbortController();
  const seen = [];
  const error = await rejection(subdivideGeometryAsync(big, { levels: 6, maxFaces: 1e9, maxBytes: 8e9 }, {
    worker,
    signal: controller.signal,
    onProgress: ({ level }) => {
      seen.push(level);
      if (level === 1) controller.abort();
    },
  }));
  assert.ok(error instanceof DOMException && error.name === 'AbortError', `${error}`);
  assert.deepEqual(seen, [1]);
  assert.equal((await rejection(subdivideGeometryAsync(big, { levels: 1 }, { worker, signal: AbortSignal.abort() }))).name, 'AbortError');
  const box = new THREE.BoxGeometry();
  assertSameGeometry(await subdivideGeometryAsync(box, { levels: 2 }, { worker }), subdivideGeometry(box, { levels: 2 }), 'after the abort');
  // What onProgress throws rejects the call with it.
  const thrown = await rejection(subdivideGeometryAsync(box, { levels: 3 }, { worker, onProgress: () => { throw new RangeError('stop'); } }));
  assert.equal(thrown.message, 'stop');
});

await check('subdivideGeometryAsync: bad input rejects with subdivideGeometry\'s message', async () => {
  const syncMessage = (geometry, options) => {
    try {
      subdivideGeometry(geometry, options);
    } catch (error) {
      return error.message;
    }
    assert.fail('subdivideGeometry did not throw');
  };
  const noPosition = new THREE.BufferGeometry();
  noPosition.setAttribute('uv', new THREE.Float32BufferAttribute([0, 0, 1, 0, 0, 1], 2));
  const odd = new THREE.BufferGeometry();
  odd.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, 0, 0, 0, 1, 0], 3));
  odd.setIndex([0, 1, 7]);
  const nan = new THREE.BufferGeometry();
  nan.setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, 0, NaN, 0, 1, 0], 3));
  const box = new THREE.BoxGeometry();
  const cases = [
    [noPosition, {}, /no 'position' attribute; it has 'uv'/],
    [odd, {}, /index\[2\] is 7, but the geometry has only 3 vertices/], // checked in the thread
    [nan, {}, /position of vertex 1 is not finite/],
    [box, { level: 2 }, /unknown option 'level'/],
    [box, { quads: true, scheme: 'loop' }, /'loop' takes triangles only/],
    [box, { creaseAngle: 30 }, /creaseAngle is in radians/],
    [box, { levels: 12, maxFaces: 100 }, /more than the limit/],
    [new THREE.Mesh(box), {}, /a Mesh: pass mesh\.geometry/],
  ];
  for (const [geometry, options, pattern] of cases) {
    const message = syncMessage(geometry, options);
    assert.match(message, pattern);
    const error = await rejection(subdivideGeometryAsync(geometry, options, { worker }));
    assert.ok(error instanceof Error, `${error}`);
    assert.equal(error.message, message);
  }
  assert.match((await rejection(subdivideGeometryAsync(box, { levels: 1 }))).message,
    /subdivideGeometryAsync: the third argument must be \{ worker \}.*createWorker\(\) of 'subsurf\/worker'.*got undefined/);
  assert.match((await rejection(subdivideGeometryAsync(box, {}, { signal: AbortSignal.timeout(1000) }))).message, /got an object without a worker/);
  const unclonable = await rejection(subdivideGeometryAsync(box, { levels: 1, holes: { toString: () => 'x', f() {} } }, { worker }));
  assert.ok(unclonable instanceof TypeError && /options cannot be sent to a worker/.test(unclonable.message), `${unclonable}`);
  assert.ok((await subdivideGeometryAsync(box, { levels: 1 }, { worker })).index.count > 0, 'the worker goes on');
});

await check('subdivideGeometryAsync: a big geometry, times on this machine (no assertion on them)', async () => {
  const big = new THREE.TorusKnotGeometry(1, 0.3, 512, 64); // 65,536 triangles, seams
  const options = { levels: 2, quads: true };
  await subdivideGeometryAsync(big, { levels: 0 }, { worker }); // the thread is up
  let start = performance.now();
  const sync = subdivideGeometry(big, options);
  const syncMs = performance.now() - start;
  start = performance.now();
  const async = await subdivideGeometryAsync(big, options, { worker });
  const asyncMs = performance.now() - start;
  assertSameGeometry(async, sync, 'big knot');
  return `TorusKnotGeometry 512 × 64 (65,536 triangles) → ${sync.index.count / 3} triangles: sync ${syncMs.toFixed(0)} ms, async ${asyncMs.toFixed(0)} ms`;
});
worker.terminate();

// ---- TypeScript declarations, with @types/three
if (threeArg < 0) await check('tsc on tests/js/three_types_check.ts with @types/three', () => {
  cpSync(join(root, 'tests', 'js', 'three_types_check.ts'), join(scratch, 'three_types_check.ts'));
  const compilerOptions = {
    strict: true, noEmit: true, skipLibCheck: false, target: 'es2022', module: 'nodenext', moduleResolution: 'nodenext',
    lib: ['es2022', 'esnext.disposable', 'dom'], types: [],
  };
  writeFileSync(join(scratch, 'tsconfig.json'), JSON.stringify({ compilerOptions, files: ['three_types_check.ts'] }));
  const tsc = spawnSync(join(root, 'node_modules', '.bin', 'tsc'), ['-p', scratch], { encoding: 'utf8' });
  assert.equal(tsc.status, 0, `tsc failed:\n${tsc.stdout}${tsc.stderr}`);
});

finish(`three ${threeVersion}`);
