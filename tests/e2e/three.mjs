// End-to-end test of subsurf/three in headless Chromium (WebGL on SwiftShader, no GPU needed):
//   node tests/e2e/three.mjs                    (after scripts/build-pkg.sh)
//   PKG_DIR=/elsewhere/pkg node tests/e2e/three.mjs
//
// Serves the built package and three's ES modules (node_modules/three/build, mapped to the bare
// name 'three' by an import map, as a plain page would) and, in the page, imports the web entry
// (subsurf.js, `await init()`) and subsurf/three's default file (three.js), subdivides three's
// BoxGeometry and draws it with a real THREE.WebGLRenderer, looking at its +z face with an
// orthographic camera, then reads pixels back:
//   - six MeshBasicMaterials, one per group: the face is drawn in group 4's colour (groups kept);
//     with creaseAngle the cube stays a cube (the face's corners are covered), without it the
//     cube is rounded (the corners show the background);
//   - a two-texel texture (red | green, nearest) through the face's UVs: the left half red, the
//     right half green (UVs refined per face, seams kept);
//   - MeshNormalMaterial: the face's centre faces the camera, (128, 128, 255) (limit normals);
// then subdivideGeometryAsync in a module Web Worker (/pkg/worker.js): byte for byte the
// geometry subdivideGeometry makes (groups, creases, quads, Loop, morphs), the input whole,
// progress per level, abort, the sync call's error message.
// Exits non-zero on failure.
import { join } from 'node:path';
import { SWIFTSHADER_WEBGL, checks, collectErrors, launchChromium, pkg, root, serveStatic } from './harness.mjs';

const PAGE = `<!doctype html><meta charset="utf-8"><title>subsurf three test</title>
<script type="importmap">{ "imports": { "three": "/three/three.module.js" } }</script>
<body style="margin:0"></body>`;

