// The subsurf demo page: pick a mesh (built in, or your own OBJ), a scheme per level, a level
// count and a boundary rule; a worker (subsurf/worker, see jobs.js) subdivides it with subsurf in
// WebAssembly, telling the page each level done, and the page draws the result over its control
// cage. The page itself only draws: meshes, OBJ parsing and writing, the predicted sizes,
// normals and edge lists all come from subsurf (see worker.js).
//
// Normals: every job asks subdivide for `normals: true` and the surface is shaded with them: the
// limit surface's normals where the last level's scheme has limit masks (Catmull-Clark, Loop,
// Quad/Triangle on quads or triangles only), else normals from the faces. The "limit surface"
// checkbox adds `limit: true` (the points move onto the limit); it is disabled, with a note,
// where the last scheme has no limit (Doo-Sabin, √3) and at level 0, and the worker drops it,
// saying why, where the library refuses it all the same (Quad/Triangle on a mixed mesh, the
// 'average' boundary).
//
// Animate (animation.js): the cage is twisted about the vertical axis and a wave runs along it,
// every frame; one Evaluator (BaseMesh.evaluator with the shown result's options, built on this
// page, again only when the result changes) gives each frame's positions and normals, written
// over the WebGL2 vertex buffers (the CPU path), or, with the GPU toggle, subsurf/webgpu's
// GpuEvaluator computes them and gpu-renderer.js draws its buffers on a WebGPU canvas over the
// WebGL one (the GPU path). Without WebGPU the toggle is disabled and says why.
//
// UVs: the built-in meshes carry UV layouts and OBJ files their vt lines; subsurf refines them as
// a face-varying channel (the fvarLinear menu picks OpenSubdiv's mode), toDrawable splits the
// refined vertices along the seams, and the surface shows a checker texture (renderer.js).
//
// Creases: an OBJ file's tags (readObj's mesh.tags) come with its mesh; its creased cage edges
// are drawn in pink, thicker, and subdivide honours them. Clicking a cage edge toggles it
// between smooth (sharpness 0) and the sharpness on the Creases slider (default 10, infinitely
// sharp) and subdivides again; that works on the built-in meshes too. The picking (nearest cage
// edge on screen, within a few pixels) is in picking.js.
//
// For tests: <html data-ready="true"> (and window.subsurfReady) once the first result is drawn;
// after every drawn result data-shape, data-scheme (one name per level, comma-separated),
// data-level, data-faces, data-vertices, data-faces-in, data-vertices-in, data-job,
// data-subdivide-ms, data-creases (creased edges the result honours), data-uv ("true" when the
// drawn surface has refined UVs), data-fvar-linear and data-drawn-vertices (the shaded mesh's
// vertices: more than data-vertices where UV seams split them); data-busy="true" from a
// change until its result is on screen (or refused), and meanwhile data-progress "2/4" once
// subdivide has done level 2 of 4 (the busy indicator says "level 2/4" too); data-error holds the error message on
// screen, if any; data-max-level the highest level under the memory guard; data-superseded how
// many jobs were cut short; data-normals "limit" or "faces" (where the shown result's normals
// come from) and data-limit ("true" when its points are on the limit surface). The animation:
// data-animate "true" or "false"; data-frames, the animated frames drawn so far; data-cpu-ms and
// data-gpu-ms, the mean time per frame of evaluate on the CPU and of the evaluation on the GPU
// over the last frames measured (absent until measured); data-gpu "on" or "off" (the GPU toggle)
// or "unavailable" (no WebGPU; absent until WebGPU has been looked for) and data-gpu-timing
// "timestamp-query", "submitted-work-done" or "none" (how the GPU time is measured; the query
// ?gpu-timing=work-done forces the second). window.subsurfDemo.creases() lists the creases of
// the selected mesh as [a, b, sharpness], edgeScreenPosition(i) gives the midpoint of cage edge i
// (display.cageEdges) in client pixels, pickAt(x, y) the cage edge a click there would toggle,
// and animator is the Animator (its evaluator, last frame, deformed cage and GPU evaluator).
import { compileSubsurf, JobRunner } from './jobs.js';
import { OrbitCamera, attachCameraControls, boundsOf } from './camera.js';
import { Renderer } from './renderer.js';
import { edgeKey, pickEdge, projectVertices } from './picking.js';
import { Animator, probeWebGpu } from './animation.js';
import { attachDropZone, showMessage } from './page.js';

const $ = (id) => document.getElementById(id);
const root = document.documentElement;

/** How many levels ahead the page asks subsurf to predict sizes (the slider never goes further). */
const LEVEL_CAP = 16;
/** A job shorter than this never shows the busy indicator, so quick changes do not flicker. */
const BUSY_DELAY_MS = 150;
/** How far from a cage edge, in CSS pixels, a click still picks it. */
const PICK_RADIUS = 6;
/** A press that moves farther than this, in CSS pixels, is a drag (orbit, pan), not a click. */
const CLICK_SLOP = 4;
/** OpenSubdiv's infinitely sharp (Sdc::Crease::SHARPNESS_INFINITE). */
const SHARPNESS_INFINITE = 10;
/** Schemes without limit masks: limit: true throws for a last level of these. */
const NO_LIMIT = new Set(['doo-sabin', 'sqrt3']);

