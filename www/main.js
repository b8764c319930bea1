// The subsurf demo page: pick a mesh (built in, or your own OBJ), a scheme per level, a level
// count and a boundary rule; a worker subdivides it with subsurf in WebAssembly and the page draws
// the result over its control cage. The page itself only draws: meshes, OBJ parsing and writing,
// the predicted sizes, normals and edge lists all come from subsurf (see worker.js).
//
// For tests: <html data-ready="true"> (and window.subsurfReady) once the first result is drawn;
// after every drawn result data-shape, data-scheme (one name per level, comma-separated),
// data-level, data-faces, data-vertices, data-faces-in, data-vertices-in, data-job and
// data-subdivide-ms; data-busy="true" from a change until its result is on screen (or refused);
// data-error holds the error message on screen, if any; data-max-level the highest level under
// the memory guard; data-superseded how many jobs were cut short.
import { compileSubsurf, JobRunner } from './jobs.js';
import { OrbitCamera, attachCameraControls, boundsOf } from './camera.js';
import { Renderer } from './renderer.js';

const $ = (id) => document.getElementById(id);
const root = document.documentElement;

/** How many levels ahead the page asks subsurf to predict sizes (the slider never goes further). */
const LEVEL_CAP = 16;
/** A job shorter than this never shows the busy indicator, so quick changes do not flicker. */
const BUSY_DELAY_MS = 150;

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
  maxFaces: 1_000_000,
  maxLevel: null,
  predicted: null, // { vertices, faces } after 0..LEVEL_CAP levels, for the last planned job
};
const sources = new Map(); // option value → source
let display = null; // what is on screen: { source, schemes, level, cage, result, timings, job }
let runner;
let renderer;
let notice = '';
let files = 0;
const camera = new OrbitCamera();
const canvas = $('view');
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
  requestAnimationFrame(() => {
    drawPending = false;
    const ratio = Math.min(devicePixelRatio, 2);
    const width = Math.round(canvas.clientWidth * ratio);
    const height = Math.round(canvas.clientHeight * ratio);
    if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
    if (renderer) {
      renderer.draw(camera, {
        smooth: document.querySelector('input[name=shading]:checked').value === 'smooth',
        wireframe: $('wireframe').checked,
        cage: $('cage').checked,
      });
    }
    const callbacks = afterDraw.splice(0);
    if (callbacks.length) requestAnimationFrame(() => callbacks.forEach((callback) => callback()));
  });
}

function frameMesh() {
  if (!display) return;
  camera.frame(boundsOf(display.cage.positions));
  requestDraw();
}

// ---------------------------------------------------------------------------------------------
// Messages and the busy indicator

function showMessage(text, kind = '') {
  const message = $('message');
  message.textContent = text;
  message.className = kind;
  message.setAttribute('role', kind === 'error' ? 'alert' : 'status');
  if (kind === 'error') root.dataset.error = text;
  else delete root.dataset.error;
}

let busyTimer = null;
function setBusy(busy, text) {
  clearInterval(busyTimer);
  busyTimer = null;
  $('busy').hidden = true;
  if (!busy) {
    delete root.dataset.busy;
    return;
  }
  root.dataset.busy = 'true';
  const since = performance.now();
  const update = () => {
    const elapsed = performance.now() - since;
    if (elapsed < BUSY_DELAY_MS) return;
    $('busy').hidden = false;
    $('busy-text').textContent = `${text} ${(elapsed / 1000).toFixed(1)} s`;
  };
  busyTimer = setInterval(update, 100);
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
  };
  const context = { source, posted: performance.now(), cage: source.mesh ?? null };
  runner.run(job, {
    plan: (message) => planned(message, context),
    result: (message) => finished(message, context),
    error: (message) => failed(message, context),
  });
  root.dataset.superseded = String(runner.superseded);
  setBusy(true, `Subdividing ${source.label}…`);
}

