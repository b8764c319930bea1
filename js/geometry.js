// subsurf/three's array-level core: a triangle list as plain typed arrays in, the subdivided,
// drawable mesh as plain typed arrays out. No three.js objects, so it can run in a Web Worker
// (every input and output array can be posted, and transferred). js/three.js converts a
// BufferGeometry to this input and the output back to a BufferGeometry.
//
// The geometry runs in Rust behind the wasm bindings (src/triangles/): welding (weldTriangles),
// edges, sharp edges, quads and smoothing fans (triangleFaces), and the normals of the sides of
// sharp edges (sideNormals). What is left here is data bookkeeping: options, gathering
// attribute rows by index, classifying attributes as vertex- or face-varying, group and skin
// bookkeeping. Rules and options: README.md, "three.js"; steps: DEVELOPERS.md, "subsurf/three".
//
// This file imports subsurf's plain glue ('./subsurf.js'), which must have been initialised
// before the first call (see three.js).
import {
  schemeNames, sideNormals, subdivide, toDrawable, triangleFaces, vertexNormals, weldTriangles,
} from './subsurf.js';

/** Options of subdivideTriangles that `subdivide` does not take. */
const OWN_OPTIONS = ['weld', 'quads', 'creaseAngle', 'sharpNormalSplits', 'normals'];
/** Schemes whose first level takes quads (the others take triangles only). */
const QUAD_SCHEMES = ['catmull-clark', 'quad-triangle', 'bilinear', 'doo-sabin'];
const INTERNAL = '__subsurf_';
/**
 * three's texture coordinates: always face-varying (as OpenSubdiv and glTF treat UVs), so that
 * `fvarLinear` applies to them with or without seams.
 */
const UV_NAMES = new Set(['uv', 'uv1', 'uv2', 'uv3']);
const PREFIX = 'subdivideGeometry:';

let initialised = false;

/**
 * Subdivides a triangle list given as typed arrays.
 *
 * `input`: `positions` (Float32Array, x, y, z per vertex); `index` (Uint32Array, three vertices
 * per triangle; omitted: every three vertices are a triangle); `attributes` (by name,
 * `{ array: Float32Array, itemSize }` per vertex, besides position, normal, tangent and skin);
 * `normals` (Float32Array, the input's normals, read with `sharpNormalSplits` only); `skin`
 * (`{ indices: Float32Array, weights: Float32Array, itemSize }`); `morphAttributes` (by name, a list
 * of `{ array, itemSize }` targets; normal targets are recomputed, so give their count as
 * `morphNormals`); `morphTargetsRelative`; `groups` (`[{ start, count, materialIndex }]`, in
 * index entries). Inputs are never written.
 *
 * Returns `{ positions, normals?, index, attributes, skin?, morphAttributes, groups }`: the
 * drawable mesh (one vertex per distinct combination of a refined vertex and its face-varying
 * values), `index` a Uint16Array or Uint32Array triangle list in group order, `attributes` by
 * name `{ array, itemSize }`, `skin` `{ indices, weights }` (4 per vertex), `morphAttributes` by
 * name lists of Float32Arrays, `groups` as given with `start` and `count` in the new index.
 * `options`: subdivideGeometry's (three.d.ts).
 */
