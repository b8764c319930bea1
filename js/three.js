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
// This file only converts: BufferAttributes to typed arrays (readGeometry) and back
// (makeGeometry). The work between is `subdivideTriangles` of ./geometry.js (typed arrays in and
// out, no three.js objects), whose geometry runs in Rust behind the wasm bindings: on this
// thread for subdivideGeometry, in a subsurf/worker thread for subdivideGeometryAsync (the
// worker's table has it, so the worker bundle never imports three).
//
// It imports subsurf's plain glue ('./subsurf.js') through ./geometry.js, which must have been
// initialised before the first call. The package's "./three" export does that: in Node it
// resolves to three-node.js (loads the .wasm synchronously, as 'subsurf/node' does), elsewhere to
// three-auto.js (a top-level `await init()`). 'subsurf/three/init' is this file as it is: call
// `await init()` from 'subsurf/init' once first (subdivideGeometryAsync alone needs no init:
// its wasm is the worker's).
import { BufferAttribute, BufferGeometry } from 'three';
import { checkOptions, describe, readOwnOptions, subdivideTriangles } from './geometry.js';

/** Attributes not carried as channels: computed (normal), dropped (tangent) or special. */
const SPECIAL = new Set(['position', 'normal', 'tangent', 'skinIndex', 'skinWeight']);

/**
 * Subdivides a triangle BufferGeometry (indexed or not) and returns a new indexed
 * BufferGeometry. See three.d.ts and the README for the options and rules.
 */
export function subdivideGeometry(geometry, options = {}) {
  const read = readGeometry(geometry, options, false);
  return makeGeometry(read, subdivideTriangles(read.input, options));
}

/**
 * subdivideGeometry with its work (subdivideTriangles) in a subsurf/worker thread: the same
 * result, as a promise. See three.d.ts.
 */
export async function subdivideGeometryAsync(geometry, options = {}, call) {
  if (call === null || typeof call !== 'object' || !call.worker || typeof call.worker.call !== 'function') {
    throw new Error('subdivideGeometryAsync: the third argument must be { worker } (optionally with signal and ' +
      "onProgress), the worker from createWorker() of 'subsurf/worker' (one serves every call; terminate() it " +
      `when done), got ${call && typeof call === 'object' ? `${describe(call)} without a worker` : describe(call)}`);
  }
  const { worker, signal } = call;
  if (signal?.aborted) throw signal.reason ?? new DOMException('subdivideGeometryAsync was aborted', 'AbortError');
  // Copies of the caller's arrays (never their own buffers), so they can all be transferred.
  const read = readGeometry(geometry, options, true);
  let { onProgress, ...rest } = options;
  if (typeof onProgress !== 'function') rest = options; // subdivide refuses it with its own message
  let sent;
  try {
    // Also a copy: the options' own arrays (creases, holes) must not be detached by the transfer.
    sent = structuredClone(rest);
  } catch (error) {
    throw new TypeError(`subdivideGeometryAsync: the options cannot be sent to a worker: ${error.message}`);
  }
  const out = await worker.call('subdivideTriangles', [read.input, sent], {
    signal,
    onProgress: call.onProgress ?? (typeof onProgress === 'function' ? onProgress : undefined),
    transfer: true,
  });
  return makeGeometry(read, out);
}

/**
 * Checks the arguments and converts the geometry to subdivideTriangles' input, and keeps what
 * the result's BufferGeometry takes from the input (name, userData, instanced attributes, morph
 * target names). `copy`: every array of the input is a new one (the async call transfers them),
 * and the wasm module need not be initialised here.
 */
