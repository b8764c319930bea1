// The glTF page: a model on the left as GLTFLoader gives it, the same model on the right with
// every mesh's geometry replaced by subsurf/three's subdivideGeometryAsync, one camera for both.
// The page only loads, clones and draws; every refined position, UV, normal, skin weight and
// morph target comes from subdivideGeometryAsync, which runs the work in a subsurf/worker thread
// so that the page stays responsive: the status tells each level as it is done, and a job
// superseded by a newer one (a slider moved again) is aborted.
//
// Each side has its own copy of the scene graph (SkeletonUtils.clone: a skinned mesh's clone is
// bound to cloned bones) and its own material clones, so a change to one side (the cage
// overlay, a disposed geometry) never shows on the other; textures are shared. The first
// animation clip plays on both sides from one clock, so they move together.
//
// For tests: <html data-ready="true"> once the first model is drawn; after every drawn result
// data-model, data-scheme, data-level (the level shown; data-requested-level the slider's),
// data-quads, data-crease-angle (degrees, or "off"), data-triangles-in, data-vertices-in,
// data-triangles-out, data-vertices-out, data-meshes, data-skinned (skinned meshes),
// data-morphed (meshes with morph targets), data-animation (the playing clip's name, or ""),
// data-subdivide-ms, data-cage ("full", "faint" or "hidden"), data-cage-edges and data-job (a
// counter of drawn results); data-busy="true" while loading or subdividing, #busy-text saying
// how far ("level k/n"); data-aborted counts superseded jobs aborted; data-error holds the error
// message on screen, if any. window.subsurfGltf has the scenes, camera and renderer.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { RoomEnvironment } from 'three/addons/environments/RoomEnvironment.js';
import * as SkeletonUtils from 'three/addons/utils/SkeletonUtils.js';
import { subdivideGeometryAsync } from 'subsurf/three';
import { createWorker } from 'subsurf/worker';
import { schemeNames, version } from 'subsurf';
import { attachDropZone, showMessage } from './page.js';

const $ = (id) => document.getElementById(id);
const root = document.documentElement;

/** Schemes whose first level takes quads: subdivideGeometry refuses `quads` with the others. */
const QUAD_SCHEMES = new Set(['catmull-clark', 'quad-triangle', 'bilinear', 'doo-sabin']);
/** Schemes whose every output face is a triangle; the others' faces are mostly quads. */
const TRIANGLE_SCHEMES = new Set(['loop', 'sqrt3', 'midpoint']);
/**
 * The most triangles the page draws on the right: beyond it a level is refused (the library's
 * own maxFaces guard, before any work) and the next lower one shown.
 */
const MAX_TRIANGLES = 2_000_000;
/** Above this many cage edges the cage is drawn faint, as on the WebGL2 page (renderer.js). */
const DENSE_CAGE_EDGES = 20_000;
const CAGE_COLOR = 0x5ac8ff; // style.css --accent, renderer.js's cage
const CAGE_OPACITY = { full: 0.7, faint: 0.08 };
const BACKGROUND = 0x1c1f24;
const FOV = 40;
/** From the front (+Z, where glTF models face), a little from the right and above. */
const VIEW_DIRECTION = new THREE.Vector3(0.5, 0.35, 1).normalize();

const SCHEME_LABELS = {
  'catmull-clark': 'Catmull-Clark',
  loop: 'Loop (triangles)',
  'doo-sabin': 'Doo-Sabin',
  'quad-triangle': 'Quad/Triangle',
  sqrt3: '√3 (triangles)',
  bilinear: 'Bilinear',
  midpoint: 'Midpoint (triangles)',
};

const count = (n) => Number(n).toLocaleString('en-US');

/** The thread every subdivision runs in; its .wasm and script come from beside subsurf/worker. */
const worker = createWorker();

const state = {
  scheme: 'catmull-clark',
  quads: true,
  level: 2,
  crease: false,
  creaseDegrees: 30,
  cage: true,
  animate: true,
};

// ---------------------------------------------------------------------------------------------
// Drawing: one renderer, two scenes, two halves of the canvas, one camera