const SHAPE_LABELS = {
  cube: 'Cube (6 quads)',
  torus: 'Torus (288 quads)',
  'sheet-with-holes': 'Sheet with two holes (boundaries)',
  icosahedron: 'Icosahedron (20 triangles)',
  dodecahedron: 'Dodecahedron (12 pentagons)',
  house: 'House (quads and triangles)',
};
const SCHEME_LABELS = {
  'catmull-clark': 'Catmull-Clark',
  loop: 'Loop (triangles only)',
  'doo-sabin': 'Doo-Sabin',
  'quad-triangle': 'Quad/Triangle',
  sqrt3: '√3 (triangles only)',
  bilinear: 'Bilinear',
  midpoint: 'Midpoint (triangles only)',
};
const BOUNDARY_LABELS = {
  'edge-and-corner': 'edge and corner (default)',
  'edge-only': 'edge only',
  fixed: 'fixed',
  average: 'average',
  none: 'none',
};
const FVAR_LABELS = {
  none: 'none (smooth everywhere)',
  'corners-only': 'corners only',
  'corners-plus1': 'corners plus 1 (default)',
  'corners-plus2': 'corners plus 2',
  boundaries: 'boundaries',
  all: 'all (linear)',
};
const FVAR_HINTS = {
  none: 'UVs are smoothed like the surface, seams and corners too.',
  'corners-only': 'UV corners stay sharp; seams are smoothed.',
  'corners-plus1': 'UV corners and where seams meet stay sharp (OpenSubdiv’s and USD’s default).',
  'corners-plus2': 'As corners plus 1, and darts and single-face corners stay sharp too.',
  boundaries: 'UVs are linear along seams and boundaries, smooth inside.',
  all: 'UVs are interpolated linearly everywhere, as bilinear.',
};
const BOUNDARY_HINTS = {
  'edge-and-corner': 'Boundary edges stay sharp; corners stay put.',
  'edge-only': 'Boundary edges stay sharp; corners are smoothed.',
  fixed: 'Boundary vertices do not move.',
  average: 'Boundary vertices move halfway to their edges’ midpoints.',
  none: 'No boundary rule: faces at the boundary are left out.',
};

const count = (n) => Number(n).toLocaleString('en-US');
const label = (labels, name) => labels[name] ?? name;

const state = {
  source: null, // the selected mesh: { value, label, kind: 'shape' | 'obj', name, text?, mesh? }
  scheme: 'catmull-clark',
  perLevel: false,
  levelSchemes: [], // with perLevel: the scheme of level i + 1
  level: 2,
  boundary: 'edge-and-corner',
  fvarLinear: 'corners-plus1',
  maxFaces: 1_000_000,
  maxLevel: null,
  predicted: null, // { vertices, faces } after 0..LEVEL_CAP levels, for the last planned job
  creaseSharpness: SHARPNESS_INFINITE, // what a click gives a smooth edge
  limit: false, // the limit surface checkbox (asked for only where the last scheme has a limit)
  animate: false,
  gpu: false, // the GPU toggle: the animation runs on WebGPU
};
// option value → source; a source also holds its tags: `creases` (edge key → { a, b, sharpness },
// as edited) and `fileTags` (readObj's tags: corners, holes, creaseMethod, ...; null for shapes)
const sources = new Map();
// what is on screen: { source, schemes, level, cage, cageEdges, result, surface, edges, options, job }
let display = null;
let hovered = -1; // the cage edge under the pointer, or -1
let runner;
let renderer;
let animator;
let animationToken = 0;
let notice = '';
let files = 0;
const camera = new OrbitCamera();
const canvas = $('view');
const gpuCanvas = $('view-gpu');
const timings = (window.subsurfTimings = { navigationToReady: null, firstJobMs: null });

// ---------------------------------------------------------------------------------------------
// Drawing

let drawPending = false;
const afterDraw = [];

/** Draws on the next animation frame; `after` runs once that frame has been presented. */
function requestDraw(after) {
  if (after) afterDraw.push(after);
  if (drawPending) return;
  drawPending = true;
  requestAnimationFrame((now) => {
    drawPending = false;
    const ratio = Math.min(devicePixelRatio, 2);
    const width = Math.round(canvas.clientWidth * ratio);
    const height = Math.round(canvas.clientHeight * ratio);
    if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
    const animating = state.animate && animator?.ready;
    if (animating) animationFrame(now);
    // On the GPU path the WebGPU canvas covers this one; the WebGL view is left as it was.
    if (renderer && !(animating && animator.onGpu)) {
      renderer.draw(camera, {
        smooth: document.querySelector('input[name=shading]:checked').value === 'smooth',
        wireframe: $('wireframe').checked,
        cage: $('cage').checked,
        texture: $('texture').checked,
      });
    }
    const callbacks = afterDraw.splice(0);
    if (callbacks.length) requestAnimationFrame(() => callbacks.forEach((callback) => callback()));
    if (state.animate && animator?.ready) requestDraw();
  });
}