function readGeometry(geometry, options, copy) {
  if (!geometry || geometry.isBufferGeometry !== true) {
    throw new Error(`subdivideGeometry: the first argument must be a THREE.BufferGeometry, got ${describe(geometry)}` +
      (geometry && geometry.isMesh ? ' (a Mesh: pass mesh.geometry)' : ''));
  }
  if (options === null || typeof options !== 'object' || Array.isArray(options)) {
    throw new Error(`subdivideGeometry: options must be an object such as { levels: 2 }, got ${describe(options)}`);
  }
  if (copy) readOwnOptions(options);
  else checkOptions(options);

  const position = geometry.getAttribute('position');
  if (!position) {
    throw new Error("subdivideGeometry: the geometry has no 'position' attribute; " +
      `it has ${Object.keys(geometry.attributes).map((n) => `'${n}'`).join(', ') || 'no attributes'}`);
  }
  if (position.itemSize !== 3) {
    throw new Error(`subdivideGeometry: the 'position' attribute must have itemSize 3, got ${position.itemSize}`);
  }
  const numInput = position.count;
  const floats = (attr, what, raw) => readFloats(attr, what, raw, copy);
  const input = { positions: floats(position, 'position'), attributes: {}, morphAttributes: {} };
  const index = geometry.index;
  if (index) input.index = copy ? index.array.slice(0, index.count) : index.array.subarray(0, index.count);
  const instanced = [];
  for (const name of Object.keys(geometry.attributes)) {
    if (SPECIAL.has(name)) continue;
    const attr = geometry.attributes[name];
    if (attr && attr.isInstancedBufferAttribute) {
      instanced.push([name, attr.clone()]); // per instance, not per vertex: copied as it is
      continue;
    }
    checkCount(attr, numInput, `attribute '${name}'`);
    input.attributes[name] = { array: floats(attr, name), itemSize: attr.itemSize };
  }
  const morphs = geometry.morphAttributes || {};
  /** By morph attribute name, each target's name and itemSize. */
  const targets = {};
  for (const name of Object.keys(morphs)) {
    if (!Array.isArray(morphs[name])) continue;
    targets[name] = morphs[name].map((attr) => ({ name: attr && attr.name, itemSize: attr && attr.itemSize }));
    if (name === 'normal') continue;
    input.morphAttributes[name] = morphs[name].map((attr, i) => {
      checkCount(attr, numInput, `morphAttributes.${name}[${i}]`);
      return { array: floats(attr, `morph ${name}`), itemSize: attr.itemSize };
    });
  }
  input.morphNormals = targets.normal ? targets.normal.length : 0;
  input.morphTargetsRelative = geometry.morphTargetsRelative;
  input.skin = readSkin(geometry, numInput, copy);
  input.groups = geometry.groups || [];
  const normal = geometry.getAttribute('normal');
  if (options.sharpNormalSplits === true && normal) {
    checkCount(normal, numInput, "attribute 'normal'");
    input.normals = floats(normal, 'normal');
  }

  let userData;
  try {
    userData = JSON.parse(JSON.stringify(geometry.userData)); // as BufferGeometry.copy does
  } catch {
    userData = { ...geometry.userData };
  }
  return { input, name: geometry.name, userData, instanced, targets, morphTargetsRelative: geometry.morphTargetsRelative };
}

/** subdivideTriangles' output as a BufferGeometry, with what `read` kept of the input. */
function makeGeometry(read, out) {
  const result = new BufferGeometry();
  result.name = read.name;
  result.userData = read.userData;
  for (const [name, attr] of read.instanced) result.setAttribute(name, attr);
  result.setAttribute('position', new BufferAttribute(out.positions, 3));
  if (out.normals) result.setAttribute('normal', new BufferAttribute(out.normals, 3));
  for (const name of Object.keys(out.attributes)) {
    const { array, itemSize } = out.attributes[name];
    result.setAttribute(name, new BufferAttribute(array, itemSize));
  }
  if (out.skin) {
    result.setAttribute('skinIndex', new BufferAttribute(out.skin.indices, 4));
    result.setAttribute('skinWeight', new BufferAttribute(out.skin.weights, 4));
  }
  const morphNames = Object.keys(out.morphAttributes);
  for (const name of morphNames) {
    const source = read.targets[name];
    result.morphAttributes[name] = out.morphAttributes[name].map((array, i) => {
      const attr = new BufferAttribute(array, name === 'normal' ? 3 : source[i].itemSize);
      attr.name = source[i].name;
      return attr;
    });
  }
  if (morphNames.length) result.morphTargetsRelative = read.morphTargetsRelative;
  for (const { start, count, materialIndex } of out.groups) result.addGroup(start, count, materialIndex);
  result.setIndex(new BufferAttribute(out.index, 1));
  return result;
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

/**
 * An attribute's values as floats, itemSize per item (its own array when that is one already,
 * unless `copy`).
 */
function readFloats(attr, what, raw = false, copy = false) {
  const { itemSize, count } = attr;
  if (!attr.isInterleavedBufferAttribute && !attr.isFloat16BufferAttribute && attr.array instanceof Float32Array &&
      attr.array.length === count * itemSize) {
    return copy ? attr.array.slice() : attr.array;
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

/** skinIndex / skinWeight as `{ indices, weights, itemSize }` (raw bone indices), or null. */
function readSkin(geometry, numInput, copy) {
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
  return {
    indices: readFloats(skinIndex, 'skinIndex', true, copy),
    weights: readFloats(skinWeight, 'skinWeight', false, copy),
    itemSize: skinIndex.itemSize,
  };
}