const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(devicePixelRatio, 2));
renderer.setClearColor(BACKGROUND, 1);
const camera = new THREE.PerspectiveCamera(FOV, 1, 0.01, 100);
camera.position.set(0, 1, 4);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = false;

/** A scene with the lights and environment both sides share in kind (each needs its own). */
function makeScene(environment) {
  const scene = new THREE.Scene();
  scene.environment = environment;
  scene.add(new THREE.HemisphereLight(0xffffff, 0x444444, 0.6));
  const key = new THREE.DirectionalLight(0xffffff, 1.4);
  key.name = 'key light';
  scene.add(key);
  return scene;
}
const pmrem = new THREE.PMREMGenerator(renderer);
const environment = pmrem.fromScene(new RoomEnvironment(), 0.04).texture;
const left = { scene: makeScene(environment), root: null, mixer: null };
const right = { scene: makeScene(environment), root: null, mixer: null };

let framePending = false;
let lastTime = null;
const afterFrame = [];

/** Draws on the next animation frame; `after` runs once that frame has been drawn. */
function requestRender(after) {
  if (after) afterFrame.push(after);
  if (framePending) return;
  framePending = true;
  requestAnimationFrame(render);
}

function render(now) {
  framePending = false;
  const width = canvas.clientWidth;
  const height = canvas.clientHeight;
  if (canvas.width !== Math.round(width * renderer.getPixelRatio()) || canvas.height !== Math.round(height * renderer.getPixelRatio())) {
    renderer.setSize(width, height, false);
  }
  const animating = state.animate && model?.clip;
  const delta = animating && lastTime !== null ? Math.min((now - lastTime) / 1000, 0.1) : 0;
  lastTime = animating ? now : null;
  if (animating) {
    left.mixer.update(delta);
    right.mixer.update(delta);
  }
  const half = Math.floor(width / 2);
  camera.aspect = half / Math.max(height, 1);
  camera.updateProjectionMatrix();
  // The key light comes from over the viewer's left shoulder, wherever the camera goes.
  const lightPosition = camera.position.clone().add(new THREE.Vector3(-1, 1.5, 0.5).applyQuaternion(camera.quaternion).multiplyScalar(camera.position.distanceTo(controls.target)));
  renderer.setScissorTest(true);
  for (const [side, x, w] of [[left, 0, half], [right, half, width - half]]) {
    const key = side.scene.getObjectByName('key light');
    key.position.copy(lightPosition);
    key.target.position.copy(controls.target);
    key.target.updateMatrixWorld();
    renderer.setViewport(x, 0, w, height);
    renderer.setScissor(x, 0, w, height);
    renderer.render(side.scene, camera);
  }
  renderer.setScissorTest(false);
  const callbacks = afterFrame.splice(0);
  for (const callback of callbacks) callback();
  if (animating) requestRender();
}

controls.addEventListener('change', () => requestRender());
new ResizeObserver(() => requestRender()).observe(canvas);

/**
 * Frames the model from its bounding box in world space (node transforms and the current pose
 * included): the camera looks at the box's centre from VIEW_DIRECTION, far enough back that the
 * box's bounding sphere fits the narrower of the viewport's two fields of view. glTF is Y-up,
 * so the camera's up is +Y.
 */
function frameModel() {
  if (!left.root) return;
  left.root.updateMatrixWorld(true);
  const box = new THREE.Box3().setFromObject(left.root);
  if (box.isEmpty()) return;
  const sphere = box.getBoundingSphere(new THREE.Sphere());
  const radius = Math.max(sphere.radius, 1e-6);
  const aspect = Math.floor(canvas.clientWidth / 2) / Math.max(canvas.clientHeight, 1);
  const vertical = THREE.MathUtils.degToRad(FOV) / 2;
  const horizontal = Math.atan(Math.tan(vertical) * aspect);
  const distance = (1.1 * radius) / Math.sin(Math.min(vertical, horizontal));
  camera.up.set(0, 1, 0);
  camera.position.copy(sphere.center).addScaledVector(VIEW_DIRECTION, distance);
  camera.near = Math.max(distance - 4 * radius, distance / 1000);
  camera.far = distance + 8 * radius;
  camera.updateProjectionMatrix();
  controls.target.copy(sphere.center);
  controls.minDistance = radius * 0.05;
  controls.maxDistance = radius * 40;
  controls.update();
  requestRender();
}

