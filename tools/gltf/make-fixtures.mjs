// Writes the glTF fixtures of tests/js/gltf.mjs: OpenSubdiv regression shapes with UVs, as a glTF
// exporter writes them, into tests/fixtures/gltf/<shape>.glb, and tests/fixtures/gltf/MANIFEST.tsv.
//
//   scripts/build-pkg.sh && node tools/gltf/make-fixtures.mjs
//
// Input: tests/meshes/osd/<shape>.obj (OpenSubdiv 3.6.0's regression shapes, byte-identical to
// ../shared/meshes/osd/; Apache License 2.0 with modification, © Pixar: see SOURCES.md there and
// each file's first line), read with the package's own OBJ reader (pkg/node.js: readObj). Tags
// (creases, corners, interpolateboundary, ...) are not written: glTF has none.
//
// Each .glb has one mesh of one triangle primitive, as exporters write them:
//   - triangles: a triangle as it is; a quad split along its shorter diagonal (ties: 0-2 on even
//     faces, 1-3 on odd ones, so both occur on regular grids); any other polygon fanned from its
//     first corner. The primitive's `extras.subsurf` records it: `source` (the OBJ path),
//     `faceSizes` and `diagonals` (one character per OBJ face: '0' = corners 0-2, '1' = corners 1-3,
//     '-' for a face that is not a quad), so a test can rebuild the polygons.
//   - vertices split where the UV differs: one glTF vertex per distinct (OBJ v, vt value) pair,
//     in order of first use (two vt lines with equal values are one UV, as for any exporter);
//   - POSITION: the OBJ's positions as Float32 (as readObj reads them); TEXCOORD_0: (u, 1 - v)
//     in Float32, since glTF's UV origin is the image's top left corner and OBJ's its bottom
//     left (Blender's and three's exporters flip the same way); no NORMAL (subdivideGeometry
//     computes its own normals); indices uint16; POSITION and TEXCOORD_0 interleaved in one
//     buffer view (glTF-Transform's default vertex layout), so GLTFLoader gives
//     InterleavedBufferAttributes.
// Re-running gives byte-identical files.
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { Document, NodeIO } from '@gltf-transform/core';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const { readObj } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);
const out = join(root, 'tests', 'fixtures', 'gltf');

/** The shapes, and what each brings. */
export const SHAPES = [
  // all triangles
  ['loop_tetrahedron', 'triangles, closed, smallest'],
  ['loop_cube', 'triangles, closed, UV seams (cube cross)'],
  ['loop_icosahedron', 'triangles, closed, valence 5'],
  ['loop_toroidal_tet', 'triangles, closed, genus 1'],
  ['loop_fvar_bound1', 'triangles, boundary, UV seams inside'],
  ['loop_xord_boundary', 'triangles, boundary, extraordinary boundary vertices'],
  ['loop_saddle_edgecorner', 'triangles, boundary, non-planar'],
  // all quads
  ['catmark_cube', 'quads, closed, UV seams (cube cross)'],
  ['catmark_torus', 'quads, closed, UV seams on both loops'],
  ['catmark_toroidal_tet', 'quads, closed, genus 1'],
  ['catmark_lefthanded', 'quads, closed, 434 faces, many UV islands'],
  ['catmark_fvar_bound1', 'quads, boundary, UV seams inside'],
  ['catmark_edgecorner', 'quads, boundary'],
  ['catmark_xord_interior', 'quads, boundary, extraordinary interior vertices'],
  // triangles, quads and n-gons
  ['catmark_pyramid', 'triangles + quad, closed'],
  ['catmark_gregory_test8', 'quads + pentagons, closed'],
  ['catmark_gregory_test5', 'triangles, quads and hexagons, boundary'],
  ['catmark_nonquads', 'triangles to hexagons, boundary'],
];