function frameMesh() {
  if (!display) return;
  camera.frame(boundsOf(display.cage.positions));
  requestDraw();
}

// ---------------------------------------------------------------------------------------------
// Messages and the busy indicator

let busyTimer = null;
let busyUpdate = null;
let busyLevels = ''; // "level 2/4" once subdivide has told the first level of the job
function setBusy(busy, text) {
  clearInterval(busyTimer);
  busyTimer = null;
  busyUpdate = null;
  busyLevels = '';
  delete root.dataset.progress;
  $('busy').hidden = true;
  if (!busy) {
    delete root.dataset.busy;
    return;
  }
  root.dataset.busy = 'true';
  const since = performance.now();
  busyUpdate = () => {
    const elapsed = performance.now() - since;
    if (elapsed < BUSY_DELAY_MS) return;
    $('busy').hidden = false;
    $('busy-text').textContent = `${text}${busyLevels ? ` ${busyLevels} ·` : ''} ${(elapsed / 1000).toFixed(1)} s`;
  };
  busyTimer = setInterval(busyUpdate, 100);
}

/** Shows how far subdivide is: told by the worker after each level of the running job. */
function showProgress({ level, levels }) {
  if (!busyUpdate) return;
  busyLevels = `level ${level}/${levels}`;
  root.dataset.progress = `${level}/${levels}`;
  busyUpdate();
}

// ---------------------------------------------------------------------------------------------
// Jobs

/** The scheme of each level the page could ask for: the per-level choices, then the last one. */
function schemeList() {
  const list = [];
  for (let i = 0; i < LEVEL_CAP; i++) {
    list.push(state.perLevel ? (state.levelSchemes[i] ?? state.levelSchemes.at(-1) ?? state.scheme) : state.scheme);
  }
  return list;
}

function describeSchemes(schemes) {
  if (schemes.length === 0) return 'no subdivision';
  return schemes.every((s) => s === schemes[0])
    ? `${label(SCHEME_LABELS, schemes[0]).replace(/ \(.*\)$/, '')} ×${schemes.length}`
    : schemes.map((s) => label(SCHEME_LABELS, s).replace(/ \(.*\)$/, '')).join(' → ');
}

/**
 * Sends the current choices to the worker, superseding any job still running. A mesh not read
 * yet goes as its name or OBJ text, a known one as its arrays. When the mesh has just been
 * picked (`clampLevel`) the level is lowered to the highest that fits the memory guard;
 * otherwise it is kept, so that the library's guard speaks when the user asks for too much.
 */
function submit({ clampLevel = false } = {}) {
  const source = state.source;
  const input = source.mesh
    ? { kind: 'mesh', mesh: source.mesh }
    : source.kind === 'shape'
      ? { kind: 'shape', name: source.name }
      : { kind: 'obj', name: source.name, text: source.text };
  const job = {
    input,
    schemes: schemeList(),
    level: state.level,
    clampLevel: clampLevel || !source.mesh,
    boundary: state.boundary,
    maxFaces: state.maxFaces,
    fvarLinear: state.fvarLinear,
    limit: state.limit && limitUnavailable() === '',
    // Until its mesh is back from the worker, a file's own tags apply (null).
    tags: source.mesh ? tagOptions(source) : null,
  };
  const context = {
    source, posted: performance.now(), cage: source.mesh ?? null, creases: source.mesh ? creaseCount(source) : null, fvarLinear: state.fvarLinear,
  };
  runner.run(job, {
    plan: (message) => planned(message, context),
    progress: showProgress,
    result: (message) => finished(message, context),
    error: (message) => failed(message, context),
  });
  root.dataset.superseded = String(runner.superseded);
  updateLimitControl();
  setBusy(true, `Subdividing ${source.label}…`);
}

function planned(message, context) {
  const { source } = context;
  if (message.mesh) {
    const { positions, indices, faceSizes, tags, attributes } = message.mesh;
    source.mesh = { positions, indices, faceSizes, ...(attributes ? { attributes } : {}) };
    source.text = null;
    context.cage = source.mesh;
    if (tags) {
      source.fileTags = tags;
      source.creases = creasesFromTags(tags);
    }
    context.creases = creaseCount(source);
    if (source === state.source) updateCreaseLegend();
  }
  if (message.boundary !== state.boundary) setBoundary(message.boundary); // the file's tag
  state.maxLevel = message.maxLevel;
  state.predicted = message.predicted;
  root.dataset.maxLevel = String(message.maxLevel);
  notice = '';
  if (message.level !== state.level) {
    notice =
      `Level ${state.level} would make ${count(message.predicted.faces[state.level])} faces, more than the ` +
      `memory guard allows (${count(state.maxFaces)}); showing level ${message.level}.`;
    state.level = message.level;
  }
  updateLevelControls();
  setBusy(true, `Subdividing to ${count(message.predicted.faces[message.level])} faces…`);
}

