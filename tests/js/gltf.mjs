// glTF files through subsurf/three, in Node, on the built package in pkg/ (run
// scripts/build-pkg.sh first):   node tests/js/gltf.mjs
//
// The fixtures, tests/fixtures/gltf/*.glb (tools/gltf/make-fixtures.mjs, MANIFEST.tsv there), are
// OpenSubdiv regression shapes with UVs as a glTF exporter writes them: triangulated (quads
// along a recorded diagonal, n-gons fanned), vertices split wherever the UV differs, V flipped.
// Each is read by three's GLTFLoader and then:
//   1. The fixture is checked against its source OBJ (tests/meshes/osd/, read by readObj): every
//      glTF triangle corner is the OBJ corner the recorded triangulation says, position bit for
//      bit and UV (u, 1 - v).
//   2. Equal to OpenSubdiv: subdivideGeometry's output, as triangles of (position, uv) corners,
//      against OpenSubdiv 3.5's own level-2 result of the untagged OBJ (tests/fixtures/osd for
//      positions, tests/fixtures/osd_fvar for the UVs, same face and vertex order; made by
//      tools/osd/make_fixtures.sh and make_fvar_fixtures.sh): Loop on the all-triangle shapes,
//      `quads: true` Catmull-Clark on the all-quad shapes (the glTF's triangles must join back
//      into the OBJ's quads), fvarLinear 'none', the default ('corners-plus1'), 'boundaries' and
//      'all'. Every reference face must be in the output (a quad as either of its two triangle
//      pairs), nothing else may be, and every value must agree. A shape whose OBJ has two vt
//      lines with equal values at one vertex is compared with subdivide on the OBJ with those
//      joined instead (glTF keeps values, so they are one UV there; OpenSubdiv sees a seam).
//      `quads: true` joins triangles folded by at most 40°: on shapes whose quads fold more, the
//      test checks that some stay split and raises the thresholds past the largest fold.
//   3. Equal to subdivide: the same comparison against `subdivide` (this package's, which
//      tests/osd_agreement.rs and osd_fvar_agreement.rs check against OpenSubdiv on these
//      shapes) on the OBJ mesh as the glTF triangulates it, for what OpenSubdiv has no fixture
//      of: Catmull-Clark on the triangles (no `quads`) of every shape, Loop on the triangulated
//      quad and mixed shapes.
//   4. Watertight: welded by position (bit patterns), every output edge is used once each way,
//      except boundary edges, used once; the input's boundary edges (glTF welded the same way)
//      each become 2^levels output boundary edges, in as many boundary loops as the input has,
//      so a closed input gives a closed output and a crack (a seam left open) would add boundary
//      edges. Checked for every output of 2. and 3.
//   5. Bad input: a glTF geometry without its position attribute, and `quads: true` with Loop.
//
// Tolerance: values agree within 1e-5 (UVs) and 1e-5 × max(1, largest |coordinate|)
// (positions), the relative tolerance of the Rust OpenSubdiv agreement tests
// (tests/common/osd.rs, RELATIVE_TOLERANCE); the differences are Float32 rounding (the order of
// the sums differs), about 1e-7. Exits non-zero on the first failure.

import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { checks, installPackage, root, triangulated } from './common.mjs';
import { edgeCounts } from './edges.mjs';

const fixtures = join(root, 'tests', 'fixtures', 'gltf');
const TOLERANCE = 1e-5;
const LEVELS = 2;
const MODES = ['none', undefined, 'boundaries', 'all']; // undefined: the default, 'corners-plus1'
let corners = 0;
const tally = {}; // per reference: { comparisons, worst, where }
let against = '';
const { check, finish } = checks('gltf');

// ---- install the package beside three, as a user's project has them (as tests/js/three.mjs)
const { consumer } = await installPackage({
  prefix: 'subsurf-gltf-',
  links: { three: join(root, 'node_modules', 'three') },
  consumer: "export * as THREE from 'three';\nexport { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';\n" +
    "export { subdivideGeometry } from 'subsurf/three';\nexport * as subsurf from 'subsurf/node';\n",
});
const { GLTFLoader, subdivideGeometry, subsurf } = consumer;
const { readObj, subdivide } = subsurf;

// ---- reading

function loadGlb(file) {
  const bytes = readFileSync(file);
  const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  return new Promise((resolve, reject) => new GLTFLoader().parse(buffer, '', resolve, reject));
}

