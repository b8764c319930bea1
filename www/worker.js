// The demo's worker: every call into subsurf that can take time runs here, so the page never
// freezes. It is a worker script of subsurf/worker's (jobs.js starts it with createWorker's
// `spawn`): `expose` from the package answers the page's calls with the functions below, posts
// their progress, transfers the buffers of their results, and the package on the page aborts a
// superseded job by terminating this worker and starting a fresh one from the compiled module.
//
// Functions (called as worker.call(name, [argument], { signal, onProgress })):
//   info()  → { version, schemes, boundaries, fvarModes, shapes }   (and warms the engine up)
//   job({ input, schemes, level, clampLevel, boundary, maxFaces, tags, fvarLinear, limit })
//       input: { kind: 'shape', name } | { kind: 'obj', name, text } | { kind: 'mesh', mesh }
//       schemes: one scheme name per level for every level the page could ask for (the page's
//       per-level choices, then its main scheme); the job uses the first `level` of them.
//       tags: subdivide's tag options (creases, corners, holes, creaseMethod, smoothTriangles),
//       or null: an OBJ file's own tags (readObj's mesh.tags, its boundary included), or none.
//       fvarLinear: how the mesh's UVs (its face-varying channel attributes.uv, if it has one)
//       are refined, for the checker texture. limit: ask for the limit surface (limit: true);
//       normals (normals: true) are always asked for.
//     progress: { type: 'plan', level, maxLevel, predicted, boundary, mesh? }
//       (mesh: the input with its tags and UVs, when not sent in; boundary: the one used), then
//       { type: 'level', level, levels, faces, vertices } after each level of subdivide
//     → { type: 'result', level, result, surface, edges, cageEdges, uvNotice, limitNotice,
//         normals, limit, options, timings }
//       surface: { positions, normals, uvs, triangles, origins } to shade: with UVs toDrawable's
//       mesh (vertices split along seams; origins: the result vertex of each), else the result
//       itself (uvs and origins null); uvNotice: why the UVs were dropped (a refusal that only
//       the UVs caused), or ''; limitNotice: why limit: true was dropped, or ''. normals:
//       'limit' (the limit surface's, from the last level's limit masks) or 'faces' (from the
//       faces around each vertex); limit: whether the points are on the limit. options: the
//       subdivide options used, for an Evaluator of the same surface (the page's animation).
//     or { type: 'error', stage: 'read' | 'predict' | 'subdivide', message } for a refusal;
//       a trap inside wasm is thrown instead, so that the package replaces this worker.
//   objBlob(mesh) → a Blob of writeObj's text (a Blob goes to the page without a copy)
import {
  subdivide, readObj, writeObj, shape, shapeNames, schemeNames, boundaryRules, fvarLinearModes,
  predictCounts, edgeList, toDrawable, version,
} from './pkg/subsurf.js';
import { expose } from './pkg/worker-thread.js';

expose({
  info() {
    warmUp();
    return { version: version(), schemes: schemeNames(), boundaries: boundaryRules(), fvarModes: fvarLinearModes(), shapes: shapeNames() };
  },
  job: ([job], { progress }) => runJob(job, progress ?? (() => {})),
  objBlob: ([mesh]) => new Blob([writeObj(mesh)], { type: 'model/obj' }),
});

// The engine compiles wasm functions on their first call; a tiny job here keeps that out of the
// time the page shows for the first real one.
function warmUp() {
  try {
    for (const [name, scheme] of [['cube', 'catmull-clark'], ['icosahedron', 'loop']]) {
      const mesh = shape(name);
      predictCounts(mesh, { scheme, levels: 1 });
      const out = subdivide(mesh, { scheme, levels: 1, normals: true });
      surfaceOf(out);
      edgeList(out);
    }
  } catch {
    // Only a warm-up: a real failure shows up in the real job.
  }
}

const isFatal = (error) => error instanceof WebAssembly.RuntimeError || error instanceof RangeError;