// ---------------------------------------------------------------------------------------------
// The busy indicator

function setBusy(text) {
  $('busy').hidden = !text;
  $('busy-text').textContent = text ?? '';
  if (text) root.dataset.busy = 'true';
  else delete root.dataset.busy;
}

// ---------------------------------------------------------------------------------------------
// The model

/**
 * What is shown: { name, meshes: [{ source, target, cage, original }], clip, urls, textures }.
 * `source` is the left side's mesh (its geometry is the input), `target` the right side's copy
 * (its geometry the result), `cage` the overlay drawing the input's triangles over the result.
 */
let model = null;
let jobs = 0;

/** Frees what a model owns: its geometries, materials, textures and the files' object URLs. */
function disposeModel(shown) {
  if (!shown) return;
  const done = new Set();
  const dispose = (thing) => {
    if (thing && !done.has(thing)) {
      done.add(thing);
      thing.dispose();
    }
  };
  for (const side of [left, right]) {
    side.root?.traverse((object) => {
      if (!object.isMesh) return;
      dispose(object.geometry);
      for (const material of [object.material].flat()) {
        for (const value of Object.values(material)) if (value?.isTexture) dispose(value);
        dispose(material);
      }
    });
    if (side.root) side.scene.remove(side.root);
    side.mixer?.stopAllAction();
    side.root = null;
    side.mixer = null;
  }
  for (const url of shown.urls) URL.revokeObjectURL(url);
}

const cloneMaterial = (material) => (Array.isArray(material) ? material.map((m) => m.clone()) : material.clone());

/** Shows `gltf` ({ scene, animations }) as the model `name`; `urls` are freed with it. */
function showModel(gltf, name, urls = [], notices = []) {
  disposeModel(model);
  const source = gltf.scene;
  // The right side: the same graph, bones and all, with its own materials.
  const target = SkeletonUtils.clone(source);
  const sources = [];
  const targets = [];
  source.traverse((object) => object.isMesh && sources.push(object));
  target.traverse((object) => object.isMesh && targets.push(object));
  const meshes = sources.map((mesh, i) => {
    const copy = targets[i];
    copy.material = cloneMaterial(mesh.material);
    // The cage: the input geometry as lines over the result, deformed as the result is: a
    // child of it (node animation), a skinned copy bound to the same bones, the same morph
    // influences. Nameless, so the animation's tracks (bound by name) keep finding the
    // result's mesh.
    const cage = copy.clone(false);
    cage.name = '';
    cage.position.set(0, 0, 0);
    cage.quaternion.identity();
    cage.scale.set(1, 1, 1);
    cage.material = new THREE.MeshBasicMaterial({ color: CAGE_COLOR, wireframe: true, transparent: true, depthWrite: false });
    if (copy.morphTargetInfluences) cage.morphTargetInfluences = copy.morphTargetInfluences;
    cage.frustumCulled = false;
    cage.renderOrder = 1;
    return { source: mesh, target: copy, cage };
  });
  for (const { target: copy, cage } of meshes) copy.add(cage);
  left.root = source;
  right.root = target;
  left.scene.add(source);
  right.scene.add(target);
  const clip = gltf.animations?.[0] ?? null;
  if (clip) {
    for (const side of [left, right]) {
      side.mixer = new THREE.AnimationMixer(side.root);
      side.mixer.clipAction(clip).play();
    }
  }
  const triangles = meshes.reduce((sum, { source: mesh }) => sum + triangleCount(mesh.geometry), 0);
  model = {
    name,
    meshes,
    clip,
    urls,
    notices,
    trianglesIn: triangles,
    verticesIn: meshes.reduce((sum, { source: mesh }) => sum + mesh.geometry.getAttribute('position').count, 0),
    cageEdges: Math.round(1.5 * triangles), // each edge of a closed triangle mesh has two triangles
    skinned: meshes.filter(({ source: mesh }) => mesh.isSkinnedMesh).length,
    morphed: meshes.filter(({ source: mesh }) => Object.keys(mesh.geometry.morphAttributes).length > 0).length,
  };
  $('model-name').textContent = name;
  $('animate').disabled = !clip;
  $('animate').parentElement.title = clip ? `Play "${clip.name || 'animation 0'}" on both sides` : 'This model has no animation';
  frameModel();
  subdivideModel();
}

