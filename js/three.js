// subsurf/three: subdivision of a three.js BufferGeometry.
//
//   import { subdivideGeometry } from 'subsurf/three';
//   mesh.geometry = subdivideGeometry(mesh.geometry, { levels: 2 });
//
// The triangles of the geometry are welded back into one surface (glTF splits vertices wherever
// UVs or normals differ), optionally joined into quads, subdivided by subsurf's `subdivide`, and
// split again where face-varying data (UV seams, sharp edges) needs it, into a new indexed
// BufferGeometry. The input is never modified. Rules and options: README.md, "three.js".
//
// This file imports subsurf's plain glue ('./subsurf.js'), which must have been initialised
// before the first call. The package's "./three" export does that: in Node it resolves to
// three-node.js (loads the .wasm synchronously, as 'subsurf/node' does), elsewhere to
// three-auto.js (a top-level `await init()`). 'subsurf/three/init' is this file as it is: call
// `await init()` from 'subsurf/init' once first.
import { BufferAttribute, BufferGeometry } from 'three';
import { schemeNames, subdivide, toDrawable, vertexNormals } from './subsurf.js';

/** Options of subdivideGeometry that `subdivide` does not take. */
const OWN_OPTIONS = ['weld', 'quads', 'creaseAngle', 'sharpNormalSplits', 'normals'];
/** Schemes whose first level takes quads (the others take triangles only). */
const QUAD_SCHEMES = ['catmull-clark', 'quad-triangle', 'bilinear', 'doo-sabin'];
/** Blender's "Tris to Quads" defaults: 40 degrees for the face and the shape thresholds. */
const DEFAULT_QUAD_ANGLE = (40 * Math.PI) / 180;
/** Two input normals of one welded vertex differ (sharpNormalSplits) beyond about 1 degree. */
const NORMAL_SPLIT_COS = Math.cos((1 * Math.PI) / 180);
/** Attributes not carried as channels: computed (normal), dropped (tangent) or special. */
const SPECIAL = new Set(['position', 'normal', 'tangent', 'skinIndex', 'skinWeight']);
const INTERNAL = '__subsurf_';
/**
 * three's texture coordinates: always face-varying (as OpenSubdiv and glTF treat UVs), so that
 * `fvarLinear` applies to them with or without seams.
 */
const UV_NAMES = new Set(['uv', 'uv1', 'uv2', 'uv3']);

let initialised = false;

/**
 * Subdivides a triangle BufferGeometry (indexed or not) and returns a new indexed
 * BufferGeometry. See three.d.ts and the README for the options and rules.
 */