function planned(message, context) {
  const { source } = context;
  if (message.mesh) {
    const { positions, indices, faceSizes } = message.mesh;
    source.mesh = { positions, indices, faceSizes };
    source.text = null;
    context.cage = source.mesh;
  }
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
  const { result, normals, edges, cageEdges, level, timings: workerTimings } = message;
  const { source, cage } = context;
  renderer.setRefined({ positions: result.positions, normals, triangles: result.triangles, edges });
  renderer.setCage({ positions: cage.positions, edges: cageEdges });
  const newSource = display?.source !== source;
  const schemes = schemeList().slice(0, level);
  display = { source, schemes, level, cage, result, job: message.id };
  if (newSource) camera.frame(boundsOf(cage.positions));

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
  showMessage(notice || `${source.label}: ${describeSchemes(schemes)}.`, notice ? 'notice' : '');

  requestDraw(() => {
    // Busy until the result is on screen, unless a newer job has started meanwhile.
    if (!runner.busy) setBusy(false);
    const shownAfter = performance.now() - context.posted;
    $('time-detail').textContent =
      `+ normals and edges ${workerTimings.display.toFixed(1)} ms; on screen ${shownAfter.toFixed(0)} ms after the change`;
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
    showMessage(`Could not open ${rejected.label}: ${message.message}\nThe view still shows the last result.`, 'error');
    return;
  }
  updateLevelControls();
  showMessage(`Not subdivided: ${message.message}\nThe view still shows the last result.`, 'error');
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
  submit({ clampLevel: true });
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
  const source = { value, label: file.name, kind: 'obj', name: file.name, text };
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
    const blob = await runner.writeObj({ positions: result.positions, indices: result.indices, faceSizes: result.faceSizes });
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
    state.boundary = event.target.value;
    $('boundary-hint').textContent = BOUNDARY_HINTS[state.boundary] ?? '';
    submit();
  });
  $('guard').addEventListener('change', (event) => {
    state.maxFaces = Number(event.target.value);
    submit();
  });

  for (const input of document.querySelectorAll('input[name=shading], #wireframe, #cage')) {
    input.addEventListener('change', () => requestDraw());
  }
  $('frame').addEventListener('click', frameMesh);
  $('download').addEventListener('click', download);
  attachCameraControls(canvas, camera, { changed: () => requestDraw(), frame: frameMesh });
  new ResizeObserver(() => requestDraw()).observe(canvas);

  // Drag and drop anywhere on the page.
  const dropZone = $('drop-zone');
  const hasFiles = (event) => [...(event.dataTransfer?.types ?? [])].includes('Files');
  let depth = 0;
  window.addEventListener('dragenter', (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    depth++;
    dropZone.hidden = false;
  });
  window.addEventListener('dragover', (event) => hasFiles(event) && event.preventDefault());
  window.addEventListener('dragleave', (event) => {
    if (!hasFiles(event)) return;
    depth = Math.max(0, depth - 1);
    if (depth === 0) dropZone.hidden = true;
  });
  window.addEventListener('drop', (event) => {
    event.preventDefault();
    depth = 0;
    dropZone.hidden = true;
    openFile(event.dataTransfer?.files?.[0]);
  });
}

async function main() {
  // Opaque (alpha: false): blended lines must not leave see-through pixels. The kept drawing
  // buffer lets tests and screenshots read the last frame.
  const gl = canvas.getContext('webgl2', { alpha: false, antialias: true, preserveDrawingBuffer: true });
  if (!gl) throw new Error('this browser has no WebGL2, which the demo needs to draw');
  renderer = new Renderer(gl);
  const module = await compileSubsurf();
  const started = await JobRunner.create(module);
  runner = started.runner;
  const { info } = started;

  for (const name of info.shapes) sources.set(name, { value: name, label: label(SHAPE_LABELS, name).replace(/ \(.*\)$/, ''), kind: 'shape', name });
  fillSelect($('shape'), info.shapes, SHAPE_LABELS);
  fillSelect($('scheme'), info.schemes, SCHEME_LABELS);
  fillSelect($('boundary'), info.boundaries, BOUNDARY_LABELS);
  $('scheme').value = state.scheme;
  $('boundary').value = state.boundary;
  $('boundary-hint').textContent = BOUNDARY_HINTS[state.boundary] ?? '';
  $('guard').value = String(state.maxFaces);
  $('version').textContent = `subsurf ${info.version} · WebAssembly in a Web Worker · WebGL2`;
  window.subsurfDemo = { camera, state, runner, get display() { return display; } };

  attachControls();
  state.source = sources.get('cube');
  selectSource(state.source);
}

main().catch((error) => {
  console.error(error);
  showMessage(`The demo could not start: ${error.message ?? error}`, 'error');
  root.dataset.fatal = String(error.message ?? error);
});
