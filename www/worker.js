// The demo's worker: every call into subsurf that can take time runs here, so the page never
// freezes. The page compiles the WebAssembly module once and posts it to each worker it starts
// (instantiating a compiled module takes milliseconds), and terminates a worker whose job has
// been superseded: terminating is the only way to stop a running wasm call.
//
// Messages in:
//   { type: 'init', module }                      → { type: 'ready', version, schemes, boundaries, fvarModes, shapes }
//   { type: 'job', id, input, schemes, level, clampLevel, boundary, maxFaces, tags, fvarLinear }
//       input: { kind: 'shape', name } | { kind: 'obj', name, text } | { kind: 'mesh', mesh }
//       schemes: one scheme name per level for every level the page could ask for (the page's
//       per-level choices, then its main scheme); the job uses the first `level` of them.
//       tags: subdivide's tag options (creases, corners, holes, creaseMethod, smoothTriangles),
//       or null: an OBJ file's own tags (readObj's mesh.tags, its boundary included), or none.
//       fvarLinear: how the mesh's UVs (its face-varying channel attributes.uv, if it has one)
//       are refined, for the checker texture.
//     → { type: 'plan', id, level, maxLevel, predicted, boundary, mesh? }
//       (mesh: the input with its tags and UVs, when not sent in; boundary: the one used)
//     → { type: 'result', id, level, result, surface, edges, cageEdges, uvNotice, timings }
//       surface: { positions, normals, uvs, triangles } to shade: with UVs toDrawable's mesh
//       (vertices split along seams), else the result itself (uvs null); uvNotice: why the UVs
//       were dropped (a refusal that only the UVs caused), or ''.
//     or { type: 'error', id, stage: 'read' | 'predict' | 'subdivide', message, fatal }
//   { type: 'writeObj', id, mesh }                → { type: 'obj', id, blob } or an error
import {
  initSync, subdivide, readObj, writeObj, shape, shapeNames, schemeNames, boundaryRules, fvarLinearModes,
  predictCounts, vertexNormals, edgeList, toDrawable, version,
} from './pkg/subsurf.js';

let ready = false;
const waiting = [];

self.onmessage = ({ data }) => {
  if (data.type === 'init') {
    initSync({ module: data.module });
    warmUp();
    ready = true;
    self.postMessage({
      type: 'ready', version: version(), schemes: schemeNames(), boundaries: boundaryRules(), fvarModes: fvarLinearModes(), shapes: shapeNames(),
    });
    waiting.splice(0).forEach(handle);
  } else if (ready) {
    handle(data);
  } else {
    waiting.push(data);
  }
};

// The engine compiles wasm functions on their first call; a tiny job here keeps that out of the
// time the page shows for the first real one.
function warmUp() {
  try {
    for (const [name, scheme] of [['cube', 'catmull-clark'], ['icosahedron', 'loop']]) {
      const mesh = shape(name);
      predictCounts(mesh, { scheme, levels: 1 });
      const out = subdivide(mesh, { scheme, levels: 1 });
      surfaceOf(out, vertexNormals(out));
      edgeList(out);
    }
  } catch {
    // Only a warm-up: a real failure shows up in the real job.
  }
}

function handle(message) {
  if (message.type === 'job') runJob(message);
  else if (message.type === 'writeObj') exportObj(message);
}

// A stage of a job: runs `work`; on a thrown error posts it and returns undefined. A
// RuntimeError is a trap inside wasm (a bug, or memory exhausted): this instance is then
// unusable, so the page replaces the worker (`fatal`).
function stage(id, name, work) {
  try {
    return { value: work() };
  } catch (error) {
    const fatal = error instanceof WebAssembly.RuntimeError || error instanceof RangeError;
    self.postMessage({ type: 'error', id, stage: name, message: String(error?.message ?? error), fatal });
    return undefined;
  }
}

function inputMesh({ input }) {
  switch (input.kind) {
    case 'shape': return shape(input.name);
    case 'obj': return readObj(input.text);
    case 'mesh': return input.mesh;
    default: throw new Error(`unknown input kind ${input.kind}`);
  }
}