export function subdivideGeometry(geometry, options = {}) {
  if (!geometry || geometry.isBufferGeometry !== true) {
    throw new Error(`subdivideGeometry: the first argument must be a THREE.BufferGeometry, got ${describe(geometry)}` +
      (geometry && geometry.isMesh ? ' (a Mesh: pass mesh.geometry)' : ''));
  }
  if (options === null || typeof options !== 'object' || Array.isArray(options)) {
    throw new Error(`subdivideGeometry: options must be an object such as { levels: 2 }, got ${describe(options)}`);
  }
  checkInitialised();
  const own = readOwnOptions(options);
  const passed = {};
  for (const key of Object.keys(options)) {
    if (!OWN_OPTIONS.includes(key) && options[key] !== undefined) passed[key] = options[key];
  }

  // ---- input arrays
  const position = geometry.getAttribute('position');
  if (!position) {
    throw new Error("subdivideGeometry: the geometry has no 'position' attribute; " +
      `it has ${Object.keys(geometry.attributes).map((n) => `'${n}'`).join(', ') || 'no attributes'}`);
  }
  if (position.itemSize !== 3) {
    throw new Error(`subdivideGeometry: the 'position' attribute must have itemSize 3, got ${position.itemSize}`);
  }
  const numInput = position.count;
  const P = readFloats(position, 'position');
  for (let i = 0; i < P.length; i++) {
    if (!Number.isFinite(P[i])) {
      throw new Error(`subdivideGeometry: position of vertex ${Math.floor(i / 3)} is not finite (${P[i]})`);
    }
  }
  const index = geometry.index;
  const cornerCount = index ? index.count : numInput;
  if (cornerCount % 3 !== 0) {
    throw new Error(`subdivideGeometry: the geometry must be a triangle list; its ${index ? 'index' : 'position'} count ` +
      `${cornerCount} is not a multiple of 3`);
  }
  if (cornerCount === 0) throw new Error('subdivideGeometry: the geometry has no triangles');
  let corner; // original vertex of every triangle corner
  if (index) {
    const array = index.array.subarray(0, cornerCount);
    corner = array instanceof Uint32Array ? array : Uint32Array.from(array);
    for (let c = 0; c < cornerCount; c++) {
      if (corner[c] >= numInput) {
        throw new Error(`subdivideGeometry: index[${c}] is ${corner[c]}, but the geometry has only ${numInput} vertices`);
      }
    }
  } else {
    corner = new Uint32Array(cornerCount);
    for (let c = 0; c < cornerCount; c++) corner[c] = c;
  }
  const numTris = cornerCount / 3;

  // ---- weld: bit-identical positions, then (weld > 0) nearer ones
  const welded = weldVertices(P, numInput, corner, own.weld);
  const { weldOf, numWelded, weldedPositions } = welded;
  // Triangles in welded vertices; those whose corners weld together are dropped.
  const keep = new Uint32Array(numTris);
  let numKept = 0;
  for (let t = 0; t < numTris; t++) {
    const a = weldOf[corner[3 * t]], b = weldOf[corner[3 * t + 1]], c = weldOf[corner[3 * t + 2]];
    if (a !== b && b !== c && c !== a) keep[numKept++] = t;
  }
  if (numKept === 0) throw new Error('subdivideGeometry: every triangle is degenerate (its corners weld together)');
  const triV = new Uint32Array(3 * numKept); // original vertex per kept-triangle corner
  const triW = new Uint32Array(3 * numKept); // welded vertex per kept-triangle corner
  for (let k = 0; k < numKept; k++) {
    for (let j = 0; j < 3; j++) {
      triV[3 * k + j] = corner[3 * keep[k] + j];
      triW[3 * k + j] = weldOf[triV[3 * k + j]];
    }
  }
  const copies = weldedCopies(triV, weldOf, numWelded, numInput);

  // ---- groups: each kept triangle in the first input group that covers it (G: none)
  const groups = geometry.groups || [];
  const G = groups.length;
  let triGroup = null;
  if (G > 0) {
    const ofTri = new Int32Array(numTris).fill(G);
    for (let g = G - 1; g >= 0; g--) {
      const { start, count } = groups[g];
      const first = Math.max(0, Math.ceil(start / 3)), end = Math.min(numTris, Math.floor((start + count) / 3));
      for (let t = first; t < end; t++) ofTri[t] = g;
    }
    triGroup = new Int32Array(numKept);
    for (let k = 0; k < numKept; k++) triGroup[k] = ofTri[keep[k]];
  }

  // ---- channels: each attribute vertex-varying, or face-varying where welded copies differ
  const channels = []; // { name, values, itemSize, fv: Int32Array | null, out: 'attribute' | 'morph', ... }
  const instanced = [];
  for (const name of Object.keys(geometry.attributes)) {
    if (SPECIAL.has(name)) continue;
    const attr = geometry.attributes[name];
    if (attr && attr.isInstancedBufferAttribute) {
      instanced.push(name); // per instance, not per vertex: copied as it is
      continue;
    }
    checkCount(attr, numInput, `attribute '${name}'`);
    channels.push(classify(readFloats(attr, name), attr.itemSize, copies, { kind: 'attribute', name }, UV_NAMES.has(name)));
  }
  const morphs = geometry.morphAttributes || {};
  for (const name of Object.keys(morphs)) {
    if (name === 'normal' || !Array.isArray(morphs[name])) continue;
    morphs[name].forEach((attr, i) => {
      checkCount(attr, numInput, `morphAttributes.${name}[${i}]`);
      channels.push(classify(readFloats(attr, `morph ${name}`), attr.itemSize, copies, { kind: 'morph', name, target: i, attr }));
    });
  }
  const fvarChannels = channels.filter((c) => c.fv);
  // Two copies of a welded vertex are one corner class when every face-varying channel agrees.
  const cornerClass = cornerClasses(fvarChannels, copies, numInput);

  // Skin: dense per-bone weight channels over the bones used (chunks of up to 16).
  const skin = readSkin(geometry, numInput, copies);

  // ---- edges, sharp edges, quads
  const userCreases = mapPairs(passed.creases, weldOf, numInput, 'creases');
  const needEdges = own.quads || own.creaseAngle !== undefined || own.sharpNormalSplits ||
    (userCreases && own.normals !== false);
  let edges = null;
  let sharp = null; // Uint8Array per edge: 1 for a crease we add, 2 for a user crease (kept as an edge)
  const ourCreases = [];
  if (needEdges) {
    edges = buildEdges(triW);
    sharp = new Uint8Array(edges.count);
    const normals = own.creaseAngle !== undefined || own.quads ? triangleNormals(triW, weldedPositions) : null;
    if (own.creaseAngle !== undefined) {
      const cosLimit = Math.cos(own.creaseAngle);
      for (let e = 0; e < edges.count; e++) {
        if (edges.uses[e] !== 2 || !edges.opposite(e)) continue;
        const t0 = (edges.h0[e] / 3) | 0, t1 = (edges.h1[e] / 3) | 0;
        const d = normals[3 * t0] * normals[3 * t1] + normals[3 * t0 + 1] * normals[3 * t1 + 1] + normals[3 * t0 + 2] * normals[3 * t1 + 2];
        if (d < cosLimit && isUnit(normals, t0) && isUnit(normals, t1)) sharp[e] = 1;
      }
    }
    if (own.sharpNormalSplits) {
      const normal = geometry.getAttribute('normal');
      if (normal) {
        checkCount(normal, numInput, "attribute 'normal'");
        const N = readFloats(normal, 'normal');
        const differ = (u, v) => {
          if (u === v) return false;
          const a = Math.hypot(N[3 * u], N[3 * u + 1], N[3 * u + 2]), b = Math.hypot(N[3 * v], N[3 * v + 1], N[3 * v + 2]);
          const d = N[3 * u] * N[3 * v] + N[3 * u + 1] * N[3 * v + 1] + N[3 * u + 2] * N[3 * v + 2];
          return !(d >= NORMAL_SPLIT_COS * a * b);
        };
        for (let e = 0; e < edges.count; e++) {
          if (edges.uses[e] !== 2 || !edges.opposite(e)) continue;
          const h0 = edges.h0[e], h1 = edges.h1[e]; // h0: a -> b, h1: b -> a
          const a0 = triV[h0], b0 = triV[next3(h0)], b1 = triV[h1], a1 = triV[next3(h1)];
          if (differ(a0, a1) && differ(b0, b1)) sharp[e] = 1;
        }
      }
    }
    for (let e = 0; e < edges.count; e++) if (sharp[e]) ourCreases.push(edges.a[e], edges.b[e]);
    if (userCreases) {
      for (let i = 0; i < userCreases.pairs.length; i += 2) {
        const e = edges.find(userCreases.pairs[i], userCreases.pairs[i + 1]);
        if (e >= 0) sharp[e] = userCreases.sharpness(i / 2) >= 10 ? 3 : 2;
      }
    }
  }
  const holeTris = mapHoles(passed.holes, keep, numKept, numTris);

  // Polygons: the kept triangles, pairs of them joined into quads with `quads`.
  const poly = own.quads
    ? joinQuads(triV, triW, numKept, edges, sharp, triGroup, cornerClass, holeTris, weldedPositions, own.quads)
    : trianglePolygons(triV, triW, numKept, triGroup);

  // ---- the mesh and options for subdivide
  const polyCount = poly.sizes.length;
  const attributes = {};
  const used = new Set([...Object.keys(geometry.attributes)]);
  const internal = (base) => {
    let name = INTERNAL + base;
    while (used.has(name)) name += '_';
    used.add(name);
    return name;
  };
  for (const ch of channels) {
    ch.key = ch.kind === 'attribute' ? ch.name : internal(`morph_${ch.name}_${ch.target}`);
    if (ch.fv) {
      const indices = new Uint32Array(poly.V.length);
      for (let k = 0; k < indices.length; k++) indices[k] = ch.fv[poly.V[k]];
      attributes[ch.key] = { array: ch.values, itemSize: ch.itemSize, indices };
    } else {
      attributes[ch.key] = { array: gatherWelded(ch.values, ch.itemSize, copies), itemSize: ch.itemSize };
    }
  }
  if (skin) {
    skin.keys = skin.chunks.map((chunk, i) => {
      const key = internal(`skin${i}`);
      attributes[key] = chunk;
      return key;
    });
  }
  let groupKey = null;
  if (G > 0) {
    // Face-varying, constant per group (one value per group): every refined face corner gets its
    // parent face's group, whatever the scheme, holes or levels.
    groupKey = internal('group');
    const array = new Float32Array(G + 1);
    for (let g = 0; g <= G; g++) array[g] = g;
    const indices = new Uint32Array(poly.V.length);
    for (let f = 0; f < polyCount; f++) {
      for (let k = poly.starts[f]; k < poly.starts[f] + poly.sizes[f]; k++) indices[k] = poly.group[f];
    }
    attributes[groupKey] = { array, itemSize: 1, indices };
  }
  let sidesKey = null;
  if (sharp && own.normals !== false && sharp.some((s) => s === 1 || s === 3)) {
    // Face-varying "smoothing fans": the corners around a vertex, split at infinitely sharp
    // edges; the refined vertices on those edges get one normal per side.
    sidesKey = internal('sides');
    const root = smoothingFans(triW, numKept, edges, sharp);
    const indices = new Uint32Array(poly.V.length);
    for (let k = 0; k < indices.length; k++) indices[k] = root[poly.triCorner[k]];
    attributes[sidesKey] = { array: new Float32Array(3 * numKept), itemSize: 1, indices };
  }

  const mesh = { positions: weldedPositions, indices: poly.W, attributes };
  if (poly.sizes.some((s) => s !== 3)) mesh.faceSizes = poly.sizes;
  const subdivideOptions = { ...passed, normals: own.normals === true };
  delete subdivideOptions.creases;
  delete subdivideOptions.corners;
  delete subdivideOptions.holes;
  if (ourCreases.length || userCreases) {
    // Ours first, the user's last: an edge named twice takes the last sharpness.
    const n = ourCreases.length / 2 + (userCreases ? userCreases.pairs.length / 2 : 0);
    const edgesArray = new Uint32Array(2 * n), sharpness = new Float32Array(n);
    edgesArray.set(ourCreases);
    sharpness.fill(10, 0, ourCreases.length / 2);
    if (userCreases) {
      edgesArray.set(userCreases.pairs, ourCreases.length);
      for (let i = 0; i < userCreases.pairs.length / 2; i++) sharpness[ourCreases.length / 2 + i] = userCreases.sharpness(i);
    }
    subdivideOptions.creases = { edges: edgesArray, sharpness };
  }
  if (passed.corners !== undefined) subdivideOptions.corners = mapCorners(passed.corners, weldOf, numInput);
  if (holeTris) {
    const holes = [];
    for (let f = 0; f < polyCount; f++) if (holeTris[poly.firstTri[f]]) holes.push(f);
    subdivideOptions.holes = Uint32Array.from(holes);
  }

  const out = subdivide(mesh, subdivideOptions);
  const outVertices = out.positions.length / 3;
  const outFaces = out.faceSizes.length;

  // ---- drawable: one vertex per distinct (vertex, face-varying values)
  const split = {};
  for (const ch of fvarChannels) split[ch.key] = out.attributes[ch.key];
  if (sidesKey) split[sidesKey] = out.attributes[sidesKey];
  let draw;
  if (Object.keys(split).length) {
    draw = toDrawable({ positions: out.positions, indices: out.indices, faceSizes: out.faceSizes, attributes: split });
  } else {
    draw = { positions: out.positions, indices: out.indices, triangles: out.triangles, origins: null, attributes: {} };
  }
  const drawCount = draw.positions.length / 3;
  const origins = draw.origins;
  const gather = (values, itemSize) => gatherRows(values, itemSize, origins, drawCount);

  // Normals: limit (subdivide's) or from the faces, one per side along sharp edges.
  let sides = null;
  if (sidesKey) sides = sideTopology(out, draw, out.attributes[sidesKey], outVertices);
  const normalsFor = (positions, limitNormals) => {
    const base = own.normals === 'faces'
      ? vertexNormals({ positions, indices: out.indices, faceSizes: out.faceSizes })
      : limitNormals;
    const normals = gather(base, 3);
    if (sides) applySideNormals(normals, sides, positions, out);
    return normals;
  };

  const result = new BufferGeometry();
  result.name = geometry.name;
  try {
    result.userData = JSON.parse(JSON.stringify(geometry.userData)); // as BufferGeometry.copy does
  } catch {
    result.userData = { ...geometry.userData };
  }
  for (const name of instanced) result.setAttribute(name, geometry.attributes[name].clone());
  result.setAttribute('position', new BufferAttribute(draw.positions, 3));
  if (own.normals !== false) result.setAttribute('normal', new BufferAttribute(normalsFor(out.positions, out.normals), 3));
  const morphOut = {};
  for (const ch of channels) {
    const refined = out.attributes[ch.key];
    const array = ch.fv ? draw.attributes[ch.key].array : gather(refined.array, ch.itemSize);
    const attr = new BufferAttribute(array, ch.itemSize);
    if (ch.kind === 'attribute') {
      result.setAttribute(ch.name, attr);
    } else {
      attr.name = ch.attr.name;
      (morphOut[ch.name] ||= [])[ch.target] = attr;
      ch.refined = refined.array;
    }
  }
  if (skin) {
    const { indices, weights } = topFourWeights(skin, skin.keys.map((k) => out.attributes[k].array), outVertices);
    result.setAttribute('skinIndex', new BufferAttribute(gatherTyped(indices, 4, origins, drawCount, skin.IndexArray), 4));
    result.setAttribute('skinWeight', new BufferAttribute(gather(weights, 4), 4));
  }
  // Morph normals: the normals of the refined morphed surface (relative: minus the base ones).
  const morphNormals = Array.isArray(morphs.normal) && morphs.normal.length > 0 && own.normals !== false;
  if (morphNormals) {
    const positionMorphs = channels.filter((c) => c.kind === 'morph' && c.name === 'position');
    morphOut.normal = morphs.normal.map((attr, i) => {
      const ch = positionMorphs.find((c) => c.target === i);
      let normals;
      if (!ch) {
        normals = geometry.morphTargetsRelative ? new Float32Array(3 * drawCount) : result.getAttribute('normal').array.slice();
      } else {
        const moved = new Float32Array(out.positions.length);
        const refined = ch.fv ? perVertex(out.attributes[ch.key], out.indices, outVertices) : ch.refined;
        for (let k = 0; k < moved.length; k++) moved[k] = geometry.morphTargetsRelative ? out.positions[k] + refined[k] : refined[k];
        let limitNormals = null;
        if (own.normals === true) {
          // Subdivide the morphed cage with the same options (positions only) for its normals.
          const cage = gatherWelded(ch.values, 3, copies);
          if (geometry.morphTargetsRelative) for (let k = 0; k < cage.length; k++) cage[k] += weldedPositions[k];
          const cageMesh = { positions: cage, indices: mesh.indices };
          if (mesh.faceSizes) cageMesh.faceSizes = mesh.faceSizes;
          limitNormals = subdivide(cageMesh, { ...subdivideOptions, normals: true }).normals;
        }
        normals = normalsFor(moved, limitNormals);
        if (geometry.morphTargetsRelative) {
          const baseNormals = result.getAttribute('normal').array;
          for (let k = 0; k < normals.length; k++) normals[k] -= baseNormals[k];
        }
      }
      const out2 = new BufferAttribute(normals, 3);
      out2.name = attr.name;
      return out2;
    });
  }
  if (Object.keys(morphOut).length) {
    for (const name of Object.keys(morphOut)) result.morphAttributes[name] = morphOut[name];
    result.morphTargetsRelative = geometry.morphTargetsRelative;
  }

  // ---- index, in group order
  let triangles = draw.triangles;
  if (G > 0) {
    const groupValues = out.attributes[groupKey];
    const faceGroup = new Uint32Array(outFaces);
    const faceStart = new Uint32Array(outFaces + 1);
    let k = 0;
    for (let f = 0; f < outFaces; f++) {
      faceGroup[f] = Math.round(groupValues.array[groupValues.indices[k]]);
      faceStart[f + 1] = faceStart[f] + 3 * (out.faceSizes[f] - 2);
      k += out.faceSizes[f];
    }
    const counts = new Uint32Array(G + 2);
    for (let f = 0; f < outFaces; f++) counts[faceGroup[f] + 1] += faceStart[f + 1] - faceStart[f];
    for (let g = 0; g <= G; g++) counts[g + 1] += counts[g];
    const sorted = new Uint32Array(triangles.length);
    const cursor = counts.slice(0, G + 1);
    for (let f = 0; f < outFaces; f++) {
      const g = faceGroup[f];
      sorted.set(triangles.subarray(faceStart[f], faceStart[f + 1]), cursor[g]);
      cursor[g] += faceStart[f + 1] - faceStart[f];
    }
    triangles = sorted;
    for (let g = 0; g < G; g++) result.addGroup(counts[g], counts[g + 1] - counts[g], groups[g].materialIndex);
  }
  result.setIndex(new BufferAttribute(drawCount > 65536 ? triangles : Uint16Array.from(triangles), 1));
  return result;
}