/** The OSD manifests: fixture file per (shape, level, mode) for the untagged rows. */
function manifest(dir, key) {
  const map = new Map();
  for (const line of readFileSync(join(root, 'tests', 'fixtures', dir, 'MANIFEST.tsv'), 'utf8').split('\n')) {
    if (!line || line.startsWith('#')) continue;
    const cols = line.split('\t');
    const k = key(cols);
    if (k) map.set(k, cols[0]);
  }
  return map;
}
const stem = (input) => input.replace(/^.*\//, '').replace(/\.obj$/, '');
const osdPositions = manifest('osd', ([, , boundary, level, input]) => boundary === 'edge-and-corner' && `${stem(input)}/${level}`);
const osdUvs = manifest('osd_fvar', ([, , boundary, level, input, mode, tagged]) =>
  tagged === 'no' && boundary === 'edge-and-corner' && `${stem(input)}/${level}/${mode}`);

/** v, vt and f lines of an OBJ file, 0-based; a corner without vt has t = -1. */
function parseObj(text) {
  const v = [], vt = [], faces = [];
  for (const line of text.split('\n')) {
    const w = line.trim().split(/\s+/);
    if (w[0] === 'v') v.push(w.slice(1, 4).map(Number));
    else if (w[0] === 'vt') vt.push(w.slice(1, 3).map(Number));
    else if (w[0] === 'f') faces.push(w.slice(1).map((c) => { const [a, b] = c.split('/'); return [Number(a) - 1, b ? Number(b) - 1 : -1]; }));
  }
  return { v, vt, faces };
}

/** OpenSubdiv's result as faces of [x, y, z, u, v] corners. */
function osdReference(shape, level, mode) {
  const posFile = osdPositions.get(`${shape}/${level}`);
  const uvFile = osdUvs.get(`${shape}/${level}/${mode ?? 'corners-plus1'}`);
  assert.ok(posFile && uvFile, `OpenSubdiv fixtures for ${shape} level ${level} ${mode}`);
  const pos = parseObj(readFileSync(join(root, 'tests', 'fixtures', 'osd', posFile), 'utf8'));
  const uv = parseObj(readFileSync(join(root, 'tests', 'fixtures', 'osd_fvar', uvFile), 'utf8'));
  assert.equal(uv.faces.length, pos.faces.length, `${posFile} and ${uvFile}: face counts`);
  return uv.faces.map((face, f) => face.map(([vi, ti], k) => {
    assert.equal(vi, pos.faces[f][k][0], `${posFile} and ${uvFile}: face ${f} corner ${k}`);
    return [...pos.v[vi], ...uv.vt[ti]];
  }));
}

/** A subsurf mesh with a uv channel (result or input) as faces of [x, y, z, u, v] corners. */
function meshFaces(mesh) {
  const uv = mesh.attributes.uv;
  const faces = [];
  let c = 0;
  for (const n of mesh.faceSizes) {
    const face = [];
    for (let k = 0; k < n; k++, c++) {
      const v = mesh.indices[c], t = uv.indices[c];
      face.push([mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2], uv.array[2 * t], uv.array[2 * t + 1]]);
    }
    faces.push(face);
  }
  return faces;
}

/**
 * The OBJ mesh with each vt index replaced by the first with the same value: glTF keeps values,
 * not indices, so two vt lines with equal values are one UV there (OpenSubdiv, which compares
 * indices, sees a seam between them). Also returns whether some vertex had two such indices.
 */
function uvsByValue(mesh) {
  const uv = mesh.attributes.uv;
  const first = new Map(), remap = new Uint32Array(uv.array.length / 2);
  remap.forEach((_, t) => {
    const k = `${uv.array[2 * t]},${uv.array[2 * t + 1]}`;
    if (!first.has(k)) first.set(k, t);
    remap[t] = first.get(k);
  });
  const indices = uv.indices.map((t) => remap[t]);
  const pairs = new Set(), merged = new Set();
  mesh.indices.forEach((v, c) => {
    pairs.add(`${v}/${uv.indices[c]}`);
    merged.add(`${v}/${indices[c]}`);
  });
  return [{ ...mesh, attributes: { uv: { ...uv, indices } } }, merged.size < pairs.size];
}

// ---- comparing

/** The largest |coordinate| of faces of corners, at least 1: positions are compared relative to it. */
function scaleOf(faces) {
  let m = 1;
  for (const face of faces) for (const c of face) for (let k = 0; k < 3; k++) m = Math.max(m, Math.abs(c[k]));
  return m;
}