function finished(message, context) {
  const { result, surface, edges, cageEdges, level, uvNotice, limitNotice, normals, limit, options, timings: workerTimings } = message;
  const { source, cage } = context;
  renderer.setRefined({ positions: result.positions, surface, edges });
  renderer.setCage({ positions: cage.positions, edges: cageEdges });
  const newSource = display?.source !== source;
  const schemes = schemeList().slice(0, level);
  display = { source, schemes, level, cage, cageEdges, result, surface, edges, options, normals, limit, job: message.id };
  hovered = -1;
  updateCageTags();
  if (newSource) camera.frame(boundsOf(cage.positions));
  if (state.animate) prepareAnimation();

  const faces = result.faceSizes.length;
  const vertices = result.positions.length / 3;
  const facesIn = cage.faceSizes.length;
  const verticesIn = cage.positions.length / 3;
  $('faces-in').textContent = count(facesIn);
  $('faces-out').textContent = count(faces);
  $('vertices-in').textContent = count(verticesIn);
  $('vertices-out').textContent = count(vertices);
  $('time').textContent = `${workerTimings.subdivide.toFixed(1)} ms`;
  $('download').disabled = false;
  $('download').title = `Save the ${count(faces)} faces as a Wavefront OBJ file`;
  const notices = [notice, uvNotice, limitNotice].filter(Boolean).join('\n');
  showMessage(notices || `${source.label}: ${describeSchemes(schemes)}.`, notices ? 'notice' : '');

  requestDraw(() => {
    // Busy until the result is on screen, unless a newer job has started meanwhile.
    if (!runner.busy) setBusy(false);
    const shownAfter = performance.now() - context.posted;
    $('time-detail').textContent =
      `+ edges and the drawable mesh ${workerTimings.display.toFixed(1)} ms; on screen ${shownAfter.toFixed(0)} ms after the change; ` +
      `${normals === 'limit' ? 'limit' : 'face'} normals${limit ? ', points on the limit' : ''}`;
    Object.assign(root.dataset, {
      shape: source.value,
      scheme: schemes.join(','),
      level: String(level),
      faces: String(faces),
      vertices: String(vertices),
      facesIn: String(facesIn),
      verticesIn: String(verticesIn),
      job: String(message.id),
      subdivideMs: workerTimings.subdivide.toFixed(2),
      creases: String(context.creases),
      uv: String(Boolean(surface.uvs)),
      fvarLinear: context.fvarLinear,
      drawnVertices: String(surface.positions.length / 3),
      normals,
      limit: String(limit),
    });
    if (!root.dataset.ready) {
      timings.navigationToReady = performance.now();
      timings.firstJobMs = shownAfter;
      root.dataset.ready = 'true';
      window.subsurfReady = true;
    }
  });
}

function failed(message, context) {
  setBusy(false);
  const { source } = context;
  if (!source.mesh && source === state.source && message.stage !== 'subdivide') {
    // The mesh could not be read: go back to the one before.
    const rejected = source;
    state.source = display?.source ?? sources.values().next().value;
    if (rejected.kind === 'obj') {
      sources.delete(rejected.value);
      $('shape').querySelector(`option[value="${rejected.value}"]`)?.remove();
    }
    $('shape').value = state.source.value;
    updateCreaseLegend();
    showMessage(`Could not open ${rejected.label}: ${message.message}\nThe view still shows the last result.`, 'error');
    return;
  }
  updateLevelControls();
  showMessage(`Not subdivided: ${message.message}\nThe view still shows the last result.`, 'error');
}

// ---------------------------------------------------------------------------------------------
// Creases

/** The creases of readObj's tags, by edge; an edge named twice takes the last value, as in subdivide. */
function creasesFromTags(tags) {
  const creases = new Map();
  const { edges, sharpness } = tags.creases;
  for (let i = 0; i < edges.length / 2; i++) {
    const [a, b] = [edges[2 * i], edges[2 * i + 1]];
    const value = sharpness.length === 1 ? sharpness[0] : sharpness[i];
    if (value > 0) creases.set(edgeKey(a, b), { a, b, sharpness: value });
    else creases.delete(edgeKey(a, b));
  }
  return creases;
}

const creaseCount = (source) => source.creases.size;

/** subdivide's tag options for `source`: its creases as edited, everything else as its file says. */
function tagOptions(source) {
  const creases = [...source.creases.values()];
  const { boundary, creases: fileCreases, ...fileTags } = source.fileTags ?? {};
  return {
    ...fileTags,
    creases: {
      edges: Uint32Array.from(creases.flatMap(({ a, b }) => [a, b])),
      sharpness: Float32Array.from(creases, ({ sharpness }) => sharpness),
    },
  };
}