// ---------------------------------------------------------------------------------------------
// Options

function readOwnOptions(options) {
  const own = { weld: 0, quads: false, creaseAngle: undefined, sharpNormalSplits: false, normals: true };
  if (options.weld !== undefined) {
    if (typeof options.weld !== 'number' || !(options.weld >= 0) || !Number.isFinite(options.weld)) {
      throw new Error(`subdivideGeometry: weld must be a distance >= 0 (0: only bit-identical positions), got ${describe(options.weld)}`);
    }
    own.weld = options.weld;
  }
  if (options.creaseAngle !== undefined) {
    const a = options.creaseAngle;
    if (typeof a !== 'number' || !(a >= 0)) {
      throw new Error(`subdivideGeometry: creaseAngle must be an angle in radians >= 0, got ${describe(a)}`);
    }
    if (a > Math.PI) {
      throw new Error(`subdivideGeometry: creaseAngle is in radians, from 0 to Math.PI; got ${a} ` +
        `(for ${a} degrees write ${a} * Math.PI / 180)`);
    }
    own.creaseAngle = a;
  }
  if (options.sharpNormalSplits !== undefined) {
    if (typeof options.sharpNormalSplits !== 'boolean') {
      throw new Error(`subdivideGeometry: sharpNormalSplits must be true or false, got ${describe(options.sharpNormalSplits)}`);
    }
    own.sharpNormalSplits = options.sharpNormalSplits;
  }
  if (options.normals !== undefined) {
    if (options.normals !== true && options.normals !== false && options.normals !== 'faces') {
      throw new Error(`subdivideGeometry: normals must be true (the limit surface's), 'faces' or false, got ${describe(options.normals)}`);
    }
    own.normals = options.normals;
  }
  const q = options.quads;
  if (q !== undefined && q !== false) {
    if (q !== true && (q === null || typeof q !== 'object')) {
      throw new Error(`subdivideGeometry: quads must be true, false or { faceAngle, shapeAngle } (radians), got ${describe(q)}`);
    }
    const angle = (key) => {
      const v = q === true ? undefined : q[key];
      if (v === undefined) return DEFAULT_QUAD_ANGLE;
      if (typeof v !== 'number' || !(v >= 0 && v <= Math.PI)) {
        throw new Error(`subdivideGeometry: quads.${key} must be an angle in radians from 0 to Math.PI, got ${describe(v)}`);
      }
      return v;
    };
    own.quads = { faceAngle: angle('faceAngle'), shapeAngle: angle('shapeAngle') };
    const scheme = options.scheme === undefined ? 'catmull-clark' : Array.isArray(options.scheme) ? options.scheme[0] : options.scheme;
    if (typeof scheme === 'string' && !QUAD_SCHEMES.includes(scheme)) {
      throw new Error(`subdivideGeometry: quads: true joins triangles into quads for Catmull-Clark, but the scheme ` +
        `'${scheme}' takes triangles only; use scheme 'catmull-clark' (or ${QUAD_SCHEMES.slice(1).map((s) => `'${s}'`).join(', ')}), ` +
        `or leave quads off`);
    }
  }
  return own;
}