/**
 * A nearest-value lookup of [x, y, z, u, v] points: distance = max(|position difference| / scale,
 * |uv difference|), the points on a grid of cell 4 × tolerance in position.
 */
class Points {
  constructor(scale) {
    this.scale = scale;
    this.cell = 4 * TOLERANCE * scale;
    this.grid = new Map();
    this.points = [];
  }
  key(x, y, z) {
    return `${Math.floor(x / this.cell)},${Math.floor(y / this.cell)},${Math.floor(z / this.cell)}`;
  }
  add(p) {
    const k = this.key(p[0], p[1], p[2]);
    if (!this.grid.has(k)) this.grid.set(k, []);
    this.grid.get(k).push(this.points.length);
    this.points.push(p);
    return this.points.length - 1;
  }
  distance(a, b) {
    let d = 0;
    for (let k = 0; k < 3; k++) d = Math.max(d, Math.abs(a[k] - b[k]) / this.scale);
    return Math.max(d, Math.abs(a[3] - b[3]), Math.abs(a[4] - b[4]));
  }
  /** [index, distance] of the nearest point, or [-1, Infinity]. */
  nearest(p) {
    let best = -1, bestD = Infinity;
    const cx = Math.floor(p[0] / this.cell), cy = Math.floor(p[1] / this.cell), cz = Math.floor(p[2] / this.cell);
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      for (const i of this.grid.get(`${cx + dx},${cy + dy},${cz + dz}`) ?? []) {
        const d = this.distance(p, this.points[i]);
        if (d < bestD) [best, bestD] = [i, d];
      }
    }
    return [best, bestD];
  }
}

/**
 * Asserts that the output geometry's triangles are the reference's faces: each corner's
 * (position, uv) within the tolerance of the reference's (the output's v flipped back: glTF's
 * 1 - v), every reference face present (a quad as either pair of triangles), nothing else.
 */
function assertSameFaces(geometry, reference, what) {
  const scale = scaleOf(reference);
  // Reference corner values, those within the tolerance of each other as one.
  const values = new Points(scale);
  const refFaces = reference.map((face) => face.map((c) => {
    const [i, d] = values.nearest(c);
    return d <= TOLERANCE ? i : values.add(c);
  }));
  const position = geometry.getAttribute('position'), uv = geometry.getAttribute('uv');
  assert.ok(uv, `${what}: the output has a uv attribute`);
  const idOf = new Int32Array(position.count);
  const hit = new Uint8Array(values.points.length);
  for (let i = 0; i < position.count; i++) {
    const p = [position.getX(i), position.getY(i), position.getZ(i), uv.getX(i), 1 - uv.getY(i)];
    const [j, d] = values.nearest(p);
    assert.ok(j >= 0 && d <= TOLERANCE, `${what}: output vertex ${i} (${p.join(', ')}) is no reference corner (nearest differs by ${d})`);
    const t = (tally[against] ??= { comparisons: 0, worst: 0, where: '' });
    if (d > t.worst) [t.worst, t.where] = [d, what];
    idOf[i] = j;
    hit[j] = 1;
    corners++;
  }
  const missed = hit.indexOf(0);
  assert.equal(missed, -1, `${what}: reference corner ${values.points[missed]} is in no output vertex`);
  // Output triangles as a multiset of rotation-normalised (a, b, c) keys.
  const tris = new Map();
  const tkey = (a, b, c) => (a < b && a < c ? `${a},${b},${c}` : b < c ? `${b},${c},${a}` : `${c},${a},${b}`);
  const index = geometry.index.array;
  for (let t = 0; t < index.length; t += 3) {
    const [a, b, c] = [idOf[index[t]], idOf[index[t + 1]], idOf[index[t + 2]]];
    assert.ok(a !== b && b !== c && c !== a, `${what}: output triangle ${t / 3} has two corners of one reference value`);
    const k = tkey(a, b, c);
    tris.set(k, (tris.get(k) ?? 0) + 1);
  }
  const take = (...keys) => {
    if (!keys.every((k) => tris.get(k) > 0)) return false;
    for (const k of keys) tris.set(k, tris.get(k) - 1);
    return true;
  };
  refFaces.forEach((f, i) => {
    let ok;
    if (f.length === 3) ok = take(tkey(f[0], f[1], f[2]));
    else if (f.length === 4) ok = take(tkey(f[0], f[1], f[2]), tkey(f[0], f[2], f[3])) || take(tkey(f[1], f[2], f[3]), tkey(f[1], f[3], f[0]));
    else assert.fail(`${what}: reference face ${i} has ${f.length} corners`);
    assert.ok(ok, `${what}: reference face ${i} (${f.map((j) => values.points[j].slice(0, 3).join(' ')).join(' | ')}) is not in the output`);
  });
  let extra = 0;
  for (const n of tris.values()) extra += n;
  assert.equal(extra, 0, `${what}: ${extra} output triangles are no reference face's`);
  tally[against].comparisons++;
}