/** Draws the tags of the mesh on screen over its cage: creased edges, sharp corners, the hovered edge. */
function updateCageTags() {
  if (!display) return;
  const { source, cageEdges } = display;
  const sharp = [];
  const semi = [];
  for (const { a, b, sharpness } of source.creases.values()) (sharpness >= SHARPNESS_INFINITE ? sharp : semi).push(a, b);
  const corners = source.fileTags?.corners;
  const sharpCorners = corners ? corners.vertices.filter((_, i) => (corners.sharpness.length === 1 ? corners.sharpness[0] : corners.sharpness[i]) > 0) : null;
  renderer.setCageTags({
    sharp: Uint32Array.from(sharp),
    semi: Uint32Array.from(semi),
    corners: sharpCorners,
    hover: hovered >= 0 ? cageEdges.subarray(2 * hovered, 2 * hovered + 2) : null,
  });
}

const plural = (n, one, many = `${one}s`) => `${count(n)} ${n === 1 ? one : many}`;

function updateCreaseLegend() {
  const source = state.source;
  const creases = [...source.creases.values()];
  const semi = creases.filter(({ sharpness }) => sharpness < SHARPNESS_INFINITE).length;
  let text = plural(creases.length, 'creased edge');
  if (semi > 0) text += ` (${semi === creases.length ? 'all' : count(semi)} semi-sharp)`;
  const corners = source.fileTags?.corners.vertices.length ?? 0;
  const holes = source.fileTags?.holes.length ?? 0;
  if (corners) text += `, ${plural(corners, 'sharp corner')}`;
  if (holes) text += `, ${plural(holes, 'hole')}`;
  $('crease-count').textContent = text;
  $('clear-creases').disabled = creases.length === 0;
}

function showCreaseSharpness() {
  const value = state.creaseSharpness;
  $('crease-sharpness-value').textContent = value >= SHARPNESS_INFINITE ? `${value} (∞)` : String(value);
}

/** The cage's vertices on screen, in CSS pixels of the canvas (see picking.js); deformed while animating. */
function cageOnScreen() {
  const { viewProjection } = camera.view(canvas.width / Math.max(canvas.height, 1));
  const positions = state.animate && animator.ready ? animator.prepared.deformed : display.cage.positions;
  return projectVertices(positions, viewProjection, canvas.clientWidth, canvas.clientHeight);
}

/** Edits act on the mesh on screen, and only while its cage (what the user clicks) is shown. */
const canEditCreases = () => display !== null && display.source === state.source && $('cage').checked;

/** The cage edge a click at client pixel (x, y) picks, or -1. */
function cageEdgeAt(x, y) {
  if (!canEditCreases()) return -1;
  const box = canvas.getBoundingClientRect();
  return pickEdge(display.cageEdges, cageOnScreen(), x - box.left, y - box.top, PICK_RADIUS);
}

/** Toggles cage edge `i` between smooth and the chosen sharpness, and subdivides again. */
function toggleCrease(i) {
  const { source, cageEdges } = display;
  const [a, b] = [cageEdges[2 * i], cageEdges[2 * i + 1]];
  const key = edgeKey(a, b);
  if (source.creases.has(key)) source.creases.delete(key);
  else source.creases.set(key, { a, b, sharpness: state.creaseSharpness });
  updateCageTags();
  updateCreaseLegend();
  requestDraw();
  submit();
}

function clearCreases() {
  if (state.source.creases.size === 0) return;
  state.source.creases.clear();
  updateCageTags();
  updateCreaseLegend();
  requestDraw();
  submit();
}

/** Clicks on the canvas pick cage edges; the pointer shows which edge a click would take. */
function attachCreaseEditing() {
  let press = null;
  canvas.addEventListener('pointerdown', (event) => {
    press = event.isPrimary && event.button === 0 && !event.shiftKey ? { x: event.clientX, y: event.clientY } : null;
  });
  canvas.addEventListener('click', (event) => {
    const moved = press ? Math.hypot(event.clientX - press.x, event.clientY - press.y) : Infinity;
    press = null;
    // The second click of a double click (which frames the mesh) is not a second toggle.
    if (event.detail > 1 || moved > CLICK_SLOP) return;
    const edge = cageEdgeAt(event.clientX, event.clientY);
    if (edge >= 0) toggleCrease(edge);
  });
  let pending = null;
  const hover = () => {
    const edge = pending ? cageEdgeAt(pending.x, pending.y) : -1;
    pending = null;
    canvas.classList.toggle('over-edge', edge >= 0);
    if (edge === hovered) return;
    hovered = edge;
    updateCageTags();
    requestDraw();
  };
  canvas.addEventListener('pointermove', (event) => {
    if (event.buttons !== 0 || event.pointerType === 'touch') return;
    if (!pending) requestAnimationFrame(hover);
    pending = { x: event.clientX, y: event.clientY };
  });
  canvas.addEventListener('pointerleave', () => {
    pending = null;
    hover();
  });
  $('crease-sharpness').addEventListener('input', (event) => {
    state.creaseSharpness = Number(event.target.value);
    showCreaseSharpness();
  });
  $('clear-creases').addEventListener('click', clearCreases);
}