function checkInitialised() {
  if (initialised) return;
  try {
    schemeNames();
  } catch (error) {
    throw new Error("subdivideGeometry: subsurf's WebAssembly module is not initialised: in a browser call " +
      "`await init()` (import init from 'subsurf/init') once first, or import 'subsurf/three' instead of " +
      `'subsurf/three/init' (it initialises the module itself, in Node too) (${error && error.message})`);
  }
  initialised = true;
}

function describe(value) {
  if (value === null) return 'null';
  if (value === undefined) return 'undefined';
  if (typeof value === 'string') return `'${value}'`;
  if (typeof value !== 'object') return String(value);
  if (Array.isArray(value)) return 'an Array';
  const name = value.constructor && value.constructor.name;
  return name && name !== 'Object' ? `a ${name}` : 'an object';
}

// ---------------------------------------------------------------------------------------------
// Reading attributes

function checkCount(attr, count, what) {
  if (!attr || typeof attr.itemSize !== 'number' || typeof attr.count !== 'number') {
    throw new Error(`subdivideGeometry: ${what} is not a BufferAttribute`);
  }
  if (attr.count !== count) {
    throw new Error(`subdivideGeometry: ${what} has ${attr.count} items but 'position' has ${count}`);
  }
  if (!(attr.itemSize >= 1 && attr.itemSize <= 16)) {
    throw new Error(`subdivideGeometry: ${what} has itemSize ${attr.itemSize}; subsurf carries 1 to 16 floats per vertex`);
  }
}

function denormalizer(array) {
  if (array instanceof Uint8Array || array instanceof Uint8ClampedArray) return (v) => v / 255;
  if (array instanceof Uint16Array) return (v) => v / 65535;
  if (array instanceof Uint32Array) return (v) => v / 4294967295;
  if (array instanceof Int8Array) return (v) => Math.max(v / 127, -1);
  if (array instanceof Int16Array) return (v) => Math.max(v / 32767, -1);
  if (array instanceof Int32Array) return (v) => Math.max(v / 2147483647, -1);
  return null;
}