const { check, finish } = checks('three e2e');
// / is the page, /pkg/... the built package, /three/... three's build.
const server = await serveStatic({ pages: { '/': PAGE }, routes: { '/pkg/': pkg, '/three/': join(root, 'node_modules', 'three', 'build') } });
const browser = await launchChromium({ args: SWIFTSHADER_WEBGL });
try {
  const page = await browser.newPage();
  const errors = collectErrors(page);
  await page.goto(`${server.origin}/`);
  const result = await page.evaluate(async () => {
    const THREE = await import('three');
    const { default: init } = await import('/pkg/subsurf.js');
    const { subdivideGeometry } = await import('/pkg/three.js');
    await init();
    const SIZE = 200, HALF = 1.25; // the view: x, y in [-1.25, 1.25]; the box's face is [-1, 1]^2
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = SIZE;
    document.body.append(canvas);
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.setSize(SIZE, SIZE, false);
    renderer.outputColorSpace = THREE.LinearSRGBColorSpace;
    renderer.setClearColor(0x000000, 1);
    const camera = new THREE.OrthographicCamera(-HALF, HALF, HALF, -HALF, 0.1, 10);
    camera.position.set(0, 0, 5);
    camera.lookAt(0, 0, 0);
    /** Draws the geometry with the material(s) and returns the RGB at each world (x, y). */
    const draw = (geometry, material, points) => {
      const scene = new THREE.Scene();
      scene.add(new THREE.Mesh(geometry, material));
      renderer.render(scene, camera);
      const gl = renderer.getContext();
      const pixel = new Uint8Array(4);
      return points.map(([x, y]) => {
        const px = Math.floor(((x + HALF) / (2 * HALF)) * SIZE), py = Math.floor(((y + HALF) / (2 * HALF)) * SIZE);
        gl.readPixels(px, py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
        return [pixel[0], pixel[1], pixel[2]];
      });
    };
    const colors = [0xff0000, 0x00ff00, 0x0000ff, 0xffff00, 0xff00ff, 0x00ffff];
    const materials = colors.map((color) => new THREE.MeshBasicMaterial({ color }));
    const box = new THREE.BoxGeometry(2, 2, 2);
    const points = [[0, 0], [0.9, 0.9], [-0.9, -0.9], [0.97, 0]];
    const sharp = subdivideGeometry(box, { levels: 3, creaseAngle: Math.PI / 4 });
    const round = subdivideGeometry(box, { levels: 3 });
    const texture = new THREE.DataTexture(new Uint8Array([255, 0, 0, 255, 0, 255, 0, 255]), 2, 1);
    texture.magFilter = texture.minFilter = THREE.NearestFilter;
    texture.needsUpdate = true;
    return {
      renderer: renderer.getContext() instanceof WebGL2RenderingContext ? 'WebGL2' : 'WebGL1',
      groups: sharp.groups.length,
      sharp: draw(sharp, materials, points),
      round: draw(round, materials, points),
      textured: draw(sharp, new THREE.MeshBasicMaterial({ map: texture }), [[-0.5, 0], [0.5, 0], [-0.95, 0.95], [0.95, -0.95]]),
      normals: draw(round, new THREE.MeshNormalMaterial(), [[0, 0]]),
      input: box.getAttribute('position').count,
    };
  });
  const near = (a, b, tol = 2) => a.every((x, i) => Math.abs(x - b[i]) <= tol);
  const MAGENTA = [255, 0, 255], BLACK = [0, 0, 0], RED = [255, 0, 0], GREEN = [0, 255, 0];
  console.log(`three e2e: ${result.renderer}, BoxGeometry (${result.input} vertices), level 3`);
  check('groups kept: 6', result.groups === 6, `${result.groups}`);
  check('creaseAngle: the +z face is group 4\'s colour to its corners', result.sharp.every((c) => near(c, MAGENTA)), JSON.stringify(result.sharp));
  check('no creases: rounded, centre in group 4\'s colour, corners and edge background',
    near(result.round[0], MAGENTA) && result.round.slice(1).every((c) => near(c, BLACK)), JSON.stringify(result.round));
  check('texture through the UVs: left red, right green', near(result.textured[0], RED) && near(result.textured[1], GREEN) &&
    near(result.textured[2], RED) && near(result.textured[3], GREEN), JSON.stringify(result.textured));
  check('MeshNormalMaterial: the centre faces the camera', near(result.normals[0], [128, 128, 255], 3), JSON.stringify(result.normals));

  // subdivideGeometryAsync: subdivideTriangles in a module Web Worker (which has no import map:
  // it would fail to load if the worker script reached 'three').
  const inWorker = await page.evaluate(async () => {
    const THREE = await import('three');
    const { subdivideGeometry, subdivideGeometryAsync } = await import('/pkg/three.js');
    const { createWorker } = await import('/pkg/worker.js');
    const worker = createWorker();
    const bytes = (a) => new Uint8Array(a.buffer, a.byteOffset, a.byteLength);
    const sameArray = (a, b) => a.constructor === b.constructor && a.length > 0 && a.byteLength === b.byteLength &&
      bytes(a).every((v, i) => v === bytes(b)[i]);
    /** The differences between two geometries (attributes, index, groups, morphs, userData), by name. */
    const differences = (a, b) => {
      const out = [];
      const names = Object.keys(a.attributes);
      if (names.sort().join() !== Object.keys(b.attributes).sort().join()) out.push('attribute names');
      for (const name of names) if (!sameArray(a.attributes[name].array, b.attributes[name]?.array ?? new Float32Array())) out.push(name);
      if (!sameArray(a.index.array, b.index.array)) out.push('index');
      if (JSON.stringify(a.groups) !== JSON.stringify(b.groups)) out.push('groups');
      for (const [name, list] of Object.entries(a.morphAttributes)) {
        list.forEach((t, i) => { if (!sameArray(t.array, b.morphAttributes[name]?.[i]?.array ?? new Float32Array())) out.push(`morph ${name}[${i}]`); });
      }
      if (JSON.stringify(a.userData) !== JSON.stringify(b.userData) || a.name !== b.name) out.push('userData/name');
      return out;
    };
    const box = new THREE.BoxGeometry(2, 2, 2, 2, 2, 2);
    box.userData = { from: 'e2e' };
    const knot = new THREE.TorusKnotGeometry(1, 0.3, 64, 8);
    const morphed = new THREE.TorusKnotGeometry(1, 0.3, 32, 6);
    morphed.morphAttributes.position = [morphed.getAttribute('position').clone()];
    morphed.morphAttributes.normal = [morphed.getAttribute('normal').clone()];
    const cases = [[box, { levels: 2 }], [box, { levels: 2, creaseAngle: 0.5, quads: true }], [knot, { levels: 2, scheme: 'loop' }], [morphed, { levels: 1 }]];
    const diffs = [];
    for (const [geometry, options] of cases) {
      const lengths = Object.values(geometry.attributes).map((a) => a.array.length).join();
      const async = await subdivideGeometryAsync(geometry, options, { worker });
      diffs.push(...differences(async, subdivideGeometry(geometry, options)));
      if (Object.values(geometry.attributes).map((a) => a.array.length).join() !== lengths) diffs.push('input detached');
    }
    const levels = [];
    await subdivideGeometryAsync(knot, { levels: 3 }, { worker, onProgress: (p) => levels.push(`${p.level}/${p.levels}`) });
    const controller = new AbortController();
    const aborted = await subdivideGeometryAsync(new THREE.TorusKnotGeometry(1, 0.3, 256, 32), { levels: 6, maxFaces: 1e9, maxBytes: 8e9 }, {
      worker, signal: controller.signal, onProgress: () => controller.abort(),
    }).then(() => 'resolved', (error) => error.name);
    const after = differences(await subdivideGeometryAsync(box, { levels: 1 }, { worker }), subdivideGeometry(box, { levels: 1 }));
    let noPosition = '';
    await subdivideGeometryAsync(new THREE.BufferGeometry(), {}, { worker }).catch((error) => { noPosition = error.message; });
    worker.terminate();
    return { cases: cases.length, diffs, levels, aborted, after, noPosition };
  });
  check(`subdivideGeometryAsync in a Web Worker = subdivideGeometry byte for byte (${inWorker.cases} geometries), input whole`,
    inWorker.diffs.length === 0, inWorker.diffs.join(', '));
  check('subdivideGeometryAsync: progress 1/3, 2/3, 3/3', inWorker.levels.join() === '1/3,2/3,3/3', inWorker.levels.join());
  check('subdivideGeometryAsync: abort rejects with an AbortError; the next call is right', inWorker.aborted === 'AbortError' && inWorker.after.length === 0,
    `${inWorker.aborted}; ${inWorker.after.join(', ')}`);
  check('subdivideGeometryAsync: no position rejects with subdivideGeometry\'s message', /no 'position' attribute/.test(inWorker.noPosition), inWorker.noPosition);
  check('no page errors', errors.length === 0, errors.join('; '));
} finally {
  await browser.close();
  server.close();
}
finish();