// ---------------------------------------------------------------------------------------------
// The limit surface and the animation (animation.js)

/** Why the limit surface cannot be asked for with the current schemes and level, or ''. */
function limitUnavailable() {
  if (state.level === 0) return 'The limit surface needs at least one level.';
  const last = schemeList()[state.level - 1];
  if (NO_LIMIT.has(last)) {
    return `${label(SCHEME_LABELS, last).replace(/ \(.*\)$/, '')} has no limit masks: no limit surface, and its normals come from the faces.`;
  }
  return '';
}

function updateLimitControl() {
  const why = limitUnavailable();
  $('limit').disabled = why !== '';
  $('limit-label').classList.toggle('disabled', why !== '');
  $('limit-hint').textContent = why ||
    (state.limit ? 'The points are moved onto the limit surface.' : 'The points stay where the levels put them; the shading uses the limit normals.');
}

/** The subsurf module on this page (the workers have their own), for the animation's Evaluator. */
let subsurfOnPage = null;
let wasmModule = null;
function loadSubsurf() {
  subsurfOnPage ??= import('./pkg/subsurf.js').then((subsurf) => {
    subsurf.initSync({ module: wasmModule });
    return subsurf;
  });
  return subsurfOnPage;
}

/** Builds the animation's evaluator for the result on screen; a later call or a stop supersedes it. */
async function prepareAnimation() {
  const token = ++animationToken;
  // The evaluator of an earlier result must not write into the buffers of this one.
  animator.release();
  updateGpuView();
  if (!display) return;
  const shown = display;
  try {
    await animator.prepare(shown);
  } catch (error) {
    if (token !== animationToken) return;
    setAnimate(false);
    showMessage(`Cannot animate this result: ${error.message ?? error}`, 'error');
    return;
  }
  if (token !== animationToken) {
    if (!state.animate) animator.release();
    return;
  }
  if (state.gpu) startGpuPath();
  updateGpuView();
  requestDraw();
}

function startGpuPath() {
  try {
    animator.startGpu();
  } catch (error) {
    setGpu(false);
    showMessage(`The GPU path could not start: ${error.message ?? error}\nThe CPU path runs.`, 'notice');
  }
}

function setAnimate(on) {
  state.animate = on;
  $('animate').checked = on;
  root.dataset.animate = String(on);
  $('frame-times').hidden = !on;
  if (on) {
    prepareAnimation();
    return;
  }
  animationToken++;
  animator.release();
  // The still result again, in the buffers its frames overwrote.
  if (display) {
    const { result, surface, cage } = display;
    renderer.updateRefined({ positions: result.positions, surfacePositions: surface.positions, surfaceNormals: surface.normals });
    renderer.updateCage(cage.positions);
  }
  updateGpuView();
  requestDraw();
}

function setGpu(on) {
  state.gpu = on;
  $('gpu').checked = on;
  if (on && state.animate && animator.ready) startGpuPath();
  if (!on) animator.stopGpu();
  updateGpuView();
  requestDraw();
}

/** Shows the WebGPU canvas while the GPU path draws, and says what the GPU toggle can do. */
function updateGpuView() {
  gpuCanvas.hidden = !(state.animate && animator.onGpu);
  const gpu = animator.gpu;
  if (gpu) root.dataset.gpu = !gpu.available ? 'unavailable' : state.gpu ? 'on' : 'off';
}

/** One animated frame: deform, evaluate, upload (CPU) or evaluate and draw (GPU); then the figures. */
function animationFrame(now) {
  try {
    animator.step(now, camera, { cage: $('cage').checked });
  } catch (error) {
    if (animator.onGpu) {
      setGpu(false);
      showMessage(`The GPU path stopped: ${error.message ?? error}\nThe CPU path runs.`, 'notice');
    } else {
      setAnimate(false);
      showMessage(`The animation stopped: ${error.message ?? error}`, 'error');
    }
    return;
  }
  const ms = (mean) => (mean === null ? '–' : mean.toFixed(2));
  const cpu = animator.cpuTime.mean;
  const gpu = animator.gpuTime.mean;
  $('frame-times').textContent = `CPU: ${ms(cpu)} ms/frame · GPU: ${ms(gpu)} ms/frame`;
  root.dataset.frames = String(animator.frames);
  if (cpu !== null) root.dataset.cpuMs = cpu.toFixed(4);
  if (gpu !== null) root.dataset.gpuMs = gpu.toFixed(4);
}

