// Every ```js example of README.md and of the npm page (js/README.md), run as a user pastes it:
//   node tests/js/readme.mjs          (after scripts/build-pkg.sh)
// Each example runs as a module of its own in a fresh project that has the built package (pkg/)
// and three installed, with the few values it leaves to the reader (a mesh, colours, a file, a
// render pass) defined before it and what its comments and the text around it claim checked
// after it. Examples for the browser (WebGPU, a worker script of one's own) run in headless
// Chromium, on SwiftShader for WebGPU. An example that no case below names fails the test, as
// does a case that names no example, so the documents and this file cannot drift apart.
import { spawnSync } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

import { checks, collectErrors, launchChromium, pkg, root, serveStatic } from '../e2e/harness.mjs';

/** The ```js blocks of a markdown text, indentation (a block inside a list item) removed. */
function examples(file) {
  const text = readFileSync(join(root, file), 'utf8');
  const found = [];
  for (const match of text.matchAll(/^( *)```js\n([\s\S]*?)^\1```$/gm)) {
    const indent = match[1].length;
    const code = match[2].split('\n').map((line) => line.slice(Math.min(indent, line.search(/\S|$/)))).join('\n');
    found.push({ file, line: text.slice(0, match.index).split('\n').length, code });
  }
  return found;
}

// What the examples use and do not define. `shape('cube')` is the built-in cube with a UV
// layout (a cross); the checks' expected values come from closed forms (Euler's formula, the
// schemes' face counts) or from a second, plain call of the API the example abbreviates.
const ASSERT = `import __assert from 'node:assert/strict';\n`;
const BROWSER_ASSERT = `const __assert = {
  ok(value, message) { if (!value) throw new Error(message ?? 'assertion failed'); },
  equal(a, b, message) { if (a !== b) throw new Error(\`\${message ?? 'not equal'}: \${a} !== \${b}\`); },
};\n`;
const CUBE = `import { shape as __shape } from 'subsurf';\nconst __cube = __shape('cube');\n`;
/** Largest absolute difference of two arrays of the same length. */
const MAX_DIFF = `function __maxDiff(a, b) {
  __assert.equal(a.length, b.length, 'lengths');
  let worst = 0;
  for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i] - b[i]));
  return worst;
}\n`;
/** Every vertex of a three.js geometry on the surface of the unit box centred at the origin. */
const ON_BOX = `function __onBox(geometry) {
  const p = geometry.getAttribute('position');
  const corners = new Set();
  for (let i = 0; i < p.count; i++) {
    const xyz = [p.getX(i), p.getY(i), p.getZ(i)];
    const a = xyz.map(Math.abs);
    __assert.ok(Math.max(...a) > 0.5 - 1e-6 && Math.max(...a) < 0.5 + 1e-6, \`vertex \${i} off the box: \${a}\`);
    if (a.every((x) => Math.abs(x - 0.5) < 1e-6)) corners.add(xyz.map(Math.sign).join());
  }
  // Split at the sharp edges, a corner has a vertex per side: count the places.
  __assert.equal(corners.size, 8, 'the box keeps its 8 corners');
}\n`;
const TORUS_KNOT = `import * as __THREE from 'three';\n`;
/** What the WebGPU examples leave to the reader: an evaluator's BaseMesh, a frame's control
 * points and a render pass (that records the buffers it is given). */
const GPU = `${BROWSER_ASSERT}${CUBE}${MAX_DIFF}import { BaseMesh } from 'subsurf';
const mesh = __cube;
const base = new BaseMesh(mesh);
const skinnedPositions = mesh.positions.map((p, i) => p * (1 + 0.2 * (i % 3)));
const __bound = [];
const pass = { setVertexBuffer: (slot, buffer) => __bound.push([slot, buffer]) };\n`;
/** The WebGPU examples' read-back against the CPU evaluator, and the two vertex buffers bound. */
const GPU_CHECKS = `const cpu = base.evaluator({ levels: 2, limit: true, normals: true }).evaluate(skinnedPositions);
__assert.ok(__maxDiff(positions, cpu.positions) < 1e-5, 'GPU positions equal the CPU evaluator');
__assert.ok(__maxDiff(normals, cpu.normals) < 1e-5, 'GPU normals equal the CPU evaluator');
__assert.equal(__bound.length, 2);
__assert.ok(__bound.every(([, buffer]) => buffer instanceof GPUBuffer && (buffer.usage & GPUBufferUsage.VERTEX)));\n`;