/** `edgeCounts` of `geometry`, asserted to be counts (no edge used twice one way, boundaries closed). */
function countEdges(geometry, what) {
  const counts = edgeCounts(geometry);
  assert.equal(typeof counts, 'object', `${what}: ${counts}`);
  return counts;
}

function assertWatertight(input, output, levels, what) {
  const a = countEdges(input, `${what} (input)`), b = countEdges(output, what);
  assert.equal(b.boundary, a.boundary * 2 ** levels, `${what}: output boundary edges (input has ${a.boundary})`);
  assert.equal(b.loops, a.loops, `${what}: boundary loops`);
  return a.boundary === 0;
}

/** The largest angle between the normals of the two triangles of a quad, either diagonal. */
function largestFold(mesh) {
  const p = (v) => [mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]];
  const normal = (a, b, c) => {
    const [u, v] = [p(b).map((x, k) => x - p(a)[k]), p(c).map((x, k) => x - p(a)[k])];
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
  };
  const angle = (m, n) => Math.acos(Math.max(-1, Math.min(1, (m[0] * n[0] + m[1] * n[1] + m[2] * n[2]) / Math.hypot(...m) / Math.hypot(...n))));
  let largest = 0, c = 0;
  for (const n of mesh.faceSizes) {
    if (n === 4) {
      const [a, b, d, e] = mesh.indices.subarray(c, c + 4);
      largest = Math.max(largest, angle(normal(a, b, d), normal(a, d, e)), angle(normal(b, d, e), normal(b, e, a)));
    }
    c += n;
  }
  return largest;
}

// ---- the fixtures