// A stage of a job: runs `work`; a refusal comes back as { error } for the page to show. A
// RuntimeError is a trap inside wasm (a bug, or memory exhausted): this instance is then
// unusable, so it is thrown on, and subsurf/worker replaces the worker.
function stage(name, work) {
  try {
    return { value: work() };
  } catch (error) {
    if (isFatal(error)) throw error;
    return { error: { type: 'error', stage: name, message: String(error?.message ?? error) } };
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

function runJob(job, progress) {
  const read = stage('read', () => inputMesh(job));
  if (read.error) return read.error;
  const mesh = read.value;
  // A file's interpolateboundary tag chooses the boundary rule; the page then shows it.
  const { boundary: fileBoundary, ...fileTags } = mesh.tags ?? {};
  const tags = job.tags ?? fileTags;
  const boundary = job.tags ? job.boundary : (fileBoundary ?? job.boundary);

  // The same counts formulas as subdivide's maxFaces guard, so maxLevel is exactly the highest
  // level the library accepts.
  const planned = stage('predict', () => predictCounts(mesh, { scheme: job.schemes, boundary }));
  if (planned.error) return planned.error;
  const predicted = planned.value;
  let maxLevel = 0;
  while (maxLevel + 1 < predicted.faces.length && predicted.faces[maxLevel + 1] <= job.maxFaces) maxLevel++;
  const level = job.clampLevel ? Math.min(job.level, maxLevel) : job.level;
  const plan = { type: 'plan', level, maxLevel, boundary, predicted: { vertices: [...predicted.vertices], faces: [...predicted.faces] } };
  if (job.input.kind !== 'mesh') plan.mesh = mesh; // copied: this worker still needs it
  progress(plan);

  const options = {
    ...tags, scheme: job.schemes.slice(0, level), levels: level, boundary, maxFaces: job.maxFaces, fvarLinear: job.fvarLinear, normals: true,
  };
  const onProgress = (p) => progress({ type: 'level', ...p });
  const { attributes, ...plain } = mesh;
  const withUv = attributes?.uv ? { ...plain, attributes: { uv: attributes.uv } } : plain;
  const started = performance.now();
  // Every scheme refines UVs, and the page only asks for the limit where the last scheme has
  // one; should a call be refused all the same, it is made again without the limit, then
  // without the UVs (and the limit again), and the page says what was dropped and why. Any
  // other refusal is the last call's.
  let uvNotice = '';
  let limitNotice = '';
  let useUv = withUv !== plain;
  let useLimit = Boolean(job.limit);
  let result;
  for (;;) {
    try {
      result = subdivide(useUv ? withUv : plain, { ...options, limit: useLimit, onProgress });
      break;
    } catch (error) {
      if (isFatal(error)) throw error;
      if (useLimit) {
        useLimit = false;
        limitNotice = `Limit surface not shown: ${String(error?.message ?? error)}`;
      } else if (useUv) {
        useUv = false;
        uvNotice = `UVs not shown: ${String(error?.message ?? error)}`;
        useLimit = Boolean(job.limit);
        limitNotice = '';
      } else {
        return { type: 'error', stage: 'subdivide', message: String(error?.message ?? error) };
      }
    }
  }
  const subdivided = performance.now();
  const display = stage('subdivide', () => ({
    surface: surfaceOf(result),
    edges: edgeList(result),
    cageEdges: edgeList(mesh),
  }));
  if (display.error) return display.error;
  const { surface, edges, cageEdges } = display.value;
  const timings = { subdivide: subdivided - started, display: performance.now() - subdivided };
  const used = { ...options, limit: useLimit };
  const normals = normalSource(used, result);
  // Every buffer of this object is transferred to the page (expose does it), none copied.
  return { type: 'result', level, result, surface, edges, cageEdges, uvNotice, limitNotice, normals, limit: useLimit, options: used, timings };
}

/**
 * Where subdivide's normals come from (see SubdivideOptions.normals): the limit masks of the last
 * level's scheme ('limit': Catmull-Clark and Loop, and Quad/Triangle on a mesh of quads or of
 * triangles only, which stays so) or the faces ('faces': the other schemes, and no levels).
 */
function normalSource({ scheme, levels }, result) {
  if (levels === 0) return 'faces';
  const last = scheme[levels - 1];
  if (last === 'catmull-clark' || last === 'loop') return 'limit';
  if (last === 'quad-triangle') {
    const sizes = result.faceSizes;
    const uniform = sizes.length > 0 && (sizes[0] === 3 || sizes[0] === 4) && sizes.every((n) => n === sizes[0]);
    return uniform ? 'limit' : 'faces';
  }
  return 'faces';
}

/**
 * What the page shades: with UVs, toDrawable's mesh, which splits the vertices along the seams
 * and carries the result's normals along as a channel (toDrawable takes channels only), with
 * `origins` to map later frames' positions and normals onto it; else the result itself.
 */
function surfaceOf(result) {
  const { normals } = result;
  const uv = result.attributes?.uv;
  if (!uv) return { positions: result.positions, normals, uvs: null, triangles: result.triangles, origins: null };
  const { positions, indices, faceSizes } = result;
  const drawable = toDrawable({ positions, indices, faceSizes, attributes: { uv, normal: { array: normals, itemSize: 3 } } });
  return {
    positions: drawable.positions,
    normals: drawable.attributes.normal.array,
    uvs: drawable.attributes.uv.array,
    triangles: drawable.triangles,
    origins: drawable.origins,
  };
}