const CASES = [
  {
    name: 'README: subdivide a cube',
    match: "const smooth = subdivide(cube, { scheme: 'catmull-clark', levels: 3 });",
    before: ASSERT,
    // Catmull-Clark on a closed quad mesh of genus 0: F' = 4F per level, and V = F + 2 (Euler).
    after: `__assert.equal(smooth.faceSizes.length, 6 * 4 ** 3);
__assert.ok(smooth.faceSizes.every((n) => n === 4));
__assert.equal(smooth.positions.length, 3 * (6 * 4 ** 3 + 2));
__assert.equal(smooth.positions.length / 3, 386, 'the comment says 386 vertices');
__assert.equal(smooth.indices.length, 4 * 384, 'the comment says 384 quads');
__assert.equal(smooth.triangles.length, 3 * 2 * 384);`,
  },
  {
    name: 'README: a vertex colour channel',
    match: 'const colored = { ...cube, attributes: { color:',
    // An affine function of the positions comes out as the same function of the refined ones.
    before: `${ASSERT}${CUBE}import { subdivide } from 'subsurf';
const cube = __cube;
const colors = cube.positions.map((p, i) => 0.25 * p + 0.5 + 0.1 * (i % 3));`,
    after: `const c = out.attributes.color.array;
__assert.equal(c.length, out.positions.length);
out.positions.forEach((p, i) => __assert.ok(Math.abs(c[i] - (0.25 * p + 0.5 + 0.1 * (i % 3))) < 1e-6, \`colour \${i}\`));`,
  },
  {
    name: 'README: UVs with seams, toDrawable',
    match: 'const uvMesh = { ...cube, attributes: { uv:',
    before: `${ASSERT}${CUBE}import { subdivide, toDrawable } from 'subsurf';
const cube = __cube;
const { array: uvs, indices: uvIndices } = cube.attributes.uv;`,
    after: `__assert.equal(out.attributes.uv.indices.length, out.indices.length, 'uv indices parallel to indices');
const n = draw.positions.length / 3;
__assert.ok(n > out.positions.length / 3, 'the cross layout has seams, so vertices split');
__assert.equal(draw.attributes.uv.array.length, 2 * n);
__assert.equal(draw.attributes.uv.indices, undefined);
__assert.equal(draw.origins.length, n);
__assert.equal(draw.triangles.length, out.triangles.length);
__assert.ok(draw.triangles.every((v) => v < n));
draw.origins.forEach((o, k) => {
  for (let j = 0; j < 3; j++) __assert.equal(draw.positions[3 * k + j], out.positions[3 * o + j]);
});`,
  },
  {
    name: 'README: into and BaseMesh',
    match: 'const base = new BaseMesh(mesh);         // throws',
    before: `${ASSERT}${CUBE}import { subdivide, BaseMesh } from 'subsurf';
const mesh = __cube;
const skinned = mesh.positions.map((p, i) => p * (1 + 0.2 * (i % 3)));`,
    after: `const expected = subdivide({ ...mesh, positions: skinned }, { levels: 2 });
__assert.deepEqual(out.positions, expected.positions);
__assert.deepEqual(out.indices, expected.indices);
__assert.throws(() => base.subdivide({ levels: 1 }), /after free\\(\\)/);`,
  },
  {
    name: 'README: readObj with tags',
    match: 'const mesh = readObj(await file.text());',
    before: `${ASSERT}import { readObj, subdivide } from 'subsurf';
const __obj = [
  'v -1 -1 -1', 'v -1 -1 1', 'v -1 1 -1', 'v -1 1 1', 'v 1 -1 -1', 'v 1 -1 1', 'v 1 1 -1', 'v 1 1 1',
  'f 1 5 6 2', 'f 5 7 8 6', 'f 7 3 4 8', 'f 3 1 2 4', 'f 2 6 8 4', 'f 1 3 7 5',
  't crease 2/1/0 0 1 10', 't corner 1/1/0 7 4.5', 't interpolateboundary 1/0/0 2',
].join('\\n');
const file = { text: async () => __obj };`,
    after: `__assert.deepEqual(mesh.tags.creases.edges, new Uint32Array([0, 1]));
__assert.deepEqual(mesh.tags.creases.sharpness, new Float32Array([10]));
__assert.deepEqual(mesh.tags.corners.vertices, new Uint32Array([7]));
__assert.deepEqual(mesh.tags.corners.sharpness, new Float32Array([4.5]));
__assert.equal(mesh.tags.holes.length, 0);
__assert.equal(mesh.tags.boundary, 'edge-only');
__assert.equal(out.faceSizes.length, 6 * 16);
// A vertex of sharpness 4.5 is a corner for four levels (DeRose, Kass and Truong 1998: it
// loses one per level): its point stays where it is, (1, 1, 1).
let corner = 0;
for (let i = 0; i < out.positions.length; i += 3) {
  if (out.positions[i] === 1 && out.positions[i + 1] === 1 && out.positions[i + 2] === 1) corner++;
}
__assert.equal(corner, 1, 'the sharp corner stays');
__assert.ok(!subdivide(mesh, { levels: 2 }).positions.some((x) => x === 1), 'without its tags the cube shrinks');
// "throws 'OBJ line 14: ...'": the message names the line.
const bad = __obj.split('\\n').slice(0, 13).concat(['v 1 2']).join('\\n');
__assert.throws(() => readObj(bad), /^Error: OBJ line 14: /);`,
  },
  {
    name: 'README: limit positions and normals',
    match: 'const out = subdivide(mesh, { levels: 2, limit: true, normals: true });',
    before: `${ASSERT}${CUBE}import { subdivide } from 'subsurf';
const mesh = __cube;`,
    // The limit surface of a cube centred at the origin is convex: outward normals point away.
    after: `const { positions: p, normals: n } = out;
__assert.equal(n.length, p.length);
for (let i = 0; i < p.length; i += 3) {
  __assert.ok(Math.abs(Math.hypot(n[i], n[i + 1], n[i + 2]) - 1) < 1e-5, \`unit normal \${i / 3}\`);
  __assert.ok(n[i] * p[i] + n[i + 1] * p[i + 1] + n[i + 2] * p[i + 2] > 0, \`outward normal \${i / 3}\`);
}`,
  },
  {
    name: 'README: BaseMesh.evaluator',
    match: 'const evaluator = base.evaluator({ levels: 2, limit: true, normals: true });  // any',
    before: `${ASSERT}${CUBE}${MAX_DIFF}import { subdivide, BaseMesh } from 'subsurf';
const mesh = __cube;
const skinnedPositions = mesh.positions.map((p, i) => p * (1 + 0.2 * (i % 3)));
const vertexColours = mesh.positions.map((p) => 0.5 * p + 0.5);`,
    // "evaluate equals subdivide on the same positions and options (to f32 rounding)"; the
    // views hold the same frame (checked first: a later call may grow the memory).
    after: `__assert.deepEqual(inPlace.positions, frame.positions);
__assert.deepEqual(inPlace.normals, frame.normals);
const __twice = evaluator.evaluateView(skinnedPositions.map((p) => 2 * p));
__assert.deepEqual(inPlace.positions, __twice.positions, 'the next frame writes over the views');
__assert.ok(inPlace.positions.every((p, i) => p === 2 * frame.positions[i]), 'twice the cage, twice the frame');
const expected = subdivide({ ...mesh, positions: skinnedPositions }, { levels: 2, limit: true, normals: true });
__assert.ok(__maxDiff(frame.positions, expected.positions) < 1e-5);
__assert.ok(__maxDiff(frame.normals, expected.normals) < 1e-5);
__assert.deepEqual(indices, expected.indices);
__assert.deepEqual(triangles, expected.triangles);
__assert.equal(attributes.uv.indices.length, indices.length);
__assert.equal(colours.length, expected.positions.length);
__assert.equal(offsets.length, expected.positions.length / 3 + 1);
__assert.equal(controls.length, weights.length);
__assert.ok(tangentWeights, 'a table with normals has tangent weights');`,
  },
  {
    name: 'README: subsurf/webgpu',
    browser: 'webgpu',
    match: "const gpu = createGpuEvaluator(device, base.evaluator({ levels: 2, limit: true, normals: true }));\n// or",
    // controlBuffer and encoder are the reader's, made on the device the example asks for:
    // globals, resolved when the example reaches them, on the device it was given.
    before: `${GPU}const __devices = [];
const __requestDevice = GPUAdapter.prototype.requestDevice;
GPUAdapter.prototype.requestDevice = async function (...args) {
  const device = await __requestDevice.apply(this, args);
  __devices.push(device);
  return device;
};
Object.defineProperty(globalThis, 'controlBuffer', { get() {
  const buffer = __devices[0].createBuffer({ size: skinnedPositions.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  __devices[0].queue.writeBuffer(buffer, 0, skinnedPositions);
  return buffer;
} });
Object.defineProperty(globalThis, 'encoder', { get() { return (globalThis.__encoder ??= __devices[0].createCommandEncoder()); } });`,
    after: GPU_CHECKS,
  },
  {
    name: 'README: subsurf/three',
    match: 'mesh.geometry = subdivideGeometry(mesh.geometry, { levels: 2 });',
    before: `${ASSERT}${TORUS_KNOT}${ON_BOX}
const mesh = new __THREE.Mesh(new __THREE.TorusKnotGeometry(1, 0.3, 64, 8));
const gltfMesh = new __THREE.Mesh(new __THREE.BoxGeometry());
const __triangles = mesh.geometry.index.count / 3;`,
    // Catmull-Clark (the default) makes 3 quads of a triangle, then 4 of a quad: 12 quads, 24
    // triangles per input triangle at level 2. The box's normals split at every edge, so with
    // sharpNormalSplits every edge is an infinite crease and the box stays a box (6 quads after
    // quads: true, 96 at level 2).
    after: `__assert.equal(mesh.geometry.index.count / 3, 24 * __triangles);
__assert.ok(mesh.geometry.getAttribute('uv') && mesh.geometry.getAttribute('normal'));
__assert.equal(hard.index.count / 3, 2 * 96);
__onBox(hard);`,
  },
  {
    name: 'README: subdivideGeometryAsync, latest wins',
    match: 'async function refine(level) {',
    before: `${ASSERT}${TORUS_KNOT}
const source = new __THREE.TorusKnotGeometry(1, 0.3, 64, 8);
const mesh = new __THREE.Mesh(source);
const status = { textContent: '' };`,
    after: `await refine(2);
__assert.equal(mesh.geometry.index.count, 24 * source.index.count);
__assert.equal(status.textContent, 'level 2/2');
// A second call aborts the first, which never lands.
await Promise.all([refine(2), refine(1)]);
__assert.equal(mesh.geometry.index.count, 6 * source.index.count);
worker.terminate();`,
  },
  {
    name: 'README: weldTriangles',
    match: 'const w = weldTriangles(positions /* Float32Array */',
    before: `${ASSERT}${TORUS_KNOT}import { subdivide } from 'subsurf';
const __box = new __THREE.BoxGeometry();
const positions = __box.getAttribute('position').array;
const index = new Uint32Array(__box.index.array);`,
    // BoxGeometry has 4 vertices per side (24); a box has 8 corners, 12 triangles, 18 edges.
    after: `__assert.equal(w.weldOf.length, 24);
__assert.equal(Math.max(...w.weldOf), 7);
__assert.equal(w.positions.length, 3 * 8);
__assert.equal(w.kept.length, 12);
__assert.equal(w.corners.length, 36);
const loop = subdivide({ positions: w.positions, indices: w.corners }, { scheme: 'loop', levels: 1 });
__assert.equal(loop.positions.length / 3, 8 + 18, 'closed: V + E');`,
  },
  {
    name: 'README: subsurf/worker',
    match: "const smooth = await worker.subdivide(mesh, { levels: 4 }, {",
    before: `${ASSERT}${CUBE}import { subdivide } from 'subsurf';
const mesh = __cube;
const status = { textContent: '' };`,
    // "with the same result, byte for byte"
    after: `const expected = subdivide(mesh, { levels: 4 });
__assert.deepEqual(smooth.positions, expected.positions);
__assert.deepEqual(smooth.indices, expected.indices);
__assert.deepEqual(smooth.attributes.uv.array, expected.attributes.uv.array);
__assert.equal(status.textContent, 'level 4/4');`,
  },
  {
    name: 'README: a worker script of your own',
    browser: 'worker',
    match: '// my-worker.js\n',
    before: `${BROWSER_ASSERT}${CUBE}import { createWorker } from 'subsurf/worker';
import { subdivide as __subdivide, toDrawable as __toDrawable } from 'subsurf';
const mesh = __cube;
const __progress = [];
const onProgress = ({ level }) => __progress.push(level);`,
    after: `const expected = __toDrawable(__subdivide(mesh, { levels: 3 }));
for (const key of ['positions', 'triangles', 'origins']) {
  __assert.equal(drawable[key].join(), expected[key].join(), key);
}
__assert.equal(drawable.attributes.uv.array.join(), expected.attributes.uv.array.join(), 'uv');
__assert.equal(__progress.join(), '1,2,3', 'progress per level');
worker.terminate();`,
  },
  {
    name: 'npm page: subdivide',
    match: "const out = subdivide(cube, { scheme: 'catmull-clark', levels: 2, boundary: 'edge-and-corner', maxFaces: 1e6 });",
    before: ASSERT,
    after: `__assert.equal(out.faceSizes.length, 6 * 16);
__assert.equal(out.positions.length / 3, 6 * 16 + 2, 'Euler: V = F + 2');
__assert.equal(out.triangles.length, 3 * 2 * 96);`,
  },
  {
    name: 'npm page: subsurf/webgpu',
    browser: 'webgpu',
    match: "const device = await requestGpuDevice();          // throws, saying why",
    before: GPU,
    after: `const { positions, normals } = await gpu.readBack();\n${GPU_CHECKS}gpu.destroy();`,
  },
  {
    name: 'npm page: subsurf/three',
    match: 'mesh.geometry = subdivideGeometry(mesh.geometry, { levels: 2, quads: true, creaseAngle: Math.PI / 6 });',
    // Every edge of a box bends by 90°, more than the crease angle: infinitely sharp creases
    // keep a box a box (the rules of DeRose, Kass and Truong 1998 leave crease edges straight).
    before: `${ASSERT}${TORUS_KNOT}${ON_BOX}
const mesh = new __THREE.Mesh(new __THREE.BoxGeometry());`,
    after: `__assert.equal(mesh.geometry.index.count / 3, 2 * 96);
__onBox(mesh.geometry);`,
  },
  {
    name: 'npm page: subsurf/worker',
    match: 'const out = await worker.subdivide(mesh, { levels: 4 }, {',
    before: `${ASSERT}${CUBE}import { subdivide } from 'subsurf';
const mesh = __cube;
const controller = new AbortController();
const __shown = [];
const show = (text) => __shown.push(text);`,
    after: `const expected = subdivide(mesh, { levels: 4 });
__assert.deepEqual(out.positions, expected.positions);
__assert.deepEqual(out.indices, expected.indices);
__assert.equal(__shown.at(-1), 'level 4/4');`,
  },
];