function triangulate(mesh) {
  const { positions, indices, faceSizes } = mesh;
  const uv = mesh.attributes.uv;
  const dist2 = (a, b) => {
    let s = 0;
    for (let k = 0; k < 3; k++) s += (positions[3 * a + k] - positions[3 * b + k]) ** 2;
    return s;
  };
  const vertexOf = new Map();
  const pos = [], tex = [], index = [];
  let diagonals = '';
  const vertex = (c) => {
    const v = indices[c], t = uv.indices[c];
    const key = `${v}/${uv.array[2 * t]},${uv.array[2 * t + 1]}`; // by value: equal vt lines make no seam
    if (!vertexOf.has(key)) {
      vertexOf.set(key, pos.length / 3);
      pos.push(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
      tex.push(uv.array[2 * t], Math.fround(1 - uv.array[2 * t + 1]));
    }
    return vertexOf.get(key);
  };
  let c = 0;
  for (let f = 0; f < faceSizes.length; f++) {
    const n = faceSizes[f];
    const ids = [];
    for (let i = 0; i < n; i++) ids.push(vertex(c + i));
    let r = 0;
    if (n === 4) {
      const d02 = dist2(indices[c], indices[c + 2]), d13 = dist2(indices[c + 1], indices[c + 3]);
      r = d13 < d02 ? 1 : d02 < d13 ? 0 : f % 2;
      diagonals += String(r);
    } else {
      diagonals += '-';
    }
    for (let i = 1; i + 1 < n; i++) index.push(ids[r], ids[(r + i) % n], ids[(r + i + 1) % n]);
    c += n;
  }
  return { pos: Float32Array.from(pos), tex: Float32Array.from(tex), index, diagonals };
}

const io = new NodeIO();
mkdirSync(out, { recursive: true });
const rows = [];
for (const [name, what] of SHAPES) {
  const source = `tests/meshes/osd/${name}.obj`;
  const mesh = readObj(readFileSync(join(root, source), 'utf8'));
  if (!mesh.attributes.uv) throw new Error(`${source} has no vt`);
  const { pos, tex, index, diagonals } = triangulate(mesh);
  if (pos.length / 3 > 65535) throw new Error(`${name}: too many vertices for uint16 indices`);

  const doc = new Document();
  const buffer = doc.createBuffer();
  const position = doc.createAccessor('POSITION').setType('VEC3').setArray(pos).setBuffer(buffer);
  const texcoord = doc.createAccessor('TEXCOORD_0').setType('VEC2').setArray(tex).setBuffer(buffer);
  const indices = doc.createAccessor('indices').setType('SCALAR').setArray(Uint16Array.from(index)).setBuffer(buffer);
  const prim = doc.createPrimitive()
    .setAttribute('POSITION', position)
    .setAttribute('TEXCOORD_0', texcoord)
    .setIndices(indices)
    .setExtras({ subsurf: { source, faceSizes: Array.from(mesh.faceSizes), diagonals } });
  const gltfMesh = doc.createMesh(name).addPrimitive(prim);
  doc.createScene(name).addChild(doc.createNode(name).setMesh(gltfMesh));
  const bytes = await io.writeBinary(doc);
  writeFileSync(join(out, `${name}.glb`), bytes);

  const sizes = {};
  for (const n of mesh.faceSizes) sizes[n] = (sizes[n] ?? 0) + 1;
  rows.push([
    `${name}.glb`, source, Object.entries(sizes).map(([n, k]) => `${n}:${k}`).join(' '), index.length / 3,
    mesh.positions.length / 3, pos.length / 3, bytes.length, what,
  ]);
  console.log(`${name}.glb: ${index.length / 3} triangles, ${pos.length / 3} vertices (OBJ: ${mesh.positions.length / 3}), ${bytes.length} bytes`);
}

writeFileSync(
  join(out, 'MANIFEST.tsv'),
  [
    '# glTF fixtures, made by tools/gltf/make-fixtures.mjs (see there and DEVELOPERS.md) with @gltf-transform/core 4.5.1',
    '# from the OpenSubdiv 3.6.0 regression shapes in tests/meshes/osd/ (Apache License 2.0 with modification, © Pixar):',
    '# triangulated (quads along the shorter diagonal, recorded in the primitive\'s extras.subsurf.diagonals; n-gons fanned',
    '# from corner 0), vertices split where the UV value differs, POSITION + TEXCOORD_0 (u, 1 - v) interleaved, no tags.',
    ['# fixture', 'source', 'OBJ faces (size:count)', 'triangles', 'OBJ vertices', 'glTF vertices', 'bytes', 'what it brings'].join('\t'),
    ...rows.map((r) => r.join('\t')),
  ].join('\n') + '\n',
);