const triangleCount = (geometry) => Math.floor((geometry.index ? geometry.index.count : geometry.getAttribute('position').count) / 3);

/** The options of subdivideGeometry for the controls, `level` levels. */
function optionsFor(level) {
  const options = { scheme: state.scheme, levels: level };
  if (state.quads && QUAD_SCHEMES.has(state.scheme)) options.quads = true;
  if (state.crease) options.creaseAngle = THREE.MathUtils.degToRad(state.creaseDegrees);
  return options;
}

class OverBudget extends Error {}

/**
 * Subdivides every mesh of the model at `level` in the worker, one after the other; throws
 * OverBudget when the results would pass MAX_TRIANGLES (the library says so before any work:
 * maxFaces is the rest of the budget), and the signal's AbortError when a newer job aborted this
 * one. Returns the new geometries (null for a mesh subdivideGeometryAsync refused, with why) and
 * the time.
 */
async function subdivideAll(level, signal) {
  const made = [];
  const refused = [];
  let remaining = MAX_TRIANGLES;
  let ms = 0;
  const perFace = TRIANGLE_SCHEMES.has(state.scheme) ? 1 : 2;
  const meshes = model.meshes;
  try {
    for (const [i, { source }] of meshes.entries()) {
      const geometry = source.geometry;
      geometry.computeBoundingSphere();
      const options = {
        ...optionsFor(level),
        maxFaces: Math.max(1, Math.floor(remaining / perFace)),
        // Exporters now and then write a seam's copies of a vertex a few float steps apart;
        // welding within a millionth of the mesh's size closes such seams and nothing else.
        weld: geometry.boundingSphere.radius * 1e-6,
      };
      const which = meshes.length > 1 ? ` mesh ${i + 1}/${meshes.length}` : '';
      setBusy(`Subdividing${which}…`);
      const onProgress = (p) => setBusy(`Subdividing${which}… level ${p.level}/${p.levels}`);
      const start = performance.now();
      let result = null;
      try {
        result = await subdivideGeometryAsync(geometry, options, { worker, signal, onProgress });
      } catch (error) {
        if (signal.aborted) throw error;
        if (/would make .* faces, more than the limit/.test(error.message)) throw new OverBudget(error.message);
        refused.push(`${source.name || 'a mesh'}: ${error.message}`);
      }
      ms += performance.now() - start;
      if (result) {
        made.push(result);
        remaining -= triangleCount(result);
        if (remaining < 0) throw new OverBudget(`more than ${count(MAX_TRIANGLES)} triangles`);
      } else {
        made.push(null);
      }
    }
  } catch (error) {
    for (const geometry of made) geometry?.dispose();
    throw error;
  }
  return { made, refused, ms };
}

/** The job running (its AbortController), if any: a newer job aborts it. */
let running = null;
let aborted = 0;

/**
 * Subdivides the model with the controls' options, in the worker, and shows the result on the
 * right. A newer request made meanwhile (a slider dragged on, another model) aborts this one.
 */