const { check, finish } = checks('readme');
const found = [...examples('README.md'), ...examples('js/README.md')];
const runs = [];
for (const example of found) {
  const cases = CASES.filter((c) => example.code.includes(c.match));
  const where = `${example.file}:${example.line}`;
  if (check(`${where} has one case in tests/js/readme.mjs`, cases.length === 1,
    cases.length ? cases.map((c) => c.name).join(', ') : 'none: add one for this example')) {
    runs.push({ ...cases[0], where, code: example.code });
  }
}
for (const c of CASES) {
  check(`case '${c.name}' names an example`, found.some((e) => e.code.includes(c.match)), 'remove or update the case');
}

// A project as a user has it: the package installed from pkg/ (as npm installs its files) and three.
const project = mkdtempSync(join(tmpdir(), 'subsurf-readme-'));
try {
  mkdirSync(join(project, 'node_modules'));
  cpSync(pkg, join(project, 'node_modules', 'subsurf'), { recursive: true });
  symlinkSync(join(root, 'node_modules', 'three'), join(project, 'node_modules', 'three'), 'dir');
  writeFileSync(join(project, 'package.json'), JSON.stringify({ type: 'module', private: true }));

  const module = (run) => `${run.before}\n// ---- the example (${run.where})\n${run.code}\n// ---- its checks\n${run.after}\n`;
  for (const run of runs.filter((r) => !r.browser)) {
    const file = join(project, `example-${run.where.replace(/[^a-z0-9]+/gi, '-')}.mjs`);
    writeFileSync(file, module(run));
    const result = spawnSync(process.execPath, [file], { cwd: project, encoding: 'utf8', timeout: 120_000 });
    check(`${run.name} (${run.where}) runs in Node`, result.status === 0,
      result.status === 0 ? '' : `${file}\n${result.stderr || result.stdout || result.error}`);
  }

  const browserRuns = runs.filter((r) => r.browser);
  if (browserRuns.length) {
    const importMap = {
      imports: {
        subsurf: '/node_modules/subsurf/auto.js',
        'subsurf/init': '/node_modules/subsurf/init.js',
        'subsurf/webgpu': '/node_modules/subsurf/webgpu.js',
        'subsurf/worker': '/node_modules/subsurf/worker.js',
        'subsurf/worker-thread': '/node_modules/subsurf/worker-thread.js',
      },
    };
    const pages = { '/': `<!doctype html><script type="importmap">${JSON.stringify(importMap)}</script>
<script type="module">
try { await import('/example.mjs'); window.__done = 'ok'; } catch (error) { window.__done = String(error.stack ?? error); }
</script>` };
    const routes = { '/node_modules/subsurf/': join(project, 'node_modules', 'subsurf') };
    const server = await serveStatic({ routes, pages });
    const browser = await launchChromium({ args: ['--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan'] });
    try {
      for (const run of browserRuns) {
        let code = run.code;
        if (run.browser === 'worker') {
          // Two files in one block: the worker script, then the page. A module worker does not
          // see the page's import map, so its bare imports are resolved as a bundler would.
          const [worker, page] = code.split('// the page\n');
          pages['/my-worker.js'] = worker.replace(/from '(subsurf\/[\w-]+)'/g, (_, name) => `from '${importMap.imports[name]}'`);
          code = page;
        }
        pages['/example.mjs'] = module({ ...run, code });
        const page = await browser.newPage();
        const errors = collectErrors(page);
        await page.goto(`${server.origin}/`);
        const done = await page.waitForFunction(() => window.__done, null, { timeout: 120_000 }).then((h) => h.jsonValue(), (e) => String(e));
        check(`${run.name} (${run.where}) runs in Chromium`, done === 'ok' && errors.length === 0,
          done === 'ok' ? errors.join('; ') : done);
        await page.close();
      }
    } finally {
      await browser.close();
      server.close();
    }
  }
} finally {
  rmSync(project, { recursive: true, force: true });
}
finish();
