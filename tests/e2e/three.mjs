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
//   - MeshNormalMaterial: the face's centre faces the camera, (128, 128, 255) (limit normals).
// Exits non-zero on failure.
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { dirname, extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkg = process.env.PKG_DIR ?? join(root, 'pkg');
const threeBuild = join(root, 'node_modules', 'three', 'build');
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
};
const PAGE = `<!doctype html><meta charset="utf-8"><title>subsurf three test</title>
<script type="importmap">{ "imports": { "three": "/three/three.module.js" } }</script>
<body style="margin:0"></body>`;

/** Answers GET path: / is the page, /pkg/... the built package, /three/... three's build. */
function respond(path) {
  if (path === '/') return { status: 200, type: TYPES['.html'], body: PAGE };
  if (path === '/favicon.ico') return { status: 204, type: 'image/x-icon', body: '' };
  for (const [prefix, dir] of [['/pkg/', pkg], ['/three/', threeBuild]]) {
    if (!path.startsWith(prefix)) continue;
    const file = normalize(join(dir, path.slice(prefix.length)));
    if (!file.startsWith(dir + sep) || !existsSync(file) || statSync(file).isDirectory()) break;
    return { status: 200, type: TYPES[extname(file)] ?? 'application/octet-stream', body: readFileSync(file) };
  }
  return { status: 404, type: 'text/plain', body: 'not found' };
}

function serve() {
  const server = createServer((request, response) => {
    const { status, type, body } = respond(decodeURIComponent(new URL(request.url, 'http://localhost').pathname));
    response.writeHead(status, { 'content-type': type, 'cache-control': 'no-store' });
    response.end(body);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

let failures = 0;
function check(name, ok, detail) {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail ? ` (${detail})` : ''}`);
  if (!ok) failures++;
}

const server = await serve();
const origin = `http://127.0.0.1:${server.address().port}`;
const browser = await chromium.launch({
  executablePath: CHROMIUM,
  headless: true,
  args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
    '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
});
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  page.on('console', (message) => { if (message.type() === 'error') errors.push(message.text()); });
  await page.goto(`${origin}/`);
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
  check('no page errors', errors.length === 0, errors.join('; '));
} finally {
  await browser.close();
  server.close();
}
if (failures) {
  console.error(`three e2e: ${failures} check(s) FAILED`);
  process.exit(1);
}
console.log('three e2e: ok');
