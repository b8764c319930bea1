// The built package as users install it (run scripts/build-pkg.sh first):
//   node tests/js/consumers.mjs
//   node tests/js/consumers.mjs --keep      (leaves the temporary projects and prints where)
// `npm pack`s pkg/ once, then for each consumer makes a fresh project in a temporary folder,
// `npm install`s the tarball there (and `three`, the repo's pinned version, where subsurf/three is
// used), builds it with no configuration of ours, and checks that it subdivides a cube with no
// init() call: Catmull-Clark level 2 gives 98 vertices and 96 quads, subsurf/three's
// subdivideGeometry of the cube's 12 triangles (quads: true) gives 98 vertices, 192 triangles
// (and subdivideGeometryAsync the same geometry byte for byte, from a worker, telling levels 1
// and 2), and subsurf/worker gives the main thread's result byte for byte, telling levels 1 and 2 (in
// Node through worker_threads; in the bundlers with no configuration: the worker script and the
// .wasm are found through their `new URL(..., import.meta.url)`).
//   node     a Node project with only the tarball: import { subdivide } from 'subsurf'
//   vite     a Vite app (vite build; the repo's pinned vite), served and opened in Chromium; and
//            the same app under Vite's dev server (`vite`, dependency pre-bundling included)
//   webpack  a webpack 5 app (webpack with no config file: src/index.js -> dist/main.js)
//   static   a plain <script type="module"> page with an import map onto node_modules/, served
//            from the project folder as it is
// The bundlers run from the repo's node_modules (pinned devDependencies); they resolve 'subsurf'
// and 'three' from the app's own node_modules, where subsurf comes from the tarball (checked).
// npm runs with --prefer-offline. Prints each part's time; exits non-zero on any failure.
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { createServer } from 'node:http';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const pkgDir = process.env.PKG_DIR ?? join(root, 'pkg');
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
const bin = (name) => join(root, 'node_modules', '.bin', name);
const keep = process.argv.includes('--keep');
const threeVersion = JSON.parse(readFileSync(join(root, 'node_modules', 'three', 'package.json'), 'utf8')).version;
const version = JSON.parse(readFileSync(join(pkgDir, 'package.json'), 'utf8')).version;
const EXPECTED = { version, vertices: 98, faces: 96, geometryVertices: 98, geometryTriangles: 192, initAgain: 24, worker: 'same', workerProgress: '1,2',
  geometryAsync: 'same', geometryAsyncProgress: '1,2' };

const scratch = mkdtempSync(join(tmpdir(), 'subsurf-consumers-'));
process.on('exit', () => {
  if (keep) console.log(`consumers: projects kept in ${scratch}`);
  else rmSync(scratch, { recursive: true, force: true });
});

const times = [];
let failures = 0;
async function part(name, fn) {
  const start = performance.now();
  try {
    await fn();
    console.log(`ok   ${name}`);
  } catch (error) {
    failures++;
    console.error(`FAIL ${name}\n${error.stack ?? error}`);
  }
  times.push([name, (performance.now() - start) / 1000]);
}

function run(cmd, args, cwd) {
  const result = spawnSync(cmd, args, { cwd, encoding: 'utf8', env: { ...process.env, NO_COLOR: '1', npm_config_update_notifier: 'false' } });
  if (result.status !== 0) {
    throw new Error(`${cmd} ${args.join(' ')} (in ${cwd}) exited ${result.status}:\n${result.stdout}${result.stderr}`);
  }
  return result.stdout;
}