async function startGpuProbe() {
  // ?gpu-timing=work-done measures with queue.onSubmittedWorkDone even where timestamp queries exist.
  const timestamps = new URLSearchParams(location.search).get('gpu-timing') !== 'work-done';
  const gpu = await probeWebGpu({ timestamps });
  animator.gpu = gpu;
  $('gpu').disabled = !gpu.available;
  $('gpu-label').classList.toggle('disabled', !gpu.available);
  $('gpu-note').textContent = gpu.available
    ? `WebGPU: the same evaluator in a compute shader, drawn from its buffers (GPU time from ${gpu.timestamps ? 'timestamp queries' : 'queue.onSubmittedWorkDone'}).`
    : gpu.note;
  $('gpu-note').classList.toggle('warn', !gpu.available);
  root.dataset.gpuTiming = gpu.available ? animator.gpuTiming : 'none';
  if (gpu.available) {
    gpu.device.lost.then((info) => {
      animator.gpu = { available: false, note: `WebGPU not available: the device was lost (${info.message || info.reason}); the CPU path runs.` };
      $('gpu-note').textContent = animator.gpu.note;
      $('gpu').disabled = true;
      setGpu(false);
    });
  }
  updateGpuView();
}

// ---------------------------------------------------------------------------------------------
// Controls

function fillSelect(select, names, labels) {
  select.replaceChildren(...names.map((name) => new Option(label(labels, name), name)));
}

function updateLevelControls() {
  const slider = $('level');
  const max = Math.min(LEVEL_CAP, Math.max(state.maxLevel ?? state.level, state.level));
  slider.max = String(max);
  slider.value = String(state.level);
  $('level-value').textContent = String(state.level);
  const hint = $('level-hint');
  if (state.maxLevel === null || !state.predicted) {
    hint.textContent = '';
    return;
  }
  const { faces } = state.predicted;
  const fits = state.maxLevel;
  const next = fits + 1 < faces.length ? ` Level ${fits + 1} would make ${count(faces[fits + 1])}.` : '';
  if (state.level > fits) {
    hint.textContent = `Level ${state.level} is over the memory guard; up to level ${fits} fits (${count(faces[fits])} faces).`;
    hint.className = 'hint warn';
  } else {
    hint.textContent = `Up to level ${fits} fits the memory guard (${count(faces[fits])} faces).${next}`;
    hint.className = 'hint';
  }
  renderLevelSchemes();
}

function renderLevelSchemes() {
  const list = $('level-schemes');
  list.hidden = !state.perLevel;
  $('scheme').disabled = state.perLevel;
  if (!state.perLevel) return;
  while (state.levelSchemes.length < state.level) state.levelSchemes.push(state.levelSchemes.at(-1) ?? state.scheme);
  const existing = list.querySelectorAll('select');
  if (existing.length === state.level) {
    // Same rows: keep them (an open menu stays open), only show the current choices.
    existing.forEach((select, i) => (select.value = state.levelSchemes[i]));
    return;
  }
  const rows = [];
  for (let i = 0; i < state.level; i++) {
    const select = document.createElement('select');
    select.className = 'level-scheme';
    select.dataset.level = String(i + 1);
    select.setAttribute('aria-label', `Scheme of level ${i + 1}`);
    fillSelect(select, [...$('scheme').options].map((o) => o.value), SCHEME_LABELS);
    select.value = state.levelSchemes[i];
    select.addEventListener('change', () => {
      state.levelSchemes[i] = select.value;
      submit();
    });
    const item = document.createElement('li');
    item.append(select);
    rows.push(item);
  }
  list.replaceChildren(...rows);
}

function selectSource(source) {
  state.source = source;
  $('shape').value = source.value;
  updateCreaseLegend();
  submit({ clampLevel: true });
}

function setFvarLinear(mode) {
  state.fvarLinear = mode;
  $('fvar-linear').value = mode;
  $('fvar-hint').textContent = FVAR_HINTS[mode] ?? '';
}

function setBoundary(boundary) {
  state.boundary = boundary;
  $('boundary').value = boundary;
  $('boundary-hint').textContent = BOUNDARY_HINTS[boundary] ?? '';
}

async function openFile(file) {
  if (!file) return;
  let text;
  try {
    text = await file.text();
  } catch (error) {
    showMessage(`Could not read ${file.name}: ${error.message}`, 'error');
    return;
  }
  const value = `file-${++files}`;
  const source = { value, label: file.name, kind: 'obj', name: file.name, text, creases: new Map(), fileTags: null };
  sources.set(value, source);
  $('shape').append(new Option(`File: ${file.name}`, value));
  selectSource(source);
}

async function download() {
  if (!display) return;
  const button = $('download');
  const { result, source, schemes, level } = display;
  button.disabled = true;
  try {
    const { positions, indices, faceSizes, attributes } = result;
    const blob = await runner.writeObj({ positions, indices, faceSizes, ...(attributes ? { attributes } : {}) });
    const base = (source.kind === 'shape' ? source.name : source.label.replace(/\.obj$/i, '')).replace(/[^\w.-]+/g, '_');
    const link = document.createElement('a');
    link.href = URL.createObjectURL(blob);
    link.download = `${base}-${[...new Set(schemes)].join('+') || 'input'}-L${level}.obj`;
    document.body.append(link);
    link.click();
    link.remove();
    setTimeout(() => URL.revokeObjectURL(link.href), 60_000);
  } catch (error) {
    showMessage(`Could not write the OBJ file: ${error.message}`, 'error');
  } finally {
    button.disabled = false;
  }
}