export function subdivideTriangles(input, options = {}) {
  const own = checkOptions(options);
  const passed = {};
  for (const key of Object.keys(options)) {
    if (!OWN_OPTIONS.includes(key) && options[key] !== undefined) passed[key] = options[key];
  }

  // ---- input arrays
  const P = input.positions;
  if (!(P instanceof Float32Array) || P.length % 3 !== 0) {
    throw new Error(`${PREFIX} positions must be a Float32Array of x, y, z per vertex`);
  }
  const numInput = P.length / 3;
  for (let i = 0; i < P.length; i++) {
    if (!Number.isFinite(P[i])) {
      throw new Error(`${PREFIX} position of vertex ${Math.floor(i / 3)} is not finite (${P[i]})`);
    }
  }
  const index = input.index;
  const cornerCount = index ? index.length : numInput;
  if (cornerCount % 3 !== 0) {
    throw new Error(`${PREFIX} the geometry must be a triangle list; its ${index ? 'index' : 'position'} count ` +
      `${cornerCount} is not a multiple of 3`);
  }
  if (cornerCount === 0) throw new Error(`${PREFIX} the geometry has no triangles`);
  let corner; // original vertex of every triangle corner
  if (index) {
    corner = index instanceof Uint32Array ? index : Uint32Array.from(index);
    for (let c = 0; c < cornerCount; c++) {
      if (corner[c] >= numInput) {
        throw new Error(`${PREFIX} index[${c}] is ${corner[c]}, but the geometry has only ${numInput} vertices`);
      }
    }
  } else {
    corner = new Uint32Array(cornerCount);
    for (let c = 0; c < cornerCount; c++) corner[c] = c;
  }
  const numTris = cornerCount / 3;

  // ---- weld (Rust): bit-identical positions, then (weld > 0) nearer ones; degenerate
  // triangles dropped
  const welded = weldTriangles(P, corner, own.weld);
  const { weldOf, kept } = welded;
  const weldedPositions = welded.positions;
  const numWelded = weldedPositions.length / 3;
  const numKept = kept.length;
  if (numKept === 0) throw new Error(`${PREFIX} every triangle is degenerate (its corners weld together)`);
  const triW = welded.corners; // welded vertex per kept-triangle corner
  const triV = new Uint32Array(3 * numKept); // original vertex per kept-triangle corner
  for (let k = 0; k < numKept; k++) {
    const t = 3 * kept[k];
    triV[3 * k] = corner[t];
    triV[3 * k + 1] = corner[t + 1];
    triV[3 * k + 2] = corner[t + 2];
  }
  const copies = weldedCopies(triV, weldOf, numWelded, numInput);

  // ---- groups: each kept triangle in the first input group that covers it (G: none)
  const groups = input.groups || [];
  const G = groups.length;
  let triGroup = null;
  if (G > 0) {
    const ofTri = new Uint32Array(numTris).fill(G);
    for (let g = G - 1; g >= 0; g--) {
      const { start, count } = groups[g];
      const first = Math.max(0, Math.ceil(start / 3)), end = Math.min(numTris, Math.floor((start + count) / 3));
      for (let t = first; t < end; t++) ofTri[t] = g;
    }
    triGroup = new Uint32Array(numKept);
    for (let k = 0; k < numKept; k++) triGroup[k] = ofTri[kept[k]];
  }

  // ---- channels: each attribute vertex-varying, or face-varying where welded copies differ
  const channels = []; // { name, values, itemSize, fv: Int32Array | null, kind: 'attribute' | 'morph', target }
  const attributesIn = input.attributes || {};
  for (const name of Object.keys(attributesIn)) {
    const { array, itemSize } = attributesIn[name];
    checkChannel(array, itemSize, numInput, `attribute '${name}'`);
    channels.push(classify(array, itemSize, copies, { kind: 'attribute', name }, UV_NAMES.has(name)));
  }
  const morphs = input.morphAttributes || {};
  for (const name of Object.keys(morphs)) {
    if (name === 'normal') continue;
    morphs[name].forEach(({ array, itemSize }, i) => {
      checkChannel(array, itemSize, numInput, `morphAttributes.${name}[${i}]`);
      channels.push(classify(array, itemSize, copies, { kind: 'morph', name, target: i }));
    });
  }
  const fvarChannels = channels.filter((c) => c.fv);
  // Two copies of a welded vertex are one corner class when every face-varying channel agrees.
  const cornerClass = cornerClasses(fvarChannels, copies, numInput);

  // Skin: dense per-bone weight channels over the bones used (chunks of up to 16).
  const skin = input.skin ? readSkin(input.skin, copies) : null;

  // ---- faces (Rust): sharp edges, quads, smoothing fans
  const userCreases = mapPairs(passed.creases, weldOf, numInput, 'creases');
  const holeTris = mapHoles(passed.holes, kept, numTris);
  const splitNormals = own.sharpNormalSplits && input.normals ? input.normals : undefined;
  if (splitNormals) checkChannel(splitNormals, 3, numInput, "attribute 'normal'");
  const faceOptions = {
    creaseAngle: own.creaseAngle,
    splitNormals,
    creases: userCreases ? { edges: userCreases.pairs, sharpness: userCreases.sharpness } : undefined,
    quads: own.quads || undefined,
    groups: triGroup || undefined,
    cornerClasses: cornerClass || undefined,
    holes: holeTris || undefined,
    sides: own.normals !== false,
  };
  const needFaces = own.quads || own.creaseAngle !== undefined || splitNormals ||
    (userCreases && own.normals !== false);
  // Without them the faces are the kept triangles as they are.
  const faces = needFaces
    ? triangleFaces({ positions: weldedPositions, corners: triW, inputCorners: triV }, faceOptions)
    : { faceSizes: null, indices: triW, inputIndices: triV, firstTriangles: null, creases: new Uint32Array(0), holes: holeTris };
  const faceCount = faces.faceSizes ? faces.faceSizes.length : numKept;
  const sizeOf = faces.faceSizes ? (f) => faces.faceSizes[f] : () => 3;
  const triangleOf = faces.firstTriangles ? (f) => faces.firstTriangles[f] : (f) => f;

  // ---- the mesh and options for subdivide
  const attributes = {};
  const used = new Set([...Object.keys(attributesIn), 'position', 'normal', 'tangent', 'skinIndex', 'skinWeight']);
  const internal = (base) => {
    let name = INTERNAL + base;
    while (used.has(name)) name += '_';
    used.add(name);
    return name;
  };
  const V = faces.inputIndices;
  for (const ch of channels) {
    ch.key = ch.kind === 'attribute' ? ch.name : internal(`morph_${ch.name}_${ch.target}`);
    if (ch.fv) {
      const indices = new Uint32Array(V.length);
      for (let k = 0; k < indices.length; k++) indices[k] = ch.fv[V[k]];
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
    const indices = new Uint32Array(V.length);
    for (let f = 0, k = 0; f < faceCount; f++) {
      const g = triGroup[triangleOf(f)];
      for (let end = k + sizeOf(f); k < end; k++) indices[k] = g;
    }
    attributes[groupKey] = { array, itemSize: 1, indices };
  }
  let sidesKey = null;
  if (faces.sides) {
    // Face-varying "smoothing fans": the corners around a vertex, split at infinitely sharp
    // edges; the refined vertices on those edges get one normal per side.
    sidesKey = internal('sides');
    attributes[sidesKey] = { array: new Float32Array(3 * numKept), itemSize: 1, indices: faces.sides };
  }

  const mesh = { positions: weldedPositions, indices: faces.indices, attributes };
  if (faces.faceSizes && faces.faceSizes.some((s) => s !== 3)) mesh.faceSizes = faces.faceSizes;
  const subdivideOptions = { ...passed, normals: own.normals === true };
  delete subdivideOptions.creases;
  delete subdivideOptions.corners;
  delete subdivideOptions.holes;
  const ourCreases = faces.creases;
  if (ourCreases.length || userCreases) {
    // Ours first, the user's last: an edge named twice takes the last sharpness.
    const n = ourCreases.length / 2 + (userCreases ? userCreases.pairs.length / 2 : 0);
    const edgesArray = new Uint32Array(2 * n), sharpness = new Float32Array(n);
    edgesArray.set(ourCreases);
    sharpness.fill(10, 0, ourCreases.length / 2);
    if (userCreases) {
      edgesArray.set(userCreases.pairs, ourCreases.length);
      sharpness.set(userCreases.sharpness, ourCreases.length / 2);
    }
    subdivideOptions.creases = { edges: edgesArray, sharpness };
  }
  if (passed.corners !== undefined) subdivideOptions.corners = mapCorners(passed.corners, weldOf, numInput);
  if (holeTris) subdivideOptions.holes = faces.holes;

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

  // Normals: limit (subdivide's) or from the faces, one per side along sharp edges (Rust).
  const normalsFor = (positions, limitNormals) => {
    const refined = { positions, indices: out.indices, faceSizes: out.faceSizes };
    const base = own.normals === 'faces' ? vertexNormals(refined) : limitNormals;
    const normals = gather(base, 3);
    if (!sidesKey) return normals;
    const sides = out.attributes[sidesKey];
    return sideNormals(refined, sides.indices, sides.array.length, draw.indices, normals);
  };

  const result = { positions: draw.positions, attributes: {}, morphAttributes: {}, groups: [] };
  if (own.normals !== false) result.normals = normalsFor(out.positions, out.normals);
  for (const ch of channels) {
    const refined = out.attributes[ch.key];
    const array = ch.fv ? draw.attributes[ch.key].array : gather(refined.array, ch.itemSize);
    if (ch.kind === 'attribute') {
      result.attributes[ch.name] = { array, itemSize: ch.itemSize };
    } else {
      (result.morphAttributes[ch.name] ||= [])[ch.target] = array;
      ch.refined = refined.array;
    }
  }
  if (skin) {
    const { indices, weights } = topFourWeights(skin, skin.keys.map((k) => out.attributes[k].array), outVertices);
    result.skin = { indices: gatherTyped(indices, 4, origins, drawCount, skin.IndexArray), weights: gather(weights, 4) };
  }
  // Morph normals: the normals of the refined morphed surface (relative: minus the base ones).
  const relative = !!input.morphTargetsRelative;
  const morphNormalCount = input.morphNormals || 0;
  if (morphNormalCount > 0 && own.normals !== false) {
    const positionMorphs = channels.filter((c) => c.kind === 'morph' && c.name === 'position');
    result.morphAttributes.normal = Array.from({ length: morphNormalCount }, (_, i) => {
      const ch = positionMorphs.find((c) => c.target === i);
      if (!ch) return relative ? new Float32Array(3 * drawCount) : result.normals.slice();
      const moved = new Float32Array(out.positions.length);
      const refined = ch.fv ? perVertex(out.attributes[ch.key], out.indices, outVertices) : ch.refined;
      for (let k = 0; k < moved.length; k++) moved[k] = relative ? out.positions[k] + refined[k] : refined[k];
      let limitNormals = null;
      if (own.normals === true) {
        // Subdivide the morphed cage with the same options (positions only) for its normals.
        const cage = gatherWelded(ch.values, 3, copies);
        if (relative) for (let k = 0; k < cage.length; k++) cage[k] += weldedPositions[k];
        const cageMesh = { positions: cage, indices: mesh.indices };
        if (mesh.faceSizes) cageMesh.faceSizes = mesh.faceSizes;
        // onProgress reports the surface's levels once, in order; these passes are not counted.
        limitNormals = subdivide(cageMesh, { ...subdivideOptions, normals: true, onProgress: undefined }).normals;
      }
      const normals = normalsFor(moved, limitNormals);
      if (relative) for (let k = 0; k < normals.length; k++) normals[k] -= result.normals[k];
      return normals;
    });
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
    for (let g = 0; g < G; g++) {
      result.groups.push({ start: counts[g], count: counts[g + 1] - counts[g], materialIndex: groups[g].materialIndex });
    }
  }
  result.index = drawCount > 65536 ? triangles : Uint16Array.from(triangles);
  return result;
}

// ---------------------------------------------------------------------------------------------
// Options

/**
 * Checks that the wasm module is initialised and reads the options subdivideTriangles reads
 * itself (those `subdivide` does not take), throwing for a bad one: so that a caller converting
 * its input first reports option errors before input errors, as a direct call does.
 */
export function checkOptions(options) {
  checkInitialised();
  return readOwnOptions(options);
}

/**
 * checkOptions without the wasm check: for subdivideGeometryAsync, whose page may have no wasm
 * module of its own (the work runs in a worker's).
 */
export function readOwnOptions(options) {
  const own = { weld: 0, quads: false, creaseAngle: undefined, sharpNormalSplits: false, normals: true };
  if (options.weld !== undefined) {
    if (typeof options.weld !== 'number' || !(options.weld >= 0) || !Number.isFinite(options.weld)) {
      throw new Error(`${PREFIX} weld must be a distance >= 0 (0: only bit-identical positions), got ${describe(options.weld)}`);
    }
    own.weld = options.weld;
  }
  if (options.creaseAngle !== undefined) {
    const a = options.creaseAngle;
    if (typeof a !== 'number' || !(a >= 0)) {
      throw new Error(`${PREFIX} creaseAngle must be an angle in radians >= 0, got ${describe(a)}`);
    }
    if (a > Math.PI) {
      throw new Error(`${PREFIX} creaseAngle is in radians, from 0 to Math.PI; got ${a} ` +
        `(for ${a} degrees write ${a} * Math.PI / 180)`);
    }
    own.creaseAngle = a;
  }
  if (options.sharpNormalSplits !== undefined) {
    if (typeof options.sharpNormalSplits !== 'boolean') {
      throw new Error(`${PREFIX} sharpNormalSplits must be true or false, got ${describe(options.sharpNormalSplits)}`);
    }
    own.sharpNormalSplits = options.sharpNormalSplits;
  }
  if (options.normals !== undefined) {
    if (options.normals !== true && options.normals !== false && options.normals !== 'faces') {
      throw new Error(`${PREFIX} normals must be true (the limit surface's), 'faces' or false, got ${describe(options.normals)}`);
    }
    own.normals = options.normals;
  }
  const q = options.quads;
  if (q !== undefined && q !== false) {
    if (q !== true && (q === null || typeof q !== 'object')) {
      throw new Error(`${PREFIX} quads must be true, false or { faceAngle, shapeAngle } (radians), got ${describe(q)}`);
    }
    const limits = {};
    for (const key of ['faceAngle', 'shapeAngle']) {
      const v = q === true ? undefined : q[key];
      if (v === undefined) continue; // Blender's default, 40 degrees (Rust's QuadLimits)
      if (typeof v !== 'number' || !(v >= 0 && v <= Math.PI)) {
        throw new Error(`${PREFIX} quads.${key} must be an angle in radians from 0 to Math.PI, got ${describe(v)}`);
      }
      limits[key] = v;
    }
    own.quads = limits;
    const scheme = options.scheme === undefined ? 'catmull-clark' : Array.isArray(options.scheme) ? options.scheme[0] : options.scheme;
    if (typeof scheme === 'string' && !QUAD_SCHEMES.includes(scheme)) {
      throw new Error(`${PREFIX} quads: true joins triangles into quads for Catmull-Clark, but the scheme ` +
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

export function describe(value) {
  if (value === null) return 'null';
  if (value === undefined) return 'undefined';
  if (typeof value === 'string') return `'${value}'`;
  if (typeof value !== 'object') return String(value);
  if (Array.isArray(value)) return 'an Array';
  const name = value.constructor && value.constructor.name;
  return name && name !== 'Object' ? `a ${name}` : 'an object';
}

function checkChannel(array, itemSize, count, what) {
  if (!(array instanceof Float32Array) || !(itemSize >= 1 && itemSize <= 16) || array.length !== count * itemSize) {
    throw new Error(`${PREFIX} ${what} must be a Float32Array of ${count} items of 1 to 16 floats ` +
      `(itemSize ${itemSize}, ${array && array.length} floats)`);
  }
}

// ---------------------------------------------------------------------------------------------
// Welded copies and channels

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
    const compare = (u, v) => {
      for (let k = 0; k < itemSize; k++) {
        const d = bits[u * itemSize + k] - bits[v * itemSize + k];
        if (d) return d;
      }
      return 0;
    };
    for (let w = 0; w < numWelded; w++) {
      firstEqual(list, start[w], start[w + 1], compare, (v, u) => { fv[v] = u; });
    }
  }
  return { ...info, values, itemSize, fv };
}

/**
 * For each copy v in list[from..to] (ascending), found(v, u) with u the first copy there equal
 * to v by `compare` (a total order, 0 for equal), v itself when none before it is. A small group
 * is compared pairwise; a large one is sorted, since pairwise the hub of a fan (three.js's cone
 * has a copy of its apex per segment) cost k² steps: 118 s for a cone of 100k segments.
 */
function firstEqual(list, from, to, compare, found) {
  if (to - from <= 16) {
    for (let i = from; i < to; i++) {
      const v = list[i];
      let u = v;
      for (let j = from; j < i; j++) {
        if (compare(list[j], v) === 0) {
          u = list[j];
          break;
        }
      }
      found(v, u);
    }
    return;
  }
  const sorted = Array.from(list.subarray(from, to)).sort((a, b) => compare(a, b) || a - b);
  let first = sorted[0];
  for (let i = 0; i < sorted.length; i++) {
    if (i > 0 && compare(sorted[i - 1], sorted[i]) !== 0) first = sorted[i];
    found(sorted[i], first);
  }
}

/** Per input vertex, the first copy of its welded vertex that agrees on every face-varying channel. */
function cornerClasses(fvarChannels, copies, numInput) {
  if (!fvarChannels.length) return null;
  const cls = new Uint32Array(numInput);
  for (let v = 0; v < numInput; v++) cls[v] = v;
  const { start, list, numWelded } = copies;
  const compare = (u, v) => {
    for (const ch of fvarChannels) {
      const d = ch.fv[u] - ch.fv[v];
      if (d) return d;
    }
    return 0;
  };
  for (let w = 0; w < numWelded; w++) {
    firstEqual(list, start[w], start[w + 1], compare, (v, u) => { cls[v] = u; });
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
 * skinIndex / skinWeight (`itemSize` each per input vertex) as dense weight channels over the
 * bones used (each welded vertex takes its first copy's influences), chunks of up to 16 bones
 * per channel.
 */
function readSkin({ indices: I, weights: W, itemSize: m }, copies) {
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
// Tags: they name input vertices and triangles; mapped to welded vertices and kept triangles

function mapPairs(creases, weldOf, numInput, what) {
  if (creases === undefined) return null;
  if (!creases || !(creases.edges instanceof Uint32Array)) {
    throw new Error(`${PREFIX} ${what} must be { edges: Uint32Array (vertex pairs), sharpness: Float32Array }`);
  }
  const { edges, sharpness } = creases;
  if (!(sharpness instanceof Float32Array)) throw new Error(`${PREFIX} ${what}.sharpness must be a Float32Array`);
  if (edges.length % 2) throw new Error(`${PREFIX} ${what}.edges has ${edges.length} entries; give vertex pairs`);
  const n = edges.length / 2;
  if (sharpness.length !== 1 && sharpness.length !== n) {
    throw new Error(`${PREFIX} ${what}.sharpness has ${sharpness.length} entries; give one per edge (${n}) or one for all`);
  }
  const pairs = [];
  const kept = [];
  for (let i = 0; i < n; i++) {
    const a = edges[2 * i], b = edges[2 * i + 1];
    if (a >= numInput || b >= numInput) {
      throw new Error(`${PREFIX} ${what} ${i} names vertex ${Math.max(a, b)}, but the geometry has ${numInput}`);
    }
    const wa = weldOf[a], wb = weldOf[b];
    if (wa < 0 || wb < 0 || wa === wb) continue; // unused by any triangle, or welded into one
    pairs.push(wa, wb);
    kept.push(sharpness.length === 1 ? sharpness[0] : sharpness[i]);
  }
  return { pairs: Uint32Array.from(pairs), sharpness: Float32Array.from(kept) };
}

function mapCorners(corners, weldOf, numInput) {
  if (!corners || !(corners.vertices instanceof Uint32Array) || !(corners.sharpness instanceof Float32Array)) {
    throw new Error(`${PREFIX} corners must be { vertices: Uint32Array, sharpness: Float32Array }`);
  }
  const { vertices, sharpness } = corners;
  const v = [], s = [];
  for (let i = 0; i < vertices.length; i++) {
    if (vertices[i] >= numInput) throw new Error(`${PREFIX} corners ${i} names vertex ${vertices[i]}, but the geometry has ${numInput}`);
    const w = weldOf[vertices[i]];
    if (w < 0) continue;
    v.push(w);
    s.push(sharpness.length === 1 ? sharpness[0] : sharpness[i]);
  }
  return { vertices: Uint32Array.from(v), sharpness: Float32Array.from(s) };
}

/** `holes` names input triangles (index / 3); the kept triangles that are holes, ascending. */
function mapHoles(holes, kept, numTris) {
  if (holes === undefined) return null;
  if (!(holes instanceof Uint32Array)) throw new Error(`${PREFIX} holes must be a Uint32Array of triangles (index / 3)`);
  const isHole = new Uint8Array(numTris);
  for (const t of holes) {
    if (t >= numTris) throw new Error(`${PREFIX} holes names triangle ${t}, but the geometry has ${numTris}`);
    isHole[t] = 1;
  }
  const out = [];
  for (let k = 0; k < kept.length; k++) if (isHole[kept[k]]) out.push(k);
  return Uint32Array.from(out);
}