// ---- the page's code, the same for the three browser apps (and the Node one, less three).
// Nothing calls init() before the counts are taken; init() afterwards must be harmless.
const CUBE = `const cube = {
  positions: new Float32Array([-1,-1,-1, -1,-1,1, -1,1,-1, -1,1,1, 1,-1,-1, 1,-1,1, 1,1,-1, 1,1,1]),
  indices: new Uint32Array([0,4,5,1, 4,6,7,5, 6,2,3,7, 2,0,1,3, 1,5,7,3, 0,2,6,4]),
  faceSizes: new Uint32Array([4, 4, 4, 4, 4, 4]),
};
const out = subdivide(cube, { levels: 2 });
const result = { version: version(), vertices: out.positions.length / 3, faces: out.faceSizes.length };
`;
// subsurf/worker: the same cube in a worker (Web Worker, or worker_threads in Node), compared
// with the main thread's result byte for byte, with the levels its progress told.
const WORKER = `const worker = createWorker();
const workerLevels = [];
const sameBytes = (a, b) => ['positions', 'indices', 'faceSizes', 'triangles'].every((k) => {
  const [x, y] = [new Uint8Array(a[k].buffer), new Uint8Array(b[k].buffer)];
  return x.length === y.length && x.length > 0 && x.every((v, i) => v === y[i]);
});
const inWorker = worker.subdivide(cube, { levels: 2 }, { onProgress: (p) => workerLevels.push(p.level) }).then((w) => {
  worker.terminate();
  return { worker: sameBytes(w, out) ? 'same' : 'different', workerProgress: workerLevels.join(',') };
}, (error) => ({ worker: String(error) }));
`;
const APP = `import init, { subdivide, version } from 'subsurf';
import { subdivideGeometry, subdivideGeometryAsync } from 'subsurf/three';
import { createWorker } from 'subsurf/worker';
import { BufferAttribute, BufferGeometry } from 'three';

${CUBE}${WORKER}
// The cube as three.js has it: 12 triangles, indexed; quads: true joins them back into quads.
const triangles = [];
for (let f = 0; f < 6; f++) {
  const [a, b, c, d] = cube.indices.slice(4 * f, 4 * f + 4);
  triangles.push(a, b, c, a, c, d);
}
const geometry = new BufferGeometry();
geometry.setAttribute('position', new BufferAttribute(cube.positions, 3));
geometry.setIndex(triangles);
const smooth = subdivideGeometry(geometry, { levels: 2, quads: true });
result.geometryVertices = smooth.getAttribute('position').count;
result.geometryTriangles = smooth.index.count / 3;

// The same in a worker (subdivideTriangles in the worker bundle, three only here): byte for byte.
const geometryWorker = createWorker();
const geometryLevels = [];
const sameArray = (a, b) => a.constructor === b.constructor && a.length === b.length && a.length > 0 && a.every((v, i) => Object.is(v, b[i]));
const inWorkerGeometry = subdivideGeometryAsync(geometry, { levels: 2, quads: true }, {
  worker: geometryWorker,
  onProgress: (p) => geometryLevels.push(p.level),
}).then((g) => {
  geometryWorker.terminate();
  const names = Object.keys(smooth.attributes);
  const same = names.join() === Object.keys(g.attributes).join() &&
    names.every((name) => sameArray(g.attributes[name].array, smooth.attributes[name].array)) && sameArray(g.index.array, smooth.index.array);
  return { geometryAsync: same ? 'same' : 'different', geometryAsyncProgress: geometryLevels.join(',') };
}, (error) => ({ geometryAsync: String(error) }));

Promise.all([init(), inWorker, inWorkerGeometry]).then(([, fromWorker, fromGeometryWorker]) => {
  result.initAgain = subdivide(cube, { levels: 1 }).faceSizes.length;
  Object.assign(result, fromWorker, fromGeometryWorker);
  document.getElementById('out').textContent = JSON.stringify(result);
  window.__subsurf = result;
}, (error) => { window.__subsurf = { error: String(error) }; });
`;
const REPORT_ERRORS = `<link rel="icon" href="data:,"><script>addEventListener('error', (e) => { window.__subsurf = { error: String(e.message) }; });</script>`;

function project(name, dependencies) {
  const dir = join(scratch, name);
  mkdirSync(dir, { recursive: true });
  writeFileSync(join(dir, 'package.json'), JSON.stringify({ name: `consumer-${name}`, private: true, type: 'module' }, null, 2));
  run('npm', ['install', '--prefer-offline', '--no-audit', '--no-fund', '--loglevel=error', ...dependencies], dir);
  // subsurf in the project's own node_modules, from the tarball, at pkg/'s version.
  const lock = JSON.parse(readFileSync(join(dir, 'package-lock.json'), 'utf8'));
  const entry = lock.packages['node_modules/subsurf'];
  assert.ok(entry && entry.resolved && entry.resolved.startsWith('file:') && entry.resolved.endsWith('.tgz'),
    `subsurf installed from the tarball: ${JSON.stringify(entry)}`);
  assert.equal(JSON.parse(readFileSync(join(dir, 'node_modules', 'subsurf', 'package.json'), 'utf8')).version, version);
  return dir;
}

const TYPES = { '.html': 'text/html; charset=utf-8', '.js': 'text/javascript; charset=utf-8', '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm', '.json': 'application/json', '.css': 'text/css' };