async function subdivideModel() {
  if (!model) return;
  if (running) {
    running.abort();
    root.dataset.aborted = String(++aborted);
  }
  const controller = new AbortController();
  running = controller;
  const { signal } = controller;
  setBusy('Subdividing…');
  let level = state.level;
  let outcome = null;
  let notice = '';
  for (; level >= 0; level--) {
    try {
      outcome = await subdivideAll(level, signal);
      break;
    } catch (error) {
      if (signal.aborted) return; // the newer job shows its own state
      if (!(error instanceof OverBudget)) {
        running = null;
        setBusy(null);
        showMessage(`${model.name}: not subdivided: ${error.message ?? error}`, 'error');
        return;
      }
      notice ||= `Level ${state.level} would draw more than ${count(MAX_TRIANGLES)} triangles; showing level ${level - 1}.`;
    }
  }
  if (signal.aborted) {
    for (const geometry of outcome?.made ?? []) geometry?.dispose();
    return;
  }
  running = null;
  if (!outcome) {
    setBusy(null);
    showMessage(`${model.name}: even level 0 is over ${count(MAX_TRIANGLES)} triangles; nothing subdivided.`, 'error');
    return;
  }
  const { made, refused, ms } = outcome;
  let trianglesOut = 0;
  let verticesOut = 0;
  model.meshes.forEach((entry, i) => {
    const { source, target } = entry;
    const geometry = made[i] ?? source.geometry;
    if (target.geometry !== source.geometry) target.geometry.dispose();
    target.geometry = geometry;
    // Recomputed from the new geometry when next needed (frustum culling, raycasts).
    if (target.isSkinnedMesh) target.boundingBox = target.boundingSphere = null;
    trianglesOut += triangleCount(geometry);
    verticesOut += geometry.getAttribute('position').count;
  });
  const job = ++jobs;
  const shown = { level, ms, trianglesOut, verticesOut };
  updateCage();
  $('level-hint').textContent = notice;
  $('level-hint').className = notice ? 'hint warn' : 'hint';
  $('triangles-in').textContent = count(model.trianglesIn);
  $('vertices-in').textContent = count(model.verticesIn);
  $('triangles-out').textContent = count(trianglesOut);
  $('vertices-out').textContent = count(verticesOut);
  $('time').textContent = `${ms.toFixed(1)} ms`;
  $('label-left').textContent = `original · ${count(model.trianglesIn)} triangles`;
  $('label-right').textContent = `${SCHEME_LABELS[state.scheme]?.replace(/ \(.*\)$/, '') ?? state.scheme} × ${level} · ${count(trianglesOut)} triangles`;
  const notices = [notice, ...model.notices, ...refused.map((r) => `Not subdivided (shown as it is): ${r}`)].filter(Boolean);
  const parts = [`${model.meshes.length} mesh${model.meshes.length === 1 ? '' : 'es'}`];
  if (model.skinned) parts.push(`${model.skinned} skinned`);
  if (model.morphed) parts.push(`${model.morphed} with morph targets`);
  if (model.clip) parts.push(`playing "${model.clip.name || 'animation 0'}"`);
  showMessage([`${model.name}: ${parts.join(', ')}.`, ...notices].join('\n'), notices.length ? 'notice' : '');
  requestRender(() => {
    // A job started since keeps its own busy state.
    if (!running) setBusy(null);
    Object.assign(root.dataset, {
      model: model.name,
      scheme: state.scheme,
      level: String(shown.level),
      requestedLevel: String(state.level),
      quads: String(Boolean(optionsFor(1).quads)),
      creaseAngle: state.crease ? String(state.creaseDegrees) : 'off',
      trianglesIn: String(model.trianglesIn),
      verticesIn: String(model.verticesIn),
      trianglesOut: String(shown.trianglesOut),
      verticesOut: String(shown.verticesOut),
      meshes: String(model.meshes.length),
      skinned: String(model.skinned),
      morphed: String(model.morphed),
      animation: model.clip ? model.clip.name || 'animation 0' : '',
      subdivideMs: shown.ms.toFixed(2),
      job: String(job),
    });
    root.dataset.ready = 'true';
  });
}

/** Shows, fades or hides the cage overlays by the checkbox and the cage's size. */
function updateCage() {
  if (!model) return;
  const dense = model.cageEdges > DENSE_CAGE_EDGES;
  const style = !state.cage ? 'hidden' : dense ? 'faint' : 'full';
  for (const { cage } of model.meshes) {
    cage.visible = style !== 'hidden';
    if (cage.visible) cage.material.opacity = CAGE_OPACITY[style];
  }
  root.dataset.cage = style;
  root.dataset.cageEdges = String(model.cageEdges);
  $('cage-hint').textContent = dense
    ? `The cage has about ${count(model.cageEdges)} edges, more than ${count(DENSE_CAGE_EDGES)}: drawn faint.`
    : '';
  requestRender();
}