function attachControls() {
  $('shape').addEventListener('change', (event) => selectSource(sources.get(event.target.value)));
  $('open').addEventListener('click', () => $('file').click());
  $('file').addEventListener('change', (event) => {
    openFile(event.target.files[0]);
    event.target.value = ''; // the same file again is a new open
  });

  $('scheme').addEventListener('change', (event) => {
    state.scheme = event.target.value;
    submit();
  });
  $('per-level').addEventListener('change', (event) => {
    state.perLevel = event.target.checked;
    state.levelSchemes = state.perLevel ? Array(state.level).fill(state.scheme) : [];
    renderLevelSchemes();
    submit();
  });
  $('level').addEventListener('input', (event) => {
    state.level = Number(event.target.value);
    $('level-value').textContent = String(state.level);
    renderLevelSchemes();
    submit();
  });
  $('boundary').addEventListener('change', (event) => {
    setBoundary(event.target.value);
    submit();
  });
  $('fvar-linear').addEventListener('change', (event) => {
    setFvarLinear(event.target.value);
    submit();
  });
  $('guard').addEventListener('change', (event) => {
    state.maxFaces = Number(event.target.value);
    submit();
  });

  $('limit').addEventListener('change', (event) => {
    state.limit = event.target.checked;
    submit();
  });
  $('animate').addEventListener('change', (event) => setAnimate(event.target.checked));
  $('gpu').addEventListener('change', (event) => setGpu(event.target.checked));

  for (const input of document.querySelectorAll('input[name=shading], #wireframe, #cage, #texture')) {
    input.addEventListener('change', () => requestDraw());
  }
  attachCreaseEditing();
  $('frame').addEventListener('click', frameMesh);
  $('download').addEventListener('click', download);
  attachCameraControls(canvas, camera, { changed: () => requestDraw(), frame: frameMesh });
  new ResizeObserver(() => requestDraw()).observe(canvas);

  attachDropZone($('drop-zone'), (files) => openFile(files?.[0]));
}

async function main() {
  // Opaque (alpha: false): blended lines must not leave see-through pixels. The kept drawing
  // buffer lets tests and screenshots read the last frame.
  const gl = canvas.getContext('webgl2', { alpha: false, antialias: true, preserveDrawingBuffer: true });
  if (!gl) throw new Error('this browser has no WebGL2, which the demo needs to draw');
  renderer = new Renderer(gl);
  animator = new Animator({ renderer, gpuCanvas, loadSubsurf });
  root.dataset.animate = 'false';
  const gpuProbe = startGpuProbe();
  const module = await compileSubsurf();
  wasmModule = module;
  const started = await JobRunner.create(module);
  runner = started.runner;
  const { info } = started;

  for (const name of info.shapes) {
    sources.set(name, { value: name, label: label(SHAPE_LABELS, name).replace(/ \(.*\)$/, ''), kind: 'shape', name, creases: new Map(), fileTags: null });
  }
  fillSelect($('shape'), info.shapes, SHAPE_LABELS);
  fillSelect($('scheme'), info.schemes, SCHEME_LABELS);
  fillSelect($('boundary'), info.boundaries, BOUNDARY_LABELS);
  fillSelect($('fvar-linear'), info.fvarModes, FVAR_LABELS);
  setFvarLinear(state.fvarLinear);
  $('scheme').value = state.scheme;
  setBoundary(state.boundary);
  $('crease-sharpness').value = String(state.creaseSharpness);
  showCreaseSharpness();
  $('guard').value = String(state.maxFaces);
  $('version').textContent = `subsurf ${info.version} · WebAssembly in a Web Worker · WebGL2`;
  gpuProbe.then(() => {
    if (animator.gpu.available) $('version').textContent += ' · WebGPU';
  });
  window.subsurfDemo = {
    camera,
    state,
    runner,
    get display() {
      return display;
    },
    creases: () => [...(state.source?.creases.values() ?? [])].map(({ a, b, sharpness }) => [a, b, sharpness]),
    edgeScreenPosition(i) {
      const screen = cageOnScreen();
      const [a, b] = [3 * display.cageEdges[2 * i], 3 * display.cageEdges[2 * i + 1]];
      const box = canvas.getBoundingClientRect();
      return { x: box.left + (screen[a] + screen[b]) / 2, y: box.top + (screen[a + 1] + screen[b + 1]) / 2 };
    },
    pickAt: (x, y) => cageEdgeAt(x, y),
    get animator() {
      return animator;
    },
  };

  attachControls();
  state.source = sources.get('cube');
  selectSource(state.source);
}

main().catch((error) => {
  console.error(error);
  showMessage(`The demo could not start: ${error.message ?? error}`, 'error');
  root.dataset.fatal = String(error.message ?? error);
});