/** Serves a folder as a static file server would, on 127.0.0.1. */
function serve(dir) {
  const server = createServer((request, response) => {
    let path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    if (path === '/favicon.ico') { response.writeHead(204); response.end(); return; }
    if (path.endsWith('/')) path += 'index.html';
    const file = normalize(join(dir, path));
    if (!file.startsWith(dir + sep) || !existsSync(file) || statSync(file).isDirectory()) {
      response.writeHead(404, { 'content-type': 'text/plain' });
      response.end('not found');
      return;
    }
    response.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-store' });
    response.end(readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

let browser;
/** Opens dir's index.html in headless Chromium and checks what the page wrote. */
async function openPage(dir, url, expectedLogs = []) {
  const server = dir ? await serve(dir) : null;
  try {
    browser ??= await chromium.launch({
      executablePath: CHROMIUM,
      headless: true,
      args: ['--no-sandbox', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
    });
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (error) => errors.push(error.message));
    page.on('console', (message) => {
      if (!expectedLogs.includes(message.text())) errors.push(`console.${message.type()}: ${message.text()}`);
    });
    page.on('requestfailed', (request) => errors.push(`${request.url()}: ${request.failure()?.errorText}`));
    page.on('response', (response) => { if (response.status() >= 400) errors.push(`${response.url()}: ${response.status()}`); });
    await page.goto(url ?? `http://127.0.0.1:${server.address().port}/`);
    const result = await page.waitForFunction(() => window.__subsurf, null, { timeout: 20000 }).then((h) => h.jsonValue(), (e) => ({ error: e.message }));
    const text = await page.textContent('#out');
    await page.close();
    assert.deepEqual(result, EXPECTED, `page result (errors: ${errors.join('; ') || 'none'})`);
    assert.equal(text, JSON.stringify(EXPECTED));
    assert.deepEqual(errors, [], 'no errors, warnings or other console output in the page');
  } finally {
    server?.close();
  }
}

/** Runs `vite` (the dev server, dependency pre-bundling and all) in dir and opens its page. */
async function viteDev(dir) {
  const port = await new Promise((resolve) => {
    const probe = createServer().listen(0, '127.0.0.1', () => { const { port } = probe.address(); probe.close(() => resolve(port)); });
  });
  const child = spawn(bin('vite'), ['--host', '127.0.0.1', '--port', String(port), '--strictPort'], { cwd: dir, env: { ...process.env, NO_COLOR: '1' } });
  let output = '';
  try {
    await new Promise((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`vite did not start in 20 s:\n${output}`)), 20000);
      const listen = (data) => {
        output += data;
        if (output.includes(`127.0.0.1:${port}`)) { clearTimeout(timer); resolve(); }
      };
      child.stdout.on('data', listen);
      child.stderr.on('data', listen);
      child.on('exit', (code) => { clearTimeout(timer); reject(new Error(`vite exited ${code}:\n${output}`)); });
    });
    await openPage(null, `http://127.0.0.1:${port}/`, ['[vite] connecting...', '[vite] connected.']);
  } finally {
    child.kill();
  }
}

/**
 * Asserts that a bundler's output `dir` has both of the package's modules as assets (found by
 * their sizes): the SIMD one, and subsurf_nosimd.wasm, which an engine without SIMD loads.
 */
function bothModules(dir) {
  const sizes = new Set();
  const walk = (d) => {
    for (const entry of readdirSync(d, { withFileTypes: true })) {
      const path = join(d, entry.name);
      if (entry.isDirectory()) walk(path);
      else if (entry.name.endsWith('.wasm')) sizes.add(statSync(path).size);
    }
  };
  walk(dir);
  for (const file of ['subsurf_bg.wasm', 'subsurf_nosimd.wasm']) {
    assert.ok(sizes.has(statSync(join(pkgDir, file)).size), `${dir} has ${file} as an asset (wasm sizes there: ${[...sizes]})`);
  }
}

let tarball;
await part('npm pack', () => {
  const [info] = JSON.parse(run('npm', ['pack', pkgDir, '--pack-destination', scratch, '--json', '--loglevel=error'], scratch));
  tarball = join(scratch, info.filename);
  const files = info.files.map((f) => f.path);
  for (const file of ['auto.js', 'three-auto.js', 'subsurf_bg.wasm', 'subsurf_nosimd.wasm', 'support.js', 'node.js', 'package.json', 'worker.js', 'worker-node.js', 'worker-client.js',
    'worker-thread.js', 'worker-script.js', 'worker-script-node.js', 'worker.d.ts', 'worker-thread.d.ts']) assert.ok(files.includes(file), `tarball has ${file}`);
});

if (tarball) {
  await part('node: fresh project, import from subsurf with no init', () => {
    const dir = project('node', [tarball]);
    writeFileSync(join(dir, 'index.js'), `import { subdivide, version } from 'subsurf';\nimport { createWorker } from 'subsurf/worker';\n` +
      `${CUBE}${WORKER}console.log(JSON.stringify({ ...result, ...(await inWorker) }));\n`);
    const printed = JSON.parse(run(process.execPath, ['index.js'], dir));
    assert.deepEqual(printed, { version, vertices: 98, faces: 96, worker: 'same', workerProgress: '1,2' });
  });

  // Vite 8 runs on Node ^20.19 or >=22.12 (Debian 12's Node 18 cannot run it).
  const [major, minor] = process.versions.node.split('.').map(Number);
  const viteRuns = major > 22 || (major === 22 && minor >= 12) || (major === 20 && minor >= 19);
  if (!viteRuns) {
    console.log(`SKIPPED vite: Node ${process.versions.node} cannot run vite 8 (it needs ^20.19 or >=22.12)`);
  } else {
    await part('vite: install', () => {
      const dir = project('vite', [tarball, `three@${threeVersion}`]);
      writeFileSync(join(dir, 'index.html'), `<!doctype html><meta charset="utf-8"><title>subsurf in Vite</title>${REPORT_ERRORS}
  <pre id="out"></pre><script type="module" src="/src/main.js"></script>\n`);
      mkdirSync(join(dir, 'src'));
      writeFileSync(join(dir, 'src', 'main.js'), APP);
    });
    await part('vite: vite build', () => {
      run(bin('vite'), ['build', '--logLevel', 'warn'], join(scratch, 'vite'));
      bothModules(join(scratch, 'vite', 'dist'));
    });
    await part('vite: page in Chromium', () => openPage(join(scratch, 'vite', 'dist')));
    await part('vite: dev server (vite), page in Chromium', () => viteDev(join(scratch, 'vite')));
  }

  await part('webpack: install', () => {
    const dir = project('webpack', [tarball, `three@${threeVersion}`]);
    mkdirSync(join(dir, 'src'));
    writeFileSync(join(dir, 'src', 'index.js'), APP);
  });
  await part('webpack: webpack (no config)', () => {
    const dir = join(scratch, 'webpack');
    // The defaults: production mode, ./src/index.js to ./dist/main.js; the .wasm becomes an asset.
    run(bin('webpack'), ['--mode', 'production'], dir);
    bothModules(join(dir, 'dist'));
    writeFileSync(join(dir, 'dist', 'index.html'), `<!doctype html><meta charset="utf-8"><title>subsurf in webpack</title>${REPORT_ERRORS}
<pre id="out"></pre><script src="main.js"></script>\n`);
  });
  await part('webpack: page in Chromium', () => openPage(join(scratch, 'webpack', 'dist')));

  await part('static: install', () => {
    const dir = project('static', [tarball, `three@${threeVersion}`]);
    const imports = {
      subsurf: './node_modules/subsurf/auto.js',
      'subsurf/three': './node_modules/subsurf/three-auto.js',
      'subsurf/worker': './node_modules/subsurf/worker.js',
      three: './node_modules/three/build/three.module.js',
    };
    writeFileSync(join(dir, 'index.html'), `<!doctype html><meta charset="utf-8"><title>subsurf in a plain page</title>${REPORT_ERRORS}
<script type="importmap">${JSON.stringify({ imports })}</script>
<pre id="out"></pre><script type="module" src="./main.js"></script>\n`);
    writeFileSync(join(dir, 'main.js'), APP);
  });
  await part('static: page in Chromium', () => openPage(join(scratch, 'static')));
}
await browser?.close();

console.log('\nconsumers: time per part');
for (const [name, seconds] of times) console.log(`  ${seconds.toFixed(1).padStart(5)}s  ${name}`);
console.log(failures === 0 ? `consumers: ok (subsurf ${version}, three ${threeVersion})` : `consumers: ${failures} FAILED`);
process.exit(failures === 0 ? 0 : 1);