// ---------------------------------------------------------------------------------------------
// The built-in model: three.js's own geometries with a checker texture drawn on a canvas

/**
 * 8 × 8 squares per unit of UV: light ones in hues running round the colour wheel with u, dark
 * ones slate, so that the direction of the layout and its seams show.
 */
function checkerTexture(size = 512, squares = 8) {
  const canvas2d = document.createElement('canvas');
  canvas2d.width = canvas2d.height = size;
  const context = canvas2d.getContext('2d');
  const cell = size / squares;
  for (let j = 0; j < squares; j++) {
    for (let i = 0; i < squares; i++) {
      context.fillStyle = (i + j) % 2 === 0 ? `hsl(${Math.round((360 * i) / squares)} 75% 62%)` : `hsl(215 20% ${24 + 3 * j}%)`;
      context.fillRect(i * cell, j * cell, cell, cell);
    }
  }
  const texture = new THREE.CanvasTexture(canvas2d);
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.wrapS = texture.wrapT = THREE.RepeatWrapping;
  texture.anisotropy = 8;
  return texture;
}

/**
 * A torus knot and a box, both textured, in a group that turns (a node animation, so that the
 * built-in model shows the animation path too). glTF-like: non-indexed seams split as
 * GLTFLoader's geometries are, Y-up. subdivideGeometry welds the box's 24 vertices back to 8.
 */
function builtInModel() {
  const map = checkerTexture();
  const material = new THREE.MeshStandardMaterial({ map, roughness: 0.55, metalness: 0 });
  const knot = new THREE.Mesh(new THREE.TorusKnotGeometry(0.7, 0.25, 64, 8), material);
  knot.name = 'knot';
  knot.position.set(-0.55, 0, 0);
  const boxMap = map.clone();
  boxMap.repeat.set(0.5, 0.5);
  const box = new THREE.Mesh(new THREE.BoxGeometry(0.9, 0.9, 0.9), new THREE.MeshStandardMaterial({ map: boxMap, roughness: 0.55 }));
  box.name = 'box';
  box.position.set(1.15, 0, 0);
  const group = new THREE.Group();
  group.name = 'built-in';
  group.add(knot, box);
  const turn = new THREE.QuaternionKeyframeTrack('box.quaternion', [0, 4, 8],
    [0, 0, 0, 1, ...new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), Math.PI).toArray(), 0, 0, 0, -1]);
  return { scene: group, animations: [new THREE.AnimationClip('box turns', 8, [turn])] };
}

// ---------------------------------------------------------------------------------------------
// Opening files: a .glb, or a .gltf with its .bin and images, through the file input or a drop