/** An attribute's values as floats, itemSize per item (its own array when that is one already). */
function readFloats(attr, what, raw = false) {
  const { itemSize, count } = attr;
  if (!attr.isInterleavedBufferAttribute && !attr.isFloat16BufferAttribute && attr.array instanceof Float32Array &&
      attr.array.length === count * itemSize) {
    return attr.array;
  }
  const out = new Float32Array(count * itemSize);
  if (attr.isFloat16BufferAttribute) {
    const get = ['getX', 'getY', 'getZ', 'getW'];
    if (itemSize > 4) throw new Error(`subdivideGeometry: ${what}: a half-float attribute with itemSize ${itemSize} is not supported`);
    for (let i = 0; i < count; i++) for (let k = 0; k < itemSize; k++) out[i * itemSize + k] = attr[get[k]](i);
    return out;
  }
  let src, stride, offset;
  if (attr.isInterleavedBufferAttribute) {
    src = attr.data.array;
    stride = attr.data.stride;
    offset = attr.offset;
  } else {
    src = attr.array;
    stride = itemSize;
    offset = 0;
  }
  const scale = attr.normalized && !raw ? denormalizer(src) : null;
  for (let i = 0; i < count; i++) {
    for (let k = 0; k < itemSize; k++) {
      const v = src[i * stride + offset + k];
      out[i * itemSize + k] = scale ? scale(v) : v;
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Welding

function hash3(x, y, z) {
  let h = Math.imul(x, 0x9e3779b1) ^ Math.imul(y, 0x85ebca77) ^ Math.imul(z, 0xc2b2ae3d);
  h ^= h >>> 15;
  h = Math.imul(h, 0x2c1b3c6d);
  h ^= h >>> 12;
  return h >>> 0;
}

function tableSize(n) {
  let size = 16;
  while (size < 2 * n) size *= 2;
  return size;
}

/**
 * weldOf[v]: the welded vertex of every input vertex the triangles use, numbered in order of
 * first use; weldedPositions: the position of each (its first input vertex's, never averaged).
 */
function weldVertices(P, n, corner, weld) {
  const bits = new Uint32Array(P.buffer, P.byteOffset, 3 * n);
  const key = (i) => (bits[i] === 0x80000000 ? 0 : bits[i]); // -0 and +0 are one position
  const size = tableSize(n);
  const mask = size - 1;
  const table = new Int32Array(size).fill(-1);
  const rep = new Int32Array(n);
  for (let v = 0; v < n; v++) {
    const x = key(3 * v), y = key(3 * v + 1), z = key(3 * v + 2);
    let slot = hash3(x, y, z) & mask;
    for (;;) {
      const u = table[slot];
      if (u < 0) {
        table[slot] = v;
        rep[v] = v;
        break;
      }
      if (key(3 * u) === x && key(3 * u + 1) === y && key(3 * u + 2) === z) {
        rep[v] = u;
        break;
      }
      slot = (slot + 1) & mask;
    }
  }
  if (weld > 0) weldByDistance(P, n, rep, weld);
  const weldOf = new Int32Array(n).fill(-1);
  const idOfRep = new Int32Array(n).fill(-1);
  let numWelded = 0;
  const order = [];
  for (let c = 0; c < corner.length; c++) {
    const v = corner[c];
    if (weldOf[v] >= 0) continue;
    const r = rep[v];
    if (idOfRep[r] < 0) {
      idOfRep[r] = numWelded++;
      order.push(r);
    }
    weldOf[v] = idOfRep[r];
  }
  const weldedPositions = new Float32Array(3 * numWelded);
  for (let w = 0; w < numWelded; w++) {
    const r = order[w];
    weldedPositions[3 * w] = P[3 * r];
    weldedPositions[3 * w + 1] = P[3 * r + 1];
    weldedPositions[3 * w + 2] = P[3 * r + 2];
  }
  return { weldOf, numWelded, weldedPositions };
}

/**
 * Merges distinct positions closer than `weld`: in input order, each one joins the nearest
 * earlier cluster centre within `weld` (a spatial hash grid of cell size `weld`), or starts a
 * cluster of its own at its position.
 */
function weldByDistance(P, n, rep, weld) {
  const size = tableSize(n);
  const mask = size - 1;
  const cellKey = new Float64Array(3 * n);
  const head = new Int32Array(size).fill(-1); // slot -> first centre in that cell
  const slotCell = new Int32Array(size).fill(-1); // slot -> a centre of that cell (its key)
  const nextInCell = new Int32Array(n).fill(-1);
  const weld2 = weld * weld;
  const slotOf = (cx, cy, cz, insert) => {
    let slot = hash3(cx | 0, cy | 0, cz | 0) & mask;
    for (;;) {
      const u = slotCell[slot];
      if (u < 0) {
        if (!insert) return -1;
        return slot;
      }
      if (cellKey[3 * u] === cx && cellKey[3 * u + 1] === cy && cellKey[3 * u + 2] === cz) return slot;
      slot = (slot + 1) & mask;
    }
  };
  for (let v = 0; v < n; v++) {
    if (rep[v] !== v) continue; // a bit-identical copy: follows its representative
    const x = P[3 * v], y = P[3 * v + 1], z = P[3 * v + 2];
    const cx = Math.floor(x / weld), cy = Math.floor(y / weld), cz = Math.floor(z / weld);
    let best = -1, bestD = Infinity;
    for (let dx = -1; dx <= 1; dx++) for (let dy = -1; dy <= 1; dy++) for (let dz = -1; dz <= 1; dz++) {
      const slot = slotOf(cx + dx, cy + dy, cz + dz, false);
      if (slot < 0) continue;
      for (let u = head[slot]; u >= 0; u = nextInCell[u]) {
        const d = (P[3 * u] - x) ** 2 + (P[3 * u + 1] - y) ** 2 + (P[3 * u + 2] - z) ** 2;
        if (d <= weld2 && d < bestD) {
          best = u;
          bestD = d;
        }
      }
    }
    if (best >= 0) {
      rep[v] = best;
    } else {
      cellKey[3 * v] = cx;
      cellKey[3 * v + 1] = cy;
      cellKey[3 * v + 2] = cz;
      const slot = slotOf(cx, cy, cz, true);
      if (slotCell[slot] < 0) slotCell[slot] = v;
      nextInCell[v] = head[slot];
      head[slot] = v;
    }
  }
  for (let v = 0; v < n; v++) rep[v] = rep[rep[v]];
}

/** The input vertices of each welded vertex (those the kept triangles use), grouped: CSR. */
function weldedCopies(triV, weldOf, numWelded, numInput) {
  const seen = new Uint8Array(numInput);
  const start = new Uint32Array(numWelded + 1);
  for (let k = 0; k < triV.length; k++) {
    const v = triV[k];
    if (!seen[v]) {
      seen[v] = 1;
      start[weldOf[v] + 1]++;
    }
  }
  for (let w = 0; w < numWelded; w++) start[w + 1] += start[w];
  const list = new Uint32Array(start[numWelded]);
  const cursor = start.slice(0, numWelded);
  for (let v = 0; v < numInput; v++) if (seen[v]) list[cursor[weldOf[v]]++] = v;
  return { start, list, numWelded };
}

/**
 * A channel of per-input-vertex values: vertex-varying when all copies of every welded vertex
 * agree (bit for bit), face-varying otherwise, with fv[v] the first copy of v's welded vertex
 * holding the same value (so equal values never make a seam).
 */
function classify(values, itemSize, copies, info, alwaysFaceVarying = false) {
  const bits = new Uint32Array(values.buffer, values.byteOffset, values.length);
  const { start, list, numWelded } = copies;
  let fv = null;
  const same = (u, v) => {
    for (let k = 0; k < itemSize; k++) if (bits[u * itemSize + k] !== bits[v * itemSize + k]) return false;
    return true;
  };
  if (alwaysFaceVarying) fv = new Int32Array(values.length / itemSize).fill(-1);
  for (let w = 0; w < numWelded && !fv; w++) {
    const first = list[start[w]];
    for (let i = start[w] + 1; i < start[w + 1]; i++) {
      if (!same(first, list[i])) {
        fv = new Int32Array(values.length / itemSize).fill(-1);
        break;
      }
    }
    if (fv) break;
  }
  if (fv) {
    for (let w = 0; w < numWelded; w++) {
      for (let i = start[w]; i < start[w + 1]; i++) {
        const v = list[i];
        fv[v] = v;
        for (let j = start[w]; j < i; j++) {
          const u = list[j];
          if (fv[u] === u && same(u, v)) {
            fv[v] = u;
            break;
          }
        }
      }
    }
  }
  return { ...info, values, itemSize, fv };
}

function cornerClasses(fvarChannels, copies, numInput) {
  const cls = new Int32Array(numInput);
  for (let v = 0; v < numInput; v++) cls[v] = v;
  if (!fvarChannels.length) return null;
  const { start, list, numWelded } = copies;
  for (let w = 0; w < numWelded; w++) {
    for (let i = start[w]; i < start[w + 1]; i++) {
      const v = list[i];
      for (let j = start[w]; j < i; j++) {
        const u = list[j];
        if (cls[u] === u && fvarChannels.every((ch) => ch.fv[u] === ch.fv[v])) {
          cls[v] = u;
          break;
        }
      }
    }
  }
  return cls;
}

/** Per welded vertex, the values of its first copy. */
function gatherWelded(values, itemSize, copies) {
  const { start, list, numWelded } = copies;
  const out = new Float32Array(numWelded * itemSize);
  for (let w = 0; w < numWelded; w++) {
    if (start[w] === start[w + 1]) continue; // only in triangles dropped as degenerate: unused
    const v = list[start[w]];
    for (let k = 0; k < itemSize; k++) out[w * itemSize + k] = values[v * itemSize + k];
  }
  return out;
}

/** A face-varying channel's value at each vertex (the last corner's where they differ). */
function perVertex(channel, indices, count) {
  const size = channel.itemSize;
  const out = new Float32Array(count * size);
  for (let k = 0; k < indices.length; k++) {
    const v = indices[k], i = channel.indices[k];
    for (let j = 0; j < size; j++) out[v * size + j] = channel.array[i * size + j];
  }
  return out;
}

function gatherRows(values, itemSize, origins, count) {
  if (!origins) return values;
  const out = new Float32Array(count * itemSize);
  for (let d = 0; d < count; d++) {
    const o = origins[d];
    for (let k = 0; k < itemSize; k++) out[d * itemSize + k] = values[o * itemSize + k];
  }
  return out;
}

function gatherTyped(values, itemSize, origins, count, ArrayType) {
  const out = new ArrayType(count * itemSize);
  for (let d = 0; d < count; d++) {
    const o = origins ? origins[d] : d;
    for (let k = 0; k < itemSize; k++) out[d * itemSize + k] = values[o * itemSize + k];
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Skinning

/**
 * skinIndex / skinWeight as dense weight channels over the bones used (each welded vertex takes
 * its first copy's influences), chunks of up to 16 bones per channel.
 */
function readSkin(geometry, numInput, copies) {
  const skinIndex = geometry.getAttribute('skinIndex');
  const skinWeight = geometry.getAttribute('skinWeight');
  if (!skinIndex && !skinWeight) return null;
  if (!skinIndex || !skinWeight) {
    throw new Error(`subdivideGeometry: the geometry has '${skinIndex ? 'skinIndex' : 'skinWeight'}' without ` +
      `'${skinIndex ? 'skinWeight' : 'skinIndex'}'; skinning needs both`);
  }
  checkCount(skinIndex, numInput, "attribute 'skinIndex'");
  checkCount(skinWeight, numInput, "attribute 'skinWeight'");
  if (skinIndex.itemSize !== skinWeight.itemSize) {
    throw new Error(`subdivideGeometry: skinIndex has itemSize ${skinIndex.itemSize} but skinWeight ${skinWeight.itemSize}`);
  }
  const m = skinIndex.itemSize;
  const I = readFloats(skinIndex, 'skinIndex', true);
  const W = readFloats(skinWeight, 'skinWeight');
  const { start, list, numWelded } = copies;
  const slotOf = new Map();
  const bones = [];
  for (let w = 0; w < numWelded; w++) {
    if (start[w] === start[w + 1]) continue;
    const v = list[start[w]];
    for (let k = 0; k < m; k++) {
      if (W[v * m + k] > 0 && !slotOf.has(I[v * m + k])) {
        slotOf.set(I[v * m + k], bones.length);
        bones.push(I[v * m + k]);
      }
    }
  }
  const B = Math.max(1, bones.length);
  const chunks = [];
  for (let first = 0; first < B; first += 16) {
    const itemSize = Math.min(16, B - first);
    chunks.push({ array: new Float32Array(numWelded * itemSize), itemSize });
  }
  for (let w = 0; w < numWelded; w++) {
    if (start[w] === start[w + 1]) continue;
    const v = list[start[w]];
    for (let k = 0; k < m; k++) {
      const weight = W[v * m + k];
      if (!(weight > 0)) continue;
      const slot = slotOf.get(I[v * m + k]);
      const chunk = chunks[slot >> 4];
      chunk.array[w * chunk.itemSize + (slot & 15)] += weight;
    }
  }
  const maxBone = bones.reduce((a, b) => Math.max(a, b), 0);
  const IndexArray = maxBone < 65536 ? Uint16Array : Uint32Array;
  return { bones, chunks, IndexArray };
}

/**
 * Per refined vertex: the four largest weights (ties: the lower bone index), renormalised to sum
 * to 1; weights <= 0 are left out (index 0, weight 0).
 */
function topFourWeights(skin, arrays, count) {
  const indices = new Uint32Array(4 * count);
  const weights = new Float32Array(4 * count);
  const { bones, chunks } = skin;
  const topW = [0, 0, 0, 0], topB = [0, 0, 0, 0];
  for (let v = 0; v < count; v++) {
    topW.fill(0);
    topB.fill(0);
    for (let c = 0; c < chunks.length; c++) {
      const size = chunks[c].itemSize, a = arrays[c];
      for (let k = 0; k < size; k++) {
        const w = a[v * size + k];
        if (!(w > 0)) continue;
        const bone = bones[16 * c + k];
        // Larger weights first; equal ones by bone index, so ties are cut the same way always.
        const before = (j) => w > topW[j] || (w === topW[j] && bone < topB[j]);
        if (!(topW[3] === 0 || before(3))) continue;
        let j = 3;
        while (j > 0 && (topW[j - 1] === 0 || before(j - 1))) {
          topW[j] = topW[j - 1];
          topB[j] = topB[j - 1];
          j--;
        }
        topW[j] = w;
        topB[j] = bone;
      }
    }
    const sum = topW[0] + topW[1] + topW[2] + topW[3];
    for (let j = 0; j < 4; j++) {
      indices[4 * v + j] = topB[j];
      weights[4 * v + j] = sum > 0 ? topW[j] / sum : 0;
    }
  }
  return { indices, weights };
}

// ---------------------------------------------------------------------------------------------
// Edges, creases and quads

const next3 = (h) => (h % 3 === 2 ? h - 2 : h + 1);

/**
 * The edges of the kept triangles: for edge e, its vertices a < b, how many half-edges use it,
 * and the first two (h = 3 * triangle + corner, from corner to the next).
 */
function buildEdges(triW) {
  const H = triW.length;
  const size = tableSize(H);
  const mask = size - 1;
  const table = new Int32Array(size).fill(-1);
  const a = new Uint32Array(H), b = new Uint32Array(H);
  const uses = new Uint32Array(H), h0 = new Int32Array(H).fill(-1), h1 = new Int32Array(H).fill(-1);
  const edgeOf = new Uint32Array(H);
  let count = 0;
  const slotFor = (x, y) => {
    let slot = hash3(x, y, 0x51ed27) & mask;
    for (;;) {
      const e = table[slot];
      if (e < 0 || (a[e] === x && b[e] === y)) return slot;
      slot = (slot + 1) & mask;
    }
  };
  for (let h = 0; h < H; h++) {
    const u = triW[h], v = triW[next3(h)];
    const x = Math.min(u, v), y = Math.max(u, v);
    const slot = slotFor(x, y);
    let e = table[slot];
    if (e < 0) {
      e = table[slot] = count++;
      a[e] = x;
      b[e] = y;
    }
    if (uses[e] === 0) h0[e] = h;
    else if (uses[e] === 1) h1[e] = h;
    uses[e]++;
    edgeOf[h] = e;
  }
  return {
    count, a, b, uses, h0, h1, edgeOf,
    /** Whether an edge's two half-edges run opposite ways (a consistently wound manifold edge). */
    opposite(e) {
      return uses[e] === 2 && triW[h0[e]] === triW[next3(h1[e])];
    },
    find(x, y) {
      const e = table[slotFor(Math.min(x, y), Math.max(x, y))];
      return e;
    },
  };
}

function triangleNormals(triW, P) {
  const T = triW.length / 3;
  const n = new Float64Array(3 * T);
  for (let t = 0; t < T; t++) {
    const [x, y, z] = cross3(P, triW[3 * t], triW[3 * t + 1], triW[3 * t + 2]);
    const l = Math.hypot(x, y, z);
    if (l > 0) {
      n[3 * t] = x / l;
      n[3 * t + 1] = y / l;
      n[3 * t + 2] = z / l;
    }
  }
  return n;
}

const isUnit = (n, t) => n[3 * t] !== 0 || n[3 * t + 1] !== 0 || n[3 * t + 2] !== 0;

function cross3(P, i, j, k) {
  const ax = P[3 * j] - P[3 * i], ay = P[3 * j + 1] - P[3 * i + 1], az = P[3 * j + 2] - P[3 * i + 2];
  const bx = P[3 * k] - P[3 * i], by = P[3 * k + 1] - P[3 * i + 1], bz = P[3 * k + 2] - P[3 * i + 2];
  return [ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx];
}

function unitNormal(P, i, j, k) {
  const [x, y, z] = cross3(P, i, j, k);
  const l = Math.hypot(x, y, z);
  return l > 0 ? [x / l, y / l, z / l] : null;
}

function angleBetween(n, m) {
  if (!n || !m) return Math.PI;
  return Math.acos(Math.max(-1, Math.min(1, n[0] * m[0] + n[1] * m[1] + n[2] * m[2])));
}

function triangleArea(P, i, j, k) {
  const [x, y, z] = cross3(P, i, j, k);
  return 0.5 * Math.hypot(x, y, z);
}

/**
 * Blender's join error for the quad (v1, v2, v3, v4) (bmo_join_triangles.c): how far the two
 * triangulations are from flat, how far the corners are from right angles, and how unequal the
 * two triangulations' areas are (concavity); each term 0 for a flat rectangle.
 */
function quadError(P, v1, v2, v3, v4) {
  const flat = (angleBetween(unitNormal(P, v1, v2, v3), unitNormal(P, v1, v3, v4)) +
    angleBetween(unitNormal(P, v2, v3, v4), unitNormal(P, v4, v1, v2))) / (2 * Math.PI);
  const vs = [v1, v2, v3, v4];
  const edge = vs.map((v, i) => {
    const w = vs[(i + 1) % 4];
    const d = [P[3 * v] - P[3 * w], P[3 * v + 1] - P[3 * w + 1], P[3 * v + 2] - P[3 * w + 2]];
    const l = Math.hypot(d[0], d[1], d[2]) || 1;
    return [d[0] / l, d[1] / l, d[2] / l];
  });
  let square = 0;
  for (let i = 0; i < 4; i++) square += Math.abs(angleBetween(edge[i], edge[(i + 1) % 4]) - Math.PI / 2);
  square /= 2 * Math.PI;
  const areaA = triangleArea(P, v1, v2, v3) + triangleArea(P, v1, v3, v4);
  const areaB = triangleArea(P, v2, v3, v4) + triangleArea(P, v4, v1, v2);
  const max = Math.max(areaA, areaB);
  const concave = max > 0 ? 1 - Math.min(areaA, areaB) / max : 1;
  return flat + square + concave;
}

function trianglePolygons(triV, triW, numKept, triGroup) {
  const sizes = new Uint32Array(numKept).fill(3);
  const starts = new Uint32Array(numKept);
  const firstTri = new Uint32Array(numKept);
  const triCorner = new Uint32Array(3 * numKept);
  for (let k = 0; k < numKept; k++) {
    starts[k] = 3 * k;
    firstTri[k] = k;
  }
  for (let c = 0; c < triCorner.length; c++) triCorner[c] = c;
  return { sizes, starts, V: triV, W: triW, firstTri, triCorner, group: triGroup };
}

/**
 * Blender's "Tris to Quads": every interior edge between two triangles that could form a quad
 * (consistently wound, same group, not a crease, not a face-varying seam at either end, not a
 * hole, a convex quad whose two triangles' normals differ by at most `faceAngle` and whose other
 * diagonal's triangles' by at most `shapeAngle`) is a candidate; candidates are taken greedily
 * in order of quadError (smallest first, ties in edge order) while both triangles are free.
 */
function joinQuads(triV, triW, numKept, edges, sharp, triGroup, cornerClass, holeTris, P, limits) {
  const candidates = [];
  const errors = [];
  for (let e = 0; e < edges.count; e++) {
    if (sharp[e] || !edges.opposite(e)) continue;
    const h = edges.h0[e], g = edges.h1[e];
    const t1 = (h / 3) | 0, t2 = (g / 3) | 0;
    if (t1 === t2) continue;
    if (triGroup && triGroup[t1] !== triGroup[t2]) continue;
    if (holeTris && (holeTris[t1] || holeTris[t2])) continue;
    // t1 = (u, v, p) with h: u -> v; t2 = (v, u, q) with g: v -> u; the quad is (u, q, v, p).
    const u = triW[h], v = triW[next3(h)], p = triW[next3(next3(h))], q = triW[next3(next3(g))];
    if (p === q) continue;
    if (cornerClass) {
      if (cornerClass[triV[h]] !== cornerClass[triV[next3(g)]]) continue;
      if (cornerClass[triV[next3(h)]] !== cornerClass[triV[g]]) continue;
    }
    const n1 = unitNormal(P, u, v, p), n2 = unitNormal(P, v, u, q);
    if (!n1 || !n2 || angleBetween(n1, n2) > limits.faceAngle) continue;
    const n3 = unitNormal(P, q, v, p), n4 = unitNormal(P, p, u, q);
    if (!n3 || !n4 || angleBetween(n3, n4) > limits.shapeAngle) continue;
    // Convex: the other diagonal's triangles face the same way as the quad.
    const nx = n1[0] + n2[0], ny = n1[1] + n2[1], nz = n1[2] + n2[2];
    if (n3[0] * nx + n3[1] * ny + n3[2] * nz <= 0 || n4[0] * nx + n4[1] * ny + n4[2] * nz <= 0) continue;
    candidates.push(e);
    errors.push(quadError(P, u, q, v, p));
  }
  const order = Uint32Array.from(candidates.keys()).sort((i, j) => errors[i] - errors[j] || i - j);
  const partner = new Int32Array(numKept).fill(-1);
  const joinEdge = new Int32Array(numKept).fill(-1);
  let joined = 0;
  for (const i of order) {
    const e = candidates[i];
    const t1 = (edges.h0[e] / 3) | 0, t2 = (edges.h1[e] / 3) | 0;
    if (partner[t1] >= 0 || partner[t2] >= 0) continue;
    partner[t1] = t2;
    partner[t2] = t1;
    joinEdge[t1] = edges.h0[e];
    joinEdge[t2] = edges.h1[e];
    joined++;
  }
  const count = numKept - joined;
  const sizes = new Uint32Array(count), starts = new Uint32Array(count), firstTri = new Uint32Array(count);
  const group = triGroup ? new Int32Array(count) : null;
  const V = new Uint32Array(3 * numKept - 2 * joined);
  const W = new Uint32Array(V.length);
  const triCorner = new Uint32Array(V.length);
  let f = 0, k = 0;
  const put = (h) => {
    V[k] = triV[h];
    W[k] = triW[h];
    triCorner[k++] = h;
  };
  for (let t = 0; t < numKept; t++) {
    const o = partner[t];
    if (o >= 0 && o < t) continue;
    starts[f] = k;
    firstTri[f] = t;
    if (group) group[f] = triGroup[t];
    if (o < 0) {
      sizes[f] = 3;
      put(3 * t);
      put(3 * t + 1);
      put(3 * t + 2);
    } else {
      sizes[f] = 4;
      const h = joinEdge[t], g = joinEdge[o];
      put(h); // u
      put(next3(next3(g))); // q
      put(next3(h)); // v (t's corner)
      put(next3(next3(h))); // p
    }
    f++;
  }
  return { sizes, starts, V, W, firstTri, triCorner, group };
}

/** Crease and corner options name input vertices; they are mapped to welded ones. */
function mapPairs(creases, weldOf, numInput, what) {
  if (creases === undefined) return null;
  if (!creases || !(creases.edges instanceof Uint32Array)) {
    throw new Error(`subdivideGeometry: ${what} must be { edges: Uint32Array (vertex pairs), sharpness: Float32Array }`);
  }
  const { edges, sharpness } = creases;
  if (!(sharpness instanceof Float32Array)) throw new Error(`subdivideGeometry: ${what}.sharpness must be a Float32Array`);
  if (edges.length % 2) throw new Error(`subdivideGeometry: ${what}.edges has ${edges.length} entries; give vertex pairs`);
  const n = edges.length / 2;
  if (sharpness.length !== 1 && sharpness.length !== n) {
    throw new Error(`subdivideGeometry: ${what}.sharpness has ${sharpness.length} entries; give one per edge (${n}) or one for all`);
  }
  const pairs = [];
  const kept = [];
  for (let i = 0; i < n; i++) {
    const a = edges[2 * i], b = edges[2 * i + 1];
    if (a >= numInput || b >= numInput) {
      throw new Error(`subdivideGeometry: ${what} ${i} names vertex ${Math.max(a, b)}, but the geometry has ${numInput}`);
    }
    const wa = weldOf[a], wb = weldOf[b];
    if (wa < 0 || wb < 0 || wa === wb) continue; // unused by any triangle, or welded into one
    pairs.push(wa, wb);
    kept.push(sharpness.length === 1 ? sharpness[0] : sharpness[i]);
  }
  return { pairs: Uint32Array.from(pairs), sharpness: (i) => kept[i] };
}

function mapCorners(corners, weldOf, numInput) {
  if (!corners || !(corners.vertices instanceof Uint32Array) || !(corners.sharpness instanceof Float32Array)) {
    throw new Error('subdivideGeometry: corners must be { vertices: Uint32Array, sharpness: Float32Array }');
  }
  const { vertices, sharpness } = corners;
  const v = [], s = [];
  for (let i = 0; i < vertices.length; i++) {
    if (vertices[i] >= numInput) throw new Error(`subdivideGeometry: corners ${i} names vertex ${vertices[i]}, but the geometry has ${numInput}`);
    const w = weldOf[vertices[i]];
    if (w < 0) continue;
    v.push(w);
    s.push(sharpness.length === 1 ? sharpness[0] : sharpness[i]);
  }
  return { vertices: Uint32Array.from(v), sharpness: Float32Array.from(s) };
}

/** `holes` names input triangles (index / 3); per kept triangle, whether it is one. */
function mapHoles(holes, keep, numKept, numTris) {
  if (holes === undefined) return null;
  if (!(holes instanceof Uint32Array)) throw new Error('subdivideGeometry: holes must be a Uint32Array of triangles (index / 3)');
  const isHole = new Uint8Array(numTris);
  for (const t of holes) {
    if (t >= numTris) throw new Error(`subdivideGeometry: holes names triangle ${t}, but the geometry has ${numTris}`);
    isHole[t] = 1;
  }
  const out = new Uint8Array(numKept);
  for (let k = 0; k < numKept; k++) out[k] = isHole[keep[k]];
  return out;
}

// ---------------------------------------------------------------------------------------------
// Sides of sharp edges and their normals

/**
 * Per kept-triangle corner, a representative corner of its smoothing fan: the corners around a
 * vertex joined across every consistently wound manifold edge that is not infinitely sharp.
 */
function smoothingFans(triW, numKept, edges, sharp) {
  const parent = new Uint32Array(3 * numKept);
  for (let c = 0; c < parent.length; c++) parent[c] = c;
  const find = (c) => {
    while (parent[c] !== c) {
      parent[c] = parent[parent[c]];
      c = parent[c];
    }
    return c;
  };
  const union = (x, y) => {
    x = find(x);
    y = find(y);
    if (x !== y) parent[Math.max(x, y)] = Math.min(x, y);
  };
  for (let e = 0; e < edges.count; e++) {
    if (sharp[e] === 1 || sharp[e] === 3 || !edges.opposite(e)) continue;
    const h = edges.h0[e], g = edges.h1[e]; // h: a -> b (corner h is a), g: b -> a (corner g is b)
    union(h, next3(g)); // the corners at a
    union(next3(h), g); // the corners at b
  }
  const root = new Uint32Array(parent.length);
  for (let c = 0; c < root.length; c++) root[c] = find(c);
  return root;
}

/** Which refined vertices lie on a sharp edge (more than one side), and each drawn vertex's side. */
function sideTopology(out, draw, sidesChannel, outVertices) {
  const sideIdx = sidesChannel.indices;
  const firstSide = new Int32Array(outVertices).fill(-1);
  const multi = new Uint8Array(outVertices);
  for (let k = 0; k < sideIdx.length; k++) {
    const v = out.indices[k];
    if (firstSide[v] < 0) firstSide[v] = sideIdx[k];
    else if (firstSide[v] !== sideIdx[k]) multi[v] = 1;
  }
  const drawSide = new Uint32Array(draw.positions.length / 3);
  for (let k = 0; k < sideIdx.length; k++) drawSide[draw.indices[k]] = sideIdx[k];
  return { sideIdx, multi, drawSide, numSides: sidesChannel.array.length };
}

/** Vertices on sharp edges: per side, the normalised sum of that side's face area vectors. */
function applySideNormals(normals, sides, positions, out) {
  const acc = new Float64Array(3 * sides.numSides);
  let k = 0;
  for (let f = 0; f < out.faceSizes.length; f++) {
    const n = out.faceSizes[f];
    let x = 0, y = 0, z = 0;
    for (let i = 0; i < n; i++) {
      const a = out.indices[k + i], b = out.indices[k + ((i + 1) % n)];
      const ax = positions[3 * a], ay = positions[3 * a + 1], az = positions[3 * a + 2];
      const bx = positions[3 * b], by = positions[3 * b + 1], bz = positions[3 * b + 2];
      x += (ay - by) * (az + bz);
      y += (az - bz) * (ax + bx);
      z += (ax - bx) * (ay + by);
    }
    for (let i = 0; i < n; i++) {
      if (!sides.multi[out.indices[k + i]]) continue;
      const s = sides.sideIdx[k + i];
      acc[3 * s] += x;
      acc[3 * s + 1] += y;
      acc[3 * s + 2] += z;
    }
    k += n;
  }
  for (let d = 0; d < sides.drawSide.length; d++) {
    const s = sides.drawSide[d];
    const x = acc[3 * s], y = acc[3 * s + 1], z = acc[3 * s + 2];
    const l = Math.hypot(x, y, z);
    if (l > 0) {
      normals[3 * d] = x / l;
      normals[3 * d + 1] = y / l;
      normals[3 * d + 2] = z / l;
    }
  }
}