const files = readdirSync(fixtures).filter((f) => f.endsWith('.glb')).sort();
assert.ok(files.length >= 10, 'the fixtures are there');
const closedShapes = [];
for (const file of files) {
  const name = file.replace(/\.glb$/, '');
  const gltf = await loadGlb(join(fixtures, file));
  const mesh = gltf.scene.getObjectByProperty('isMesh', true);
  const geometry = mesh.geometry;
  const extras = geometry.userData.subsurf;
  const [obj, equalValueSeams] = uvsByValue(readObj(readFileSync(join(root, extras.source), 'utf8')));
  // OpenSubdiv's fixtures see seams between equal vt values that glTF cannot express: compare
  // such shapes with subdivide on the OBJ with those values joined instead.
  const quadRef = (mode) => (equalValueSeams ? meshFaces(subdivide(obj, { levels: LEVELS, fvarLinear: mode })) : osdReference(name, LEVELS, mode));
  const loopRef = (mode) => (equalValueSeams ? meshFaces(subdivide(obj, { scheme: 'loop', levels: LEVELS, fvarLinear: mode })) : osdReference(name, LEVELS, mode));
  const by = equalValueSeams ? 'subdivide on the OBJ (equal vt values joined)' : 'OpenSubdiv';
  const sizes = new Set(obj.faceSizes);
  const allTriangles = sizes.size === 1 && sizes.has(3), allQuads = sizes.size === 1 && sizes.has(4);
  const tri = triangulated(obj, (f) => Number(extras.diagonals[f]));

  await check(`${name}: the glTF is the OBJ as the recorded triangulation splits it`, () => {
    assert.deepEqual(Array.from(obj.faceSizes), extras.faceSizes);
    assert.equal(geometry.index.count, tri.indices.length);
    const position = geometry.getAttribute('position'), uv = geometry.getAttribute('uv');
    const split = new Set();
    for (let c = 0; c < tri.indices.length; c++) {
      const g = geometry.index.getX(c), v = tri.indices[c], t = tri.attributes.uv.indices[c];
      [position.getX(g), position.getY(g), position.getZ(g)].forEach((x, k) => assert.equal(x, obj.positions[3 * v + k], `corner ${c} position`));
      assert.equal(uv.getX(g), obj.attributes.uv.array[2 * t], `corner ${c} u`);
      assert.equal(uv.getY(g), Math.fround(1 - obj.attributes.uv.array[2 * t + 1]), `corner ${c} v`);
      split.add(`${v}/${t}`);
    }
    assert.equal(position.count, split.size, 'one glTF vertex per (v, vt value) pair');
  });

  const before = [geometry.index.array.slice(), geometry.getAttribute('position').data.array.slice()];
  const variants = [];
  if (allTriangles) {
    for (const mode of MODES) variants.push({ label: `Loop, fvarLinear ${mode ?? 'default'}, = ${by}`, options: { scheme: 'loop', fvarLinear: mode }, ref: () => loopRef(mode) });
  } else {
    variants.push({ label: 'Loop = subdivide on the triangulated OBJ', options: { scheme: 'loop' }, ref: () => meshFaces(subdivide(tri, { scheme: 'loop', levels: LEVELS })) });
  }
  if (allQuads) {
    // quads: true joins two triangles only if they fold by at most 40° (both diagonals, as
    // Blender's "Tris to Quads"); where the shape's quads fold more, the thresholds are raised
    // just past its largest fold, after checking that the default leaves some quads split.
    const fold = largestFold(obj);
    let quads = true;
    if (fold > (40 * Math.PI) / 180) {
      await check(`${name}: quads folded by up to ${((fold * 180) / Math.PI).toFixed(1)}°: quads: true leaves some as triangles`, () => {
        const out = subdivideGeometry(geometry, { quads: true, levels: 1, normals: false });
        assert.ok(out.index.count / 3 > 8 * obj.faceSizes.length, `${out.index.count / 3} triangles`);
      });
      const angle = Math.min(Math.PI, fold + 0.02);
      quads = { faceAngle: angle, shapeAngle: angle };
    }
    const label = quads === true ? 'quads: true' : `quads: { faceAngle, shapeAngle: ${((quads.faceAngle * 180) / Math.PI).toFixed(1)}° }`;
    for (const mode of MODES) variants.push({ label: `${label}, Catmull-Clark, fvarLinear ${mode ?? 'default'}, = ${by} on the quads`, options: { quads, fvarLinear: mode }, ref: () => quadRef(mode) });
  }
  for (const mode of ['none', 'all']) {
    variants.push({ label: `Catmull-Clark on the triangles, fvarLinear ${mode}, = subdivide on the triangulated OBJ`, options: { fvarLinear: mode }, ref: () => meshFaces(subdivide(tri, { levels: LEVELS, fvarLinear: mode })) });
  }
  for (const { label, options, ref } of variants) {
    await check(`${name}: ${label}, level ${LEVELS}; watertight where the input is`, () => {
      for (const k of Object.keys(options)) if (options[k] === undefined) delete options[k];
      const out = subdivideGeometry(geometry, { ...options, levels: LEVELS, normals: false });
      const reference = ref();
      against = label.includes('= OpenSubdiv') ? 'OpenSubdiv' : 'subdivide';
      assertSameFaces(out, reference, `${name}, ${label}`);
      if (assertWatertight(geometry, out, LEVELS, `${name}, ${label}`) && !closedShapes.includes(name)) closedShapes.push(name);
    });
  }
  await check(`${name}: the loaded geometry is left as it was`, () => {
    assert.deepEqual(geometry.index.array, before[0]);
    assert.deepEqual(geometry.getAttribute('position').data.array, before[1], 'the interleaved position/uv buffer');
  });
}

// ---- bad input, on a geometry GLTFLoader made
await check('bad input: a glTF geometry without position; quads: true with Loop', async () => {
  const gltf = await loadGlb(join(fixtures, 'catmark_cube.glb'));
  const geometry = gltf.scene.getObjectByProperty('isMesh', true).geometry;
  assert.throws(() => subdivideGeometry(geometry, { quads: true, scheme: 'loop' }), /quads: true.*'loop' takes triangles only/);
  const noPosition = geometry.clone();
  noPosition.deleteAttribute('position');
  assert.throws(() => subdivideGeometry(noPosition, { levels: 1 }), /no 'position' attribute; it has 'uv'/);
  // The original is untouched and still subdivides.
  assert.equal(subdivideGeometry(geometry, { levels: 1, quads: true }).index.count, 6 * 4 * 6);
});

console.log(`gltf: ${files.length} fixtures (${closedShapes.length} closed), ${corners} output vertices compared, tolerance ${TOLERANCE}`);
for (const [name, t] of Object.entries(tally)) {
  console.log(`gltf:   against ${name}: ${t.comparisons} comparisons, worst difference ${t.worst.toExponential(2)} (${t.where})`);
}
finish();