/** The file names a glTF's URI may refer to, most specific first. */
function candidateNames(uri) {
  const path = decodeURIComponent(uri.split(/[?#]/)[0]).replace(/^(\.\/)+/, '');
  return [path, path.split('/').pop()];
}

async function openFiles(fileList) {
  const files = [...(fileList ?? [])];
  if (files.length === 0) return;
  const main = files.find((f) => /\.glb$/i.test(f.name)) ?? files.find((f) => /\.gltf$/i.test(f.name));
  if (!main) {
    showMessage(`None of ${files.map((f) => f.name).join(', ')} is a .glb or .gltf file.`, 'error');
    return;
  }
  // The other files, by name, as object URLs: the glTF's URIs are resolved against them.
  const byName = new Map(files.filter((f) => f !== main).map((f) => [f.name, URL.createObjectURL(f)]));
  const missing = new Set();
  const manager = new THREE.LoadingManager();
  manager.setURLModifier((url) => {
    if (/^(data|blob):/.test(url)) return url;
    for (const name of candidateNames(url)) if (byName.has(name)) return byName.get(name);
    missing.add(candidateNames(url)[0]);
    return url;
  });
  setBusy(`Loading ${main.name}…`);
  const extra = files.length > 1 ? ` with ${files.length - 1} other file${files.length > 2 ? 's' : ''}` : '';
  try {
    const data = /\.glb$/i.test(main.name) ? await main.arrayBuffer() : await main.text();
    const gltf = await new GLTFLoader(manager).parseAsync(data, '');
    const notices = missing.size
      ? [`Missing: ${[...missing].join(', ')} (open or drop the .gltf together with its .bin and image files).`]
      : [];
    showModel(gltf, main.name, [...byName.values()], notices);
  } catch (error) {
    for (const url of byName.values()) URL.revokeObjectURL(url);
    setBusy(null);
    const hint = missing.size ? `\nMissing: ${[...missing].join(', ')}: open or drop them together with ${main.name}.` : '';
    showMessage(`Could not open ${main.name}${extra}: ${error.message ?? error}${hint}\nThe view still shows the last model.`, 'error');
  }
}

// ---------------------------------------------------------------------------------------------
// Controls

function updateQuadsControl() {
  const available = QUAD_SCHEMES.has(state.scheme);
  $('quads').disabled = !available;
  $('quads-label').classList.toggle('disabled', !available);
  $('quads-label').title = available
    ? 'Join pairs of triangles into quads first (Blender\'s "Tris to Quads"), then subdivide'
    : `${SCHEME_LABELS[state.scheme] ?? state.scheme} takes triangles only`;
}

function attachControls() {
  $('scheme').addEventListener('change', (event) => {
    state.scheme = event.target.value;
    updateQuadsControl();
    subdivideModel();
  });
  $('quads').addEventListener('change', (event) => {
    state.quads = event.target.checked;
    subdivideModel();
  });
  $('level').addEventListener('input', (event) => {
    state.level = Number(event.target.value);
    $('level-value').textContent = String(state.level);
    subdivideModel();
  });
  $('crease').addEventListener('change', (event) => {
    state.crease = event.target.checked;
    $('crease-angle').disabled = !state.crease;
    subdivideModel();
  });
  $('crease-angle').addEventListener('input', (event) => {
    state.creaseDegrees = Number(event.target.value);
    $('crease-value').textContent = `${state.creaseDegrees}°`;
  });
  // The slider subdivides when let go, not at every step of a drag.
  $('crease-angle').addEventListener('change', () => subdivideModel());
  $('cage').addEventListener('change', (event) => {
    state.cage = event.target.checked;
    updateCage();
  });
  $('animate').addEventListener('change', (event) => {
    state.animate = event.target.checked;
    requestRender();
  });
  $('frame').addEventListener('click', frameModel);
  canvas.addEventListener('dblclick', frameModel);
  canvas.addEventListener('keydown', (event) => {
    if (event.key === 'f' || event.key === 'F') frameModel();
  });
  $('open').addEventListener('click', () => $('file').click());
  $('file').addEventListener('change', (event) => {
    openFiles(event.target.files);
    event.target.value = ''; // the same files again are a new open
  });
  $('default-model').addEventListener('click', () => showModel(builtInModel(), 'Built-in: torus knot and box'));

  attachDropZone($('drop-zone'), openFiles);
}

function main() {
  const select = $('scheme');
  select.replaceChildren(...schemeNames().map((name) => new Option(SCHEME_LABELS[name] ?? name, name)));
  select.value = state.scheme;
  $('level').value = String(state.level);
  $('quads').checked = state.quads;
  $('cage').checked = state.cage;
  updateQuadsControl();
  $('version').textContent = `subsurf ${version()} · subsurf/three · three.js r${THREE.REVISION}`;
  attachControls();
  // For tests and the console: showModel({ scene, animations }, name) shows any three.js scene.
  window.subsurfGltf = { THREE, renderer, camera, controls, left, right, get model() { return model; }, showModel, frameModel, requestRender };
  showModel(builtInModel(), 'Built-in: torus knot and box');
}

try {
  main();
} catch (error) {
  console.error(error);
  showMessage(`The page could not start: ${error.message ?? error}`, 'error');
  root.dataset.fatal = String(error.message ?? error);
}