function runJob(job) {
  const { id } = job;
  const read = stage(id, 'read', () => inputMesh(job));
  if (!read) return;
  const mesh = read.value;
  // A file's interpolateboundary tag chooses the boundary rule; the page then shows it.
  const { boundary: fileBoundary, ...fileTags } = mesh.tags ?? {};
  const tags = job.tags ?? fileTags;
  const boundary = job.tags ? job.boundary : (fileBoundary ?? job.boundary);

  // The same counts formulas as subdivide's maxFaces guard, so maxLevel is exactly the highest
  // level the library accepts.
  const planned = stage(id, 'predict', () => predictCounts(mesh, { scheme: job.schemes, boundary }));
  if (!planned) return;
  const predicted = planned.value;
  let maxLevel = 0;
  while (maxLevel + 1 < predicted.faces.length && predicted.faces[maxLevel + 1] <= job.maxFaces) maxLevel++;
  const level = job.clampLevel ? Math.min(job.level, maxLevel) : job.level;
  const plan = { type: 'plan', id, level, maxLevel, boundary, predicted: { vertices: [...predicted.vertices], faces: [...predicted.faces] } };
  if (job.input.kind !== 'mesh') plan.mesh = mesh; // copied: this worker still needs it
  self.postMessage(plan);

  const options = {
    ...tags, scheme: job.schemes.slice(0, level), levels: level, boundary, maxFaces: job.maxFaces, fvarLinear: job.fvarLinear,
  };
  const { attributes, ...plain } = mesh;
  const withUv = attributes?.uv ? { ...plain, attributes: { uv: attributes.uv } } : plain;
  const started = performance.now();
  // Every scheme refines UVs; should a call with them be refused all the same, the surface is
  // subdivided without them, and the page says why. Any other refusal is the second call's.
  let uvNotice = '';
  let refined;
  try {
    refined = { value: subdivide(withUv, options) };
  } catch (error) {
    if (withUv === plain || error instanceof WebAssembly.RuntimeError || error instanceof RangeError) {
      refined = stage(id, 'subdivide', () => { throw error; });
    } else {
      refined = stage(id, 'subdivide', () => subdivide(plain, options));
      uvNotice = `UVs not shown: ${String(error?.message ?? error)}`;
    }
  }
  if (!refined) return;
  const subdivided = performance.now();
  const result = refined.value;
  const display = stage(id, 'subdivide', () => ({
    surface: surfaceOf(result, vertexNormals(result)),
    edges: edgeList(result),
    cageEdges: edgeList(mesh),
  }));
  if (!display) return;
  const { surface, edges, cageEdges } = display.value;
  const timings = { subdivide: subdivided - started, display: performance.now() - subdivided };
  const arrays = [result.positions, result.indices, result.faceSizes, result.triangles, edges, cageEdges];
  if (surface.uvs) arrays.push(surface.positions, surface.normals, surface.uvs, surface.triangles);
  else arrays.push(surface.normals);
  for (const channel of Object.values(result.attributes ?? {})) arrays.push(channel.array, channel.indices);
  const transfer = [...new Set(arrays.filter(Boolean).map((array) => array.buffer))];
  self.postMessage({ type: 'result', id, level, result, surface, edges, cageEdges, uvNotice, timings }, transfer);
}

/**
 * What the page shades: with UVs, toDrawable's mesh, which splits the vertices along the seams
 * and carries the normals along as a channel; else the result with its normals.
 */
function surfaceOf(result, normals) {
  const uv = result.attributes?.uv;
  if (!uv) return { positions: result.positions, normals, uvs: null, triangles: result.triangles };
  const { positions, indices, faceSizes } = result;
  const drawable = toDrawable({ positions, indices, faceSizes, attributes: { uv, normal: { array: normals, itemSize: 3 } } });
  return {
    positions: drawable.positions,
    normals: drawable.attributes.normal.array,
    uvs: drawable.attributes.uv.array,
    triangles: drawable.triangles,
  };
}

function exportObj({ id, mesh }) {
  const written = stage(id, 'write', () => writeObj(mesh));
  if (written) self.postMessage({ type: 'obj', id, blob: new Blob([written.value], { type: 'model/obj' }) });
}
