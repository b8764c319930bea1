// End-to-end test of the demo page in headless Chromium (Playwright, playwright-core):
//   node tests/e2e/demo.mjs                      (after scripts/build-pkg.sh)
//   UPDATE_SCREENSHOT=1 node tests/e2e/demo.mjs  (also rewrites docs/demo.png for the README)
//   DEMO_URL=http://127.0.0.1:8080/ node tests/e2e/demo.mjs   (a page scripts/demo.sh serves)
//   PKG_DIR=/elsewhere/pkg node tests/e2e/demo.mjs             (a package built elsewhere)
//
// Serves www/ (with /pkg/ mapped to the freshly built pkg/) on a free port and drives the page as
// a user would: checks that the canvas shows a shaded mesh, that the face and vertex counts shown
// for each scheme, level and mesh equal the counts formulas, that an OBJ opened through the file
// input is subdivided and a broken one is refused with a message while the last result stays,
// that an OBJ's crease tags are drawn and honoured and that clicking a cage edge toggles its
// crease and changes the surface (on a built-in mesh too), that meshes with UVs (built-in, or an
// OBJ with vt) show the checker texture with their vertices split along the seams, that the
// fvarLinear menu changes the picture, that the memory guard refuses a level with a message, that a big job still running is
// superseded by a later change while the page stays responsive and shows the levels done, that the OBJ download holds the
// shown mesh, and that mouse and touch move the camera; that the surface is shaded with the
// library's limit normals and the limit surface checkbox gives the library's limit (disabled for
// Doo-Sabin); that animate moves the surface every frame through one evaluator (frames equal
// subdivide of the deformed cage, a positive CPU time per frame, the still picture back after)
// while the GPU toggle says WebGPU is missing; and, in a second browser with WebGPU (SwiftShader),
// that the GPU path draws a shaded, moving surface on the WebGPU canvas from the GPU evaluator's
// buffers, equal to the CPU's frame, with its time per frame shown. Screenshots go to
// artifacts/. Exits non-zero on failure.
import assert from 'node:assert/strict';
import { copyFileSync, mkdirSync, readFileSync, existsSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { launchChromium, pkg, root, serveStatic } from './harness.mjs';

const artifacts = join(root, 'artifacts');
// WebGPU through SwiftShader's Vulkan, as /work/shared/toolchain.md says, plus what drawing to a
// WebGPU canvas needs headless: SwiftShader for Vulkan and for ANGLE (WebGL), so that the
// canvas's images can be shared with the compositor. Without those three the GPU process loses
// the device at the first canvas frame ("Could not find SharedImageBackingFactory ...
// WebgpuSwapChainTexture"); compute alone works either way.
const WEBGPU_ARGS = ['--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan',
  '--use-vulkan=swiftshader', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'];

/** Counts pixels of a PNG (decoded by the page itself) that differ from the background. */
async function analyze(page, png) {
  return page.evaluate(async (base64) => {
    const blob = await (await fetch(`data:image/png;base64,${base64}`)).blob();
    const image = await createImageBitmap(blob);
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const { data } = context.getImageData(0, 0, image.width, image.height);
    const background = [data[0], data[1], data[2]]; // a corner is always background
    let mesh = 0;
    let crease = 0;
    let hash = 0;
    let lumaSum = 0;
    let lumaSquares = 0;
    let jumps = 0;
    let pairs = 0;
    let blue = 0;
    let previous = null; // the luma of the pixel to the left, if it is a mesh pixel
    const shades = new Set();
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      const difference = Math.abs(r - background[0]) + Math.abs(g - background[1]) + Math.abs(b - background[2]);
      if (difference > 30) {
        mesh++;
        shades.add(r >> 3);
        const luma = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        if (b > r) blue++; // the checker's dark squares; the plain outside is orange (red over blue)
        lumaSum += luma;
        lumaSquares += luma * luma;
        if (previous !== null && (i / 4) % image.width !== 0) {
          jumps += Math.abs(luma - previous);
          pairs++;
        }
        previous = luma;
      } else {
        previous = null;
      }
      // The pinks of creased cage edges: red over blue over green. The surface's oranges have
      // blue under green, the cage's blues red under blue.
      if (r > 150 && r >= b && b > g + 40) crease++;
      hash = (hash * 31 + data[i] * 7 + data[i + 1] * 3 + data[i + 2]) | 0;
    }
    // The spread of brightness over the mesh, and its mean jump from pixel to pixel: shading
    // alone varies smoothly, a checker texture adds jumps between light and dark squares.
    const lumaMean = lumaSum / Math.max(mesh, 1);
    const lumaStd = Math.sqrt(Math.max(lumaSquares / Math.max(mesh, 1) - lumaMean * lumaMean, 0));
    return {
      total: data.length / 4, mesh, crease, shades: shades.size, hash, background, lumaStd, lumaJump: jumps / Math.max(pairs, 1),
      blueShare: blue / Math.max(mesh, 1),
    };
  }, png.toString('base64'));
}

function fail(message) {
  console.error(`e2e demo: FAILED ${message}`);
  process.exitCode = 1;
}

// ---- the counts formulas
// Catmull-Clark, closed mesh: F' = Σ face sizes, V' = V + E + F; after the first level all quads
// (F' = 4F, E' = 2E + Σ face sizes). Cube: 6·4^L faces, 6·4^L + 2 vertices (L ≥ 1).
const cubeCatmullClark = (level) => ({ faces: 6 * 4 ** level, vertices: level === 0 ? 8 : 6 * 4 ** level + 2 });
// The cube's UV cross cuts it along a spanning tree of 7 edges: at level L the tree has 7·2^L
// edges and 7·2^L + 1 vertices, the cut-open disk 14·2^L boundary vertices, so drawing splits
// 7·2^L − 1 more vertices than the surface has.
const cubeDrawnVertices = (level) => cubeCatmullClark(level).vertices + 7 * 2 ** level - 1;
// Loop: F' = 4F, V' = V + E. Icosahedron: 20·4^L faces, 10·4^L + 2 vertices.
const icosahedronLoop = (level) => ({ faces: 20 * 4 ** level, vertices: 10 * 4 ** level + 2 });

async function run() {
  if (!existsSync(join(pkg, 'subsurf_bg.wasm'))) throw new Error(`${pkg} is not built; run scripts/build-pkg.sh`);
  mkdirSync(artifacts, { recursive: true });
  // DEMO_URL tests a page served elsewhere, e.g. by scripts/demo.sh.
  // www/, with /pkg/ served from the built package.
  const server = process.env.DEMO_URL ? null : await serveStatic({ routes: { '/pkg/': pkg, '/': join(root, 'www') } });
  const url = process.env.DEMO_URL ?? `${server.origin}/`;
  console.log(`  testing ${url}`);
  const browser = await launchChromium({ args: ['--disable-gpu', '--enable-unsafe-swiftshader'] });
  const problems = [];
  const report = {};
  try {
    const context = await browser.newContext({ viewport: { width: 1280, height: 800 }, hasTouch: true, acceptDownloads: true });
    const page = await context.newPage();
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    page.on('console', (message) => message.type() === 'error' && problems.push(`console error: ${message.text()}`));
    page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));

    // ---- ready
    const loadStarted = Date.now();
    await page.goto(url);
    await page.waitForFunction(() => window.subsurfReady === true || document.documentElement.dataset.fatal, null, { timeout: 60_000 });
    const fatal = await page.evaluate(() => document.documentElement.dataset.fatal);
    assert.equal(fatal, undefined, `the page could not start: ${fatal}`);
    report.readyMs = Date.now() - loadStarted;
    report.readyInPage = await page.evaluate(() => window.subsurfTimings);

    const canvas = page.locator('#view');
    const dataset = () => page.evaluate(() => ({ ...document.documentElement.dataset }));
    // The canvas's own pixels (the page keeps its drawing buffer), without the overlays on it.
    const shot = async (name) => {
      const url = await canvas.evaluate((element) => element.toDataURL('image/png'));
      const png = Buffer.from(url.slice(url.indexOf(',') + 1), 'base64');
      writeFileSync(join(artifacts, `demo-${name}.png`), png);
      return analyze(page, png);
    };
    const afterFrames = () => page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
    const subdivideTimes = [];

    /** Waits until the drawn result matches `expected` (dataset fields) and no job runs. */
    const shows = async (expected, what) => {
      await page
        .waitForFunction((want) => {
          const data = document.documentElement.dataset;
          return !data.busy && Object.entries(want).every(([key, value]) => data[key] === String(value));
        }, expected, { timeout: 60_000 })
        .catch(async () => {
          throw new Error(`${what}: expected ${JSON.stringify(expected)}; the page shows ${JSON.stringify(await dataset())}`);
        });
      const data = await dataset();
      subdivideTimes.push({ what, faces: Number(data.faces), ms: Number(data.subdivideMs) });
      if (expected.faces !== undefined) {
        assert.equal(await page.locator('#faces-out').textContent(), Number(expected.faces).toLocaleString('en-US'), `${what}: faces shown`);
      }
      if (expected.vertices !== undefined) {
        assert.equal(await page.locator('#vertices-out').textContent(), Number(expected.vertices).toLocaleString('en-US'), `${what}: vertices shown`);
      }
      if (expected.facesIn !== undefined) {
        assert.equal(await page.locator('#faces-in').textContent(), Number(expected.facesIn).toLocaleString('en-US'), `${what}: faces in`);
      }
      assert.equal(data.error, undefined, `${what}: no error expected, the page says ${data.error}`);
      return data;
    };
    /** Waits until an error message is on screen and returns it. */
    const showsError = async (what) => {
      await page.waitForFunction(() => document.documentElement.dataset.error && !document.documentElement.dataset.busy, null, { timeout: 30_000 })
        .catch(async () => {
          throw new Error(`${what}: expected an error message; the page shows ${JSON.stringify(await dataset())}`);
        });
      const text = await page.locator('#message').textContent();
      assert.ok(await page.locator('#message').isVisible(), `${what}: the message is visible`);
      assert.equal(await page.locator('#message').getAttribute('class'), 'error');
      return text;
    };
    const setLevel = (level) => page.locator('#level').evaluate((input, value) => {
      input.value = String(value);
      input.dispatchEvent(new Event('input', { bubbles: true }));
    }, level);

    // ---- the first view: the cube, Catmull-Clark, two levels, drawn and shaded
    await shows({ shape: 'cube', scheme: 'catmull-clark,catmull-clark', level: 2, ...cubeCatmullClark(2), facesIn: 6, verticesIn: 8 }, 'first view');
    const first = await shot('ready');
    const share = first.mesh / first.total;
    console.log(`  ready in ${report.readyMs} ms (page load to first result on screen; in the page ` +
      `${report.readyInPage.navigationToReady.toFixed(0)} ms after navigation, the first job ${report.readyInPage.firstJobMs.toFixed(0)} ms ` +
      `of that, its subdivision ${(await dataset()).subdivideMs} ms); mesh covers ${(100 * share).toFixed(1)}% of the canvas in ${first.shades} shades`);
    assert.ok(share > 0.05 && share < 0.9, `mesh pixels ${(100 * share).toFixed(1)}% of the canvas`);
    assert.ok(first.shades >= 4, `only ${first.shades} shades; the mesh should be shaded`);

    // The slider with the keyboard, as a user would.
    await page.locator('#level').focus();
    await page.keyboard.press('ArrowRight');
    await shows({ level: 3, ...cubeCatmullClark(3) }, 'cube level 3 by keyboard');
    assert.notEqual((await shot('cube-level3')).hash, first.hash, 'the picture changes with the level');

    // ---- UVs: the cube's cross layout, refined with the surface and drawn as a checker
    const firstData = await shows({ level: 3, uv: true, fvarLinear: 'corners-plus1', drawnVertices: cubeDrawnVertices(3) }, 'cube level 3 with UVs');
    assert.ok(Number(firstData.drawnVertices) > Number(firstData.vertices), 'UV seams split vertices for drawing');
    const checkered = await shot('uv-checker');
    // The surface alone (no cage, no wireframe lines), with and without the texture.
    await page.uncheck('#cage');
    await page.uncheck('#wireframe');
    await afterFrames();
    const surfaceTextured = await shot('uv-surface');
    await page.uncheck('#texture');
    await afterFrames();
    const surfacePlain = await shot('uv-surface-plain');
    for (const toggle of ['#texture', '#cage', '#wireframe']) await page.check(toggle);
    await afterFrames();
    const percent = (x) => `${(100 * x).toFixed(0)}%`;
    console.log(`  UV checker: dark (blue) squares cover ${percent(surfaceTextured.blueShare)} of the surface, ${percent(surfacePlain.blueShare)} without the texture; ` +
      `brightness spread ${surfaceTextured.lumaStd.toFixed(1)} and ${surfacePlain.lumaStd.toFixed(1)}, mean jump between neighbouring pixels ${surfaceTextured.lumaJump.toFixed(2)} and ${surfacePlain.lumaJump.toFixed(2)}`);
    // A checker is half dark and half light squares; the plain surface is all orange.
    assert.ok(surfaceTextured.blueShare > 0.25 && surfaceTextured.blueShare < 0.75, `the checker covers the surface (${percent(surfaceTextured.blueShare)} dark)`);
    assert.ok(surfacePlain.blueShare < 0.02, 'no checker without the texture');
    assert.ok(surfaceTextured.lumaStd > surfacePlain.lumaStd, 'the squares spread the brightness further than shading alone');
    assert.ok(surfaceTextured.lumaJump > 1.5 * surfacePlain.lumaJump, 'the squares add sharp edges');
    assert.equal((await shot('uv-checker-again')).hash, checkered.hash, 'the same picture with everything back on');
    // The fvarLinear menu: 'all' keeps the UVs linear, a different picture; back to the default.
    await page.selectOption('#fvar-linear', 'all');
    await shows({ level: 3, uv: true, fvarLinear: 'all', drawnVertices: cubeDrawnVertices(3) }, "fvarLinear 'all'");
    assert.notEqual((await shot('uv-linear-all')).hash, checkered.hash, 'linear UVs look different');
    await page.selectOption('#fvar-linear', 'corners-plus1');
    await shows({ level: 3, fvarLinear: 'corners-plus1' }, 'fvarLinear back to the default');
    assert.equal((await shot('uv-default-again')).hash, checkered.hash, 'the default picture again');

    // ---- Catmull-Clark on the cube: 6·4^L
    for (const level of [0, 1, 4, 2]) {
      await setLevel(level);
      await shows({ scheme: Array(level).fill('catmull-clark').join(','), level, ...cubeCatmullClark(level) }, `cube, Catmull-Clark level ${level}`);
    }

    // ---- every scheme the package offers is in the menu
    const library = await import(pathToFileURL(join(pkg, 'node.js')).href);
    const menu = (select) => page.locator(`${select} option`).evaluateAll((options) => options.map((o) => o.value));
    assert.deepEqual(await menu('#scheme'), library.schemeNames(), 'the scheme menu lists schemeNames()');
    assert.deepEqual(await menu('#boundary'), library.boundaryRules(), 'the boundary menu lists boundaryRules()');
    assert.deepEqual(await menu('#shape'), library.shapeNames(), 'the mesh menu lists shapeNames()');

    // ---- Doo-Sabin on the cube, one level: F' = V + E + F = 8 + 12 + 6 = 26, V' = Σ face sizes = 24
    await setLevel(1);
    await shows({ level: 1, faces: 24 }, 'cube level 1');
    await page.selectOption('#scheme', 'doo-sabin');
    const dooSabin = await shows({ scheme: 'doo-sabin', level: 1, faces: 26, vertices: 24 }, 'Doo-Sabin on the cube');
    // Doo-Sabin refines the UVs too: its 24 corner points, and 8 more drawn where the faces
    // across the cross's cut edges and around its cut vertices take one side's values.
    assert.equal(dooSabin.uv, 'true', 'Doo-Sabin keeps the UVs');
    assert.equal(dooSabin.drawnVertices, '32');
    assert.doesNotMatch(await page.locator('#message').textContent(), /UVs not shown/);
    const dooSabinPicture = await shot('doo-sabin-cube');

    // ---- Loop on the cube: a scheme/mesh mismatch is refused and the last result stays
    await page.selectOption('#scheme', 'loop');
    const mismatch = await showsError('Loop on the cube');
    console.log(`  Loop on the cube: "${mismatch.split('\n')[0]}"`);
    assert.match(mismatch, /triangles only/);
    assert.match(mismatch, /quad-triangle/, 'the message says what to do');
    const afterMismatch = await dataset();
    assert.equal(afterMismatch.faces, dooSabin.faces, 'the Doo-Sabin result is still the one shown');
    assert.equal(afterMismatch.scheme, 'doo-sabin');
    assert.equal((await shot('error-mismatch')).hash, dooSabinPicture.hash, 'the picture did not change');
    await page.screenshot({ path: join(artifacts, 'demo-page-error.png') });

    // ---- Loop on the icosahedron: 20·4^L faces
    await page.selectOption('#shape', 'icosahedron');
    for (const level of [1, 3, 0, 2]) {
      if (level !== 1) await setLevel(level);
      await shows({ shape: 'icosahedron', scheme: Array(level).fill('loop').join(','), level, ...icosahedronLoop(level), facesIn: 20 }, `Loop on the icosahedron, level ${level}`);
    }
    await shot('loop-icosahedron');

    // √3 on the icosahedron: F' = 3F, V' = V + F (closed).
    await page.selectOption('#scheme', 'sqrt3');
    await shows({ scheme: 'sqrt3,sqrt3', faces: 180, vertices: 92 }, '√3 on the icosahedron, level 2');

    // ---- a different scheme per level: Loop, then Catmull-Clark on the 80 triangles
    await page.check('#per-level');
    await page.locator('.level-scheme[data-level="1"]').selectOption('loop');
    await page.locator('.level-scheme[data-level="2"]').selectOption('catmull-clark');
    // Loop: 80 triangles, 42 vertices, 120 edges; Catmull-Clark: F' = 3·80, V' = 42 + 120 + 80.
    await shows({ scheme: 'loop,catmull-clark', level: 2, faces: 240, vertices: 242 }, 'Loop then Catmull-Clark');
    await page.uncheck('#per-level');
    await page.selectOption('#scheme', 'catmull-clark');
    // Catmull-Clark twice: 60 quads, 62 vertices, 120 edges; then 240 quads, 62 + 120 + 60 vertices.
    await shows({ scheme: 'catmull-clark,catmull-clark', faces: 240, vertices: 242 }, 'Catmull-Clark on the icosahedron, level 2');

    // ---- the other built-in meshes, Catmull-Clark level 1: F' = Σ face sizes, V' = V + E + F
    await setLevel(1);
    await shows({ level: 1, faces: 60 }, 'icosahedron level 1');
    const builtIns = [
      ['dodecahedron', { faces: 60, vertices: 20 + 30 + 12, facesIn: 12 }],
      ['torus', { faces: 4 * 288, vertices: 288 + 576 + 288, facesIn: 288 }],
      // 96 vertices, 69 quads, Euler characteristic −1, so 166 edges.
      ['sheet-with-holes', { faces: 4 * 69, vertices: 96 + 166 + 69, facesIn: 69 }],
      ['house', { faces: 5 * 4 + 4 * 3, vertices: 9 + 16 + 9, facesIn: 9 }],
    ];
    for (const [shape, counts] of builtIns) {
      await page.selectOption('#shape', shape);
      await shows({ shape, level: 1, ...counts }, `${shape}, Catmull-Clark level 1`);
      await shot(shape);
    }
    // Quad/Triangle on the house: quads split into 4 quads around a face point, triangles into
    // 4 triangles; no face point for a triangle: V' = 9 + 16 + 5.
    await page.selectOption('#scheme', 'quad-triangle');
    await shows({ shape: 'house', scheme: 'quad-triangle', faces: 36, vertices: 30 }, 'Quad/Triangle on the house');

    // Boundary rules on the sheet: 'fixed' moves the surface.
    await page.selectOption('#shape', 'sheet-with-holes');
    await page.selectOption('#scheme', 'catmull-clark');
    await setLevel(2);
    const sheet = await shows({ shape: 'sheet-with-holes', scheme: 'catmull-clark,catmull-clark', faces: 16 * 69 }, 'sheet level 2');
    const sheetPicture = await shot('sheet-edge-and-corner');
    await page.selectOption('#boundary', 'fixed');
    await page.waitForFunction((job) => document.documentElement.dataset.job !== job && !document.documentElement.dataset.busy, sheet.job);
    assert.notEqual((await shot('sheet-fixed')).hash, sheetPicture.hash, 'the boundary rule changes the surface');
    await page.selectOption('#boundary', 'edge-and-corner');
    await page.waitForFunction(() => !document.documentElement.dataset.busy);
    assert.equal((await shot('sheet-edge-and-corner-again')).hash, sheetPicture.hash, 'back to the first picture');

    // ---- the user's own OBJ through the file input: a square pyramid (1 quad, 4 triangles)
    const pyramid = ['# a square pyramid', 'v -1 0 -1', 'v 1 0 -1', 'v 1 0 1', 'v -1 0 1', 'v 0 1.5 0',
      'f 1 2 3 4', 'f 4 3 5', 'f 3 2 5', 'f 2 1 5', 'f 1 4 5', ''].join('\n');
    await page.setInputFiles('#file', { name: 'pyramid.obj', mimeType: 'model/obj', buffer: Buffer.from(pyramid) });
    // Catmull-Clark level 2: level 1 has Σ face sizes = 16 quads and 5 + 8 + 5 = 18 vertices,
    // level 2 has 64 quads and 18 + 32 + 16 = 66 vertices.
    const opened = await shows({ shape: 'file-1', level: 2, faces: 64, vertices: 66, facesIn: 5, verticesIn: 5, uv: false, drawnVertices: 66 }, 'pyramid.obj');
    assert.equal(await page.locator('#shape option:checked').textContent(), 'File: pyramid.obj');
    const pyramidPicture = await shot('pyramid-obj');

    // A broken OBJ: refused with a message naming the file and the line; the pyramid stays.
    const broken = ['v 0 0 0', 'v 1 0 0', 'v 0 1 0', 'f 1 2 7', ''].join('\n');
    await page.setInputFiles('#file', { name: 'broken.obj', mimeType: 'model/obj', buffer: Buffer.from(broken) });
    const brokenMessage = await showsError('broken.obj');
    console.log(`  broken.obj: "${brokenMessage.split('\n')[0]}"`);
    assert.match(brokenMessage, /broken\.obj/);
    assert.match(brokenMessage, /line 4/);
    const afterBroken = await dataset();
    assert.equal(afterBroken.job, opened.job, 'no new result after the broken file');
    assert.equal(afterBroken.faces, '64');
    assert.equal(await page.locator('#shape').inputValue(), 'file-1', 'the pyramid is still the selected mesh');
    assert.equal((await shot('error-broken-obj')).hash, pyramidPicture.hash, 'the pyramid is still drawn');
    // The pyramid keeps working after the error.
    await setLevel(1);
    await shows({ shape: 'file-1', level: 1, faces: 16, vertices: 18 }, 'pyramid.obj level 1 after the error');

    // ---- download the result as OBJ: the file holds the shown mesh
    const [download] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
    const saved = join(artifacts, 'demo-download.obj');
    await download.saveAs(saved);
    const lines = readFileSync(saved, 'utf8').split('\n');
    assert.equal(download.suggestedFilename(), 'pyramid-catmull-clark-L1.obj');
    assert.equal(lines.filter((line) => line.startsWith('v ')).length, 18, 'vertices in the downloaded OBJ');
    assert.equal(lines.filter((line) => line.startsWith('f ')).length, 16, 'faces in the downloaded OBJ');
    assert.equal(lines.filter((line) => line.startsWith('vt ')).length, 0, 'no UVs in, none out');

    // ---- an OBJ with UVs: a unit square in the xy plane whose vt are its x, y. Catmull-Clark
    // level 1 with the default mode keeps the corner UVs (one face each) and takes midpoints and
    // the centre, as the positions do on a lone quad (edge-and-corner): the downloaded file's vt
    // of every corner equals its vertex's x, y, and the checker is drawn.
    const square = ['v 0 0 0', 'v 1 0 0', 'v 1 1 0', 'v 0 1 0', 'vt 0 0', 'vt 1 0', 'vt 1 1', 'vt 0 1', 'f 1/1 2/2 3/3 4/4', ''].join('\n');
    await page.setInputFiles('#file', { name: 'square.obj', mimeType: 'model/obj', buffer: Buffer.from(square) });
    await shows({ shape: 'file-3', level: 1, faces: 4, vertices: 9, uv: true, drawnVertices: 9 }, 'square.obj with vt');
    const squareShot = await shot('uv-obj');
    assert.ok(squareShot.blueShare > 0.2, `the OBJ's UVs show the checker (${(100 * squareShot.blueShare).toFixed(0)}% dark squares)`);
    const [squareDownload] = await Promise.all([page.waitForEvent('download'), page.click('#download')]);
    const squarePath = join(artifacts, 'demo-download-uv.obj');
    await squareDownload.saveAs(squarePath);
    const squareLines = readFileSync(squarePath, 'utf8').trim().split('\n');
    const vs = squareLines.filter((line) => line.startsWith('v ')).map((line) => line.split(' ').slice(1).map(Number));
    const vts = squareLines.filter((line) => line.startsWith('vt ')).map((line) => line.split(' ').slice(1).map(Number));
    const corners = squareLines.filter((line) => line.startsWith('f ')).flatMap((line) => line.split(' ').slice(1));
    assert.equal(vts.length, 9, 'vt lines in the downloaded OBJ');
    assert.equal(corners.length, 16);
    for (const corner of corners) {
      const [v, vt] = corner.split('/').map((i) => Number(i) - 1);
      assert.deepEqual(vts[vt], vs[v].slice(0, 2), `corner ${corner}: its vt is its vertex's x, y`);
    }

    // ---- drag and drop: a tetrahedron dropped on the page (Catmull-Clark level 1: 4 · 3 quads,
    // 4 + 6 + 4 vertices)
    const tetrahedron = ['v 1 1 1', 'v 1 -1 -1', 'v -1 1 -1', 'v -1 -1 1', 'f 1 2 3', 'f 1 3 4', 'f 1 4 2', 'f 2 4 3', ''].join('\n');
    const dropZoneShown = await page.evaluate((text) => {
      const transfer = new DataTransfer();
      transfer.items.add(new File([text], 'tetrahedron.obj', { type: 'model/obj' }));
      const event = (type) => new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true });
      document.getElementById('view').dispatchEvent(event('dragenter'));
      const shown = !document.getElementById('drop-zone').hidden;
      document.getElementById('view').dispatchEvent(event('drop'));
      return shown;
    }, tetrahedron);
    assert.ok(dropZoneShown, 'dragging a file over the page shows the drop zone');
    await shows({ shape: 'file-4', level: 1, faces: 12, vertices: 14, facesIn: 4, verticesIn: 4 }, 'tetrahedron.obj dropped');
    assert.ok(await page.locator('#drop-zone').isHidden(), 'the drop zone hides after the drop');
    await shot('tetrahedron-dropped');

    // ---- creases: an OBJ with OpenSubdiv crease tags (12 creased edges: 11 of sharpness 5, one
    // of 0.1; interpolateboundary 2, edge-only). Its creased cage edges are drawn in pink, the
    // surface honours them, and clicking a cage edge toggles its crease.
    const tagged = readFileSync(join(root, 'tests', 'meshes', 'osd', 'catmark_cube_creases1.obj'), 'utf8');
    const taggedMesh = library.readObj(tagged);
    // What the page must show: subdivide in Node, one level, with the given creases.
    const expectedPositions = (creases) => Array.from(library.subdivide(taggedMesh, {
      levels: 1,
      boundary: 'edge-only',
      creases: { edges: Uint32Array.from(creases.flatMap(([a, b]) => [a, b])), sharpness: Float32Array.from(creases, (c) => c[2]) },
    }).positions);
    const shownPositions = () => page.evaluate(() => Array.from(window.subsurfDemo.display.result.positions));
    const pageCreases = () => page.evaluate(() => window.subsurfDemo.creases());
    const fileCreases = [];
    for (let i = 0; i < taggedMesh.tags.creases.sharpness.length; i++) {
      fileCreases.push([taggedMesh.tags.creases.edges[2 * i], taggedMesh.tags.creases.edges[2 * i + 1], taggedMesh.tags.creases.sharpness[i]]);
    }
    await page.setInputFiles('#file', { name: 'cube_creases1.obj', mimeType: 'model/obj', buffer: Buffer.from(tagged) });
    let creased = await shows({ shape: 'file-5', level: 1, faces: 24, vertices: 26, facesIn: 6, creases: 12 }, 'cube_creases1.obj');
    assert.equal(await page.locator('#crease-count').textContent(), '12 creased edges (all semi-sharp)');
    assert.equal(await page.locator('#boundary').inputValue(), 'edge-only', "the file's interpolateboundary 2 sets the boundary rule");
    assert.deepEqual(await pageCreases(), fileCreases, 'the page holds the creases of the file');
    const smoothPositions = expectedPositions([]);
    let positions = await shownPositions();
    assert.deepEqual(positions, expectedPositions(fileCreases), 'the surface honours the file\'s creases');
    assert.notDeepEqual(positions, smoothPositions, 'creases change the surface');
    const creasedPicture = await shot('creases-file');
    console.log(`  cube_creases1.obj: "${await page.locator('#crease-count').textContent()}", ${creasedPicture.crease} crease-coloured pixels`);
    assert.ok(creasedPicture.crease > 400, `creased edges are drawn in their colour (${creasedPicture.crease} pixels)`);

    // A click away from every edge changes nothing.
    const box0 = await canvas.boundingBox();
    assert.equal(await page.evaluate(([x, y]) => window.subsurfDemo.pickAt(x, y), [box0.x + 5, box0.y + 5]), -1);
    await page.mouse.click(box0.x + 5, box0.y + 5);
    await afterFrames();
    assert.equal((await dataset()).job, creased.job, 'a click on no edge does not subdivide again');

    // A cage edge of sharpness 5 whose midpoint on screen is closer to it than to any other edge.
    const target = await page.evaluate(() => {
      const demo = window.subsurfDemo;
      const edges = demo.display.cageEdges;
      for (let i = 0; i < edges.length / 2; i++) {
        const crease = demo.creases().find(([a, b]) => (a === edges[2 * i] && b === edges[2 * i + 1]) || (a === edges[2 * i + 1] && b === edges[2 * i]));
        const at = demo.edgeScreenPosition(i);
        if (crease?.[2] === 5 && demo.pickAt(at.x, at.y) === i) return { i, a: crease[0], b: crease[1], edge: [edges[2 * i], edges[2 * i + 1]], ...at };
      }
      return null;
    });
    assert.ok(target, 'some creased cage edge can be clicked');
    const withoutTarget = fileCreases.filter(([a, b]) => !(a === target.a && b === target.b));
    await page.mouse.click(target.x, target.y);
    creased = await shows({ shape: 'file-5', creases: 11 }, `click on cage edge ${target.a}-${target.b}`);
    assert.equal(await page.locator('#crease-count').textContent(), '11 creased edges (all semi-sharp)');
    assert.deepEqual(await pageCreases(), withoutTarget, `edge ${target.a}-${target.b} is smooth after the click`);
    const unclicked = positions;
    positions = await shownPositions();
    assert.notDeepEqual(positions, unclicked, 'the surface changes with the click');
    assert.deepEqual(positions, expectedPositions(withoutTarget), 'the surface is that of the remaining creases');
    const afterFirstClick = positions;

    // Clicking it again creases it with the chosen sharpness (the slider, 10 by default).
    await page.mouse.click(target.x, target.y);
    await shows({ shape: 'file-5', creases: 12 }, `second click on cage edge ${target.a}-${target.b}`);
    assert.equal(await page.locator('#crease-count').textContent(), '12 creased edges (11 semi-sharp)');
    const reclicked = [...withoutTarget, [...target.edge, 10]];
    assert.deepEqual(await pageCreases(), reclicked);
    positions = await shownPositions();
    assert.deepEqual(positions, expectedPositions(reclicked), 'the edge is now infinitely sharp');
    // (At one level, sharpness 5 and 10 both act as infinitely sharp: the surface is as before.)
    assert.notDeepEqual(positions, afterFirstClick, 'the surface changes with the second click');

    // Clear creases: every edge smooth, nothing drawn in crease colours.
    await page.click('#clear-creases');
    await shows({ shape: 'file-5', creases: 0 }, 'clear creases');
    assert.equal(await page.locator('#crease-count').textContent(), '0 creased edges');
    assert.ok(await page.locator('#clear-creases').isDisabled(), 'nothing left to clear');
    assert.deepEqual(await shownPositions(), smoothPositions, 'the surface of the smooth cube');
    const cleared = await shot('creases-cleared');
    assert.ok(cleared.crease < creasedPicture.crease / 10, `no creased edges drawn (${cleared.crease} crease-coloured pixels)`);

    // A built-in mesh has no tags; a click creases one of its edges.
    await page.selectOption('#boundary', 'edge-and-corner');
    await page.selectOption('#shape', 'cube');
    const cube = await shows({ shape: 'cube', level: 1, creases: 0 }, 'cube without creases');
    const cubePositions = await shownPositions();
    const cubeTarget = await page.evaluate(() => {
      const demo = window.subsurfDemo;
      for (let i = 0; i < demo.display.cageEdges.length / 2; i++) {
        const at = demo.edgeScreenPosition(i);
        if (demo.pickAt(at.x, at.y) === i) return at;
      }
      return null;
    });
    await page.mouse.click(cubeTarget.x, cubeTarget.y);
    await shows({ shape: 'cube', level: 1, creases: 1 }, 'a crease on the cube');
    assert.equal(await page.locator('#crease-count').textContent(), '1 creased edge');
    assert.notDeepEqual(await shownPositions(), cubePositions, 'the crease changes the cube');
    assert.ok((await shot('cube-crease')).crease > 50, 'the crease is drawn');
    await page.click('#clear-creases');
    await shows({ shape: 'cube', level: 1, creases: 0 }, 'the cube smooth again');
    assert.deepEqual(await shownPositions(), cubePositions);
    assert.notEqual((await dataset()).job, cube.job);

    // ---- the memory guard: a level over maxFaces is refused with a message; the result stays
    await page.selectOption('#shape', 'cube');
    await setLevel(6);
    const big = await shows({ shape: 'cube', level: 6, ...cubeCatmullClark(6) }, 'cube level 6');
    await page.selectOption('#guard', '10000');
    const guardMessage = await showsError('level 6 with a guard of 10,000 faces');
    console.log(`  guard: "${guardMessage.split('\n')[0]}"`);
    assert.match(guardMessage, /24576 faces, more than the limit of 10000/);
    assert.equal((await dataset()).job, big.job, 'the level-6 result stays');
    assert.equal((await dataset()).maxLevel, '5', 'the page knows the highest level that fits');
    assert.match(await page.locator('#level-hint').textContent(), /up to level 5 fits/);
    await setLevel(5);
    await shows({ level: 5, ...cubeCatmullClark(5) }, 'cube level 5 under the guard');
    assert.equal(await page.locator('#level').getAttribute('max'), '5', 'the slider stops at the guard');
    // A new mesh starts at the highest level that fits: the torus at level 5 would make
    // 288·4^5 faces; level 2 (4,608) is the highest under 10,000.
    await page.selectOption('#shape', 'torus');
    await shows({ shape: 'torus', level: 2, faces: 288 * 16 }, 'torus lowered to level 2');
    assert.match(await page.locator('#message').textContent(), /showing level 2/);

    // ---- responsiveness: a big job runs in the worker; a later change supersedes it. The
    // dodecahedron (60·4^(L-1) quads) gives the biggest job under the largest guard: 3.9M faces
    // at level 9, 2.5 times the cube's 1.6M, which the wasm package now refines in well under the
    // 400 ms this section needs the job to outlast.
    await page.selectOption('#guard', '4000000');
    await page.selectOption('#shape', 'dodecahedron');
    await setLevel(1);
    const before = await shows({ shape: 'dodecahedron', level: 1, faces: 60 }, 'dodecahedron level 1 before the big job');
    const race = await page.evaluate(async () => {
      const data = document.documentElement.dataset;
      const seen = [];
      new MutationObserver(() => seen.push(data.faces)).observe(document.documentElement, { attributeFilter: ['data-faces'] });
      const superseded = Number(data.superseded);
      const slider = document.getElementById('level');
      const maxLevel = Number(slider.max);
      slider.value = String(maxLevel);
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      // While the big job runs, the main thread must keep running timers on time.
      let worstLateness = 0;
      const started = performance.now();
      let last = started;
      while (performance.now() - started < 400) {
        await new Promise((resolve) => setTimeout(resolve, 10));
        const now = performance.now();
        worstLateness = Math.max(worstLateness, now - last - 10);
        last = now;
      }
      const stillBusy = window.subsurfDemo.runner.busy; // the worker has not answered yet
      const busyShown = !document.getElementById('busy').hidden;
      const busyText = document.getElementById('busy-text').textContent;
      slider.value = '2';
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      const changedAt = performance.now();
      await new Promise((resolve) => {
        const check = () => (data.level === '2' && !data.busy ? resolve() : setTimeout(check, 5));
        check();
      });
      return {
        maxLevel, stillBusy, busyShown, busyText, worstLateness, seen,
        superseded: Number(data.superseded) - superseded, laterShownAfter: performance.now() - changedAt,
      };
    });
    console.log(`  big job (level ${race.maxLevel}): busy indicator "${race.busyText}", worst timer lateness ` +
      `${race.worstLateness.toFixed(0)} ms; the later level-2 result was on screen ${race.laterShownAfter.toFixed(0)} ms after the change`);
    assert.equal(race.maxLevel, 9, 'dodecahedron under a 4,000,000-face guard: level 9 (3,932,160 faces) is the highest');
    assert.ok(race.stillBusy, 'the big job was still running 400 ms later (the test needs a job that long)');
    assert.ok(race.busyShown, 'the busy indicator is shown while a long job runs');
    // Levels 1-7 of the 9 take a few milliseconds: by now subdivide has told several of them.
    assert.match(race.busyText, /level [1-9]\/9 ·/, 'the busy indicator shows the levels done (subsurf/worker progress)');
    assert.ok(race.worstLateness < 150, `the page stayed responsive (timers at most ${race.worstLateness.toFixed(0)} ms late)`);
    assert.equal(race.superseded, 1, 'the big job was superseded');
    assert.ok(!race.seen.includes(String(60 * 4 ** (race.maxLevel - 1))), 'the superseded result never reached the screen');
    await shows({ level: 2, faces: 240 }, 'the later result wins');
    assert.notEqual((await dataset()).job, before.job);
    await page.selectOption('#shape', 'cube');
    await shows({ shape: 'cube', level: 2, ...cubeCatmullClark(2) }, 'back to the cube at level 2');

    // ---- display options and the camera
    await page.selectOption('#guard', '1000000');
    await shows({ level: 2 }, 'guard back to a million');
    await page.click('#frame');
    await afterFrames();
    const framed = await shot('framed');
    await page.check('input[name=shading][value=flat]');
    await afterFrames();
    assert.notEqual((await shot('flat')).hash, framed.hash, 'flat shading looks different');
    await page.check('input[name=shading][value=smooth]');
    for (const toggle of ['#wireframe', '#cage']) {
      await page.uncheck(toggle);
      await afterFrames();
      assert.notEqual((await shot(`no-${toggle.slice(1)}`)).hash, framed.hash, `${toggle} changes the picture`);
      await page.check(toggle);
    }
    await afterFrames();
    assert.equal((await shot('framed-again')).hash, framed.hash, 'the same settings give the same picture');

    const box = await canvas.boundingBox();
    const centre = { x: box.x + box.width / 2, y: box.y + box.height / 2 };
    // Orbit with the left button.
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down();
    await page.mouse.move(centre.x + 120, centre.y + 40, { steps: 8 });
    await page.mouse.up();
    await afterFrames();
    const orbited = await shot('orbit');
    assert.notEqual(orbited.hash, framed.hash, 'dragging orbits the view');
    assert.ok(orbited.mesh / orbited.total > 0.05, 'the mesh is still in view after orbiting');
    // Zoom with the wheel.
    await page.mouse.wheel(0, -400);
    await afterFrames();
    const zoomed = await shot('zoom');
    assert.ok(zoomed.mesh > orbited.mesh, 'zooming in makes the mesh larger');
    // Pan with the right button.
    await page.mouse.move(centre.x, centre.y);
    await page.mouse.down({ button: 'right' });
    await page.mouse.move(centre.x - 150, centre.y, { steps: 6 });
    await page.mouse.up({ button: 'right' });
    await afterFrames();
    assert.notEqual((await shot('pan')).hash, zoomed.hash, 'right-dragging pans the view');
    // Touch: two fingers pinching in zoom out, one finger orbits.
    const cdp = await context.newCDPSession(page);
    const touch = (type, points) => cdp.send('Input.dispatchTouchEvent', { type, touchPoints: points.map(([x, y], id) => ({ x, y, id })) });
    const beforeTouch = await shot('before-touch');
    await touch('touchStart', [[centre.x - 150, centre.y], [centre.x + 150, centre.y]]);
    for (let step = 1; step <= 5; step++) {
      await touch('touchMove', [[centre.x - 150 + 20 * step, centre.y], [centre.x + 150 - 20 * step, centre.y]]);
    }
    await touch('touchEnd', []);
    await afterFrames();
    const pinched = await shot('pinch');
    assert.ok(pinched.mesh < beforeTouch.mesh, 'pinching in zooms out');
    await touch('touchStart', [[centre.x, centre.y]]);
    for (let step = 1; step <= 5; step++) await touch('touchMove', [[centre.x + 25 * step, centre.y]]);
    await touch('touchEnd', []);
    await afterFrames();
    assert.notEqual((await shot('touch-orbit')).hash, pinched.hash, 'a one-finger drag orbits');
    // The frame button brings the mesh back to the framed view (same direction as after the orbit).
    await page.click('#frame');
    await afterFrames();
    const reframed = await shot('reframed');
    assert.ok(Math.abs(reframed.mesh / framed.mesh - 1) < 0.25, 'framing restores the mesh size on screen');

    // ---- limit normals: subdivide's normals shade the surface (the limit surface's after
    // Catmull-Clark), and the limit surface checkbox moves the points onto it
    await page.click('#frame');
    const cubeMesh = library.shape('cube');
    const near = (a, b, tolerance, what) => {
      assert.equal(a.length, b.length, `${what}: lengths`);
      const worst = a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);
      assert.ok(worst <= tolerance, `${what}: off by ${worst}`);
    };
    const shownNormals = () => page.evaluate(() => Array.from(window.subsurfDemo.display.result.normals));
    await shows({ shape: 'cube', level: 2, normals: 'limit', limit: false }, 'cube with limit normals');
    near(await shownNormals(), Array.from(library.subdivide(cubeMesh, { levels: 2, normals: true }).normals), 1e-6, 'the normals drawn are the library\'s');
    assert.ok(!(await page.locator('#limit').isDisabled()), 'Catmull-Clark has a limit surface');
    await page.check('#limit');
    await shows({ shape: 'cube', level: 2, normals: 'limit', limit: true }, 'the limit surface');
    const atLimit = library.subdivide(cubeMesh, { levels: 2, limit: true, normals: true });
    near(await shownPositions(), Array.from(atLimit.positions), 1e-6, 'limit positions');
    near(await shownNormals(), Array.from(atLimit.normals), 1e-6, 'limit normals');
    // Doo-Sabin has no limit masks: the checkbox is disabled with a note, the normals come from the faces.
    await page.selectOption('#scheme', 'doo-sabin');
    await shows({ scheme: 'doo-sabin,doo-sabin', normals: 'faces', limit: false }, 'Doo-Sabin: normals from the faces');
    assert.ok(await page.locator('#limit').isDisabled(), 'no limit surface for Doo-Sabin');
    assert.match(await page.locator('#limit-hint').textContent(), /Doo-Sabin has no limit masks/);
    await page.selectOption('#scheme', 'catmull-clark');
    await shows({ scheme: 'catmull-clark,catmull-clark', normals: 'limit', limit: true }, 'back to Catmull-Clark at the limit');
    await page.uncheck('#limit');
    await shows({ level: 2, normals: 'limit', limit: false }, 'limit surface off');
    console.log(`  limit normals: ${await page.locator('#time-detail').textContent()}`);

    // ---- animate: the cage is deformed every frame, one evaluator moves the surface
    await afterFrames();
    const still = await shot('still-before-animation');
    assert.equal((await dataset()).animate, 'false');
    assert.equal((await dataset()).gpu, 'unavailable', 'this browser has no WebGPU adapter (--disable-gpu)');
    assert.ok(await page.locator('#gpu').isDisabled(), 'the GPU toggle is disabled without WebGPU');
    const gpuNote = await page.locator('#gpu-note').textContent();
    assert.match(gpuNote, /^WebGPU not available: /, 'the page says why the GPU path is off');
    console.log(`  GPU toggle: "${gpuNote}"`);
    const framesAtLeast = (n) => page.waitForFunction((want) => Number(document.documentElement.dataset.frames ?? 0) >= want, n, { timeout: 30_000 });
    const frames = async () => Number((await dataset()).frames ?? 0);
    await page.check('#animate');
    await framesAtLeast((await frames()) + 10);
    assert.equal((await dataset()).animate, 'true');
    const moving = [await shot('animate-1')];
    await framesAtLeast((await frames()) + 5);
    moving.push(await shot('animate-2'));
    assert.notEqual(moving[0].hash, moving[1].hash, 'the surface moves from frame to frame');
    assert.notEqual(moving[1].hash, still.hash, 'the animated picture is not the still one');
    for (const picture of moving) {
      assert.ok(picture.mesh / picture.total > 0.05, 'the animated mesh stays in view');
      assert.ok(picture.shades >= 4, 'the animated mesh is shaded');
    }
    await page.waitForFunction(() => Number(document.documentElement.dataset.cpuMs) > 0, null, { timeout: 30_000 });
    const cpuMs = Number((await dataset()).cpuMs);
    assert.ok(Number.isFinite(cpuMs) && cpuMs > 0, `data-cpu-ms is a positive number (${cpuMs})`);
    assert.match(await page.locator('#frame-times').textContent(), /^CPU: \d+\.\d\d ms\/frame/);
    assert.ok(await page.locator('#frame-times').isVisible(), 'the frame time is on screen');
    // A frame is subdivide's surface of the deformed cage, in the shown result's options.
    const frameOf = () => page.evaluate(() => {
      const { prepared } = window.subsurfDemo.animator;
      return {
        cage: Array.from(prepared.deformed), positions: Array.from(prepared.frame.positions), normals: Array.from(prepared.frame.normals),
        job: prepared.display.job, vertices: prepared.evaluator.numVertices,
      };
    });
    let frame = await frameOf();
    assert.equal(String(frame.job), (await dataset()).job, 'the evaluator is that of the result shown');
    const deformedCube = { positions: Float32Array.from(frame.cage), indices: cubeMesh.indices, faceSizes: cubeMesh.faceSizes };
    assert.notDeepEqual(frame.cage, Array.from(cubeMesh.positions), 'the cage is deformed');
    const expectedFrame = library.subdivide(deformedCube, { levels: 2, normals: true });
    near(frame.positions, Array.from(expectedFrame.positions), 1e-5, 'animated positions');
    near(frame.normals, Array.from(expectedFrame.normals), 1e-4, 'animated normals');
    // A new level while animating builds a new evaluator for it.
    await setLevel(3);
    await shows({ level: 3, ...cubeCatmullClark(3) }, 'level 3 while animating');
    await framesAtLeast((await frames()) + 5);
    frame = await frameOf();
    assert.equal(String(frame.job), (await dataset()).job, 'the evaluator follows the new result');
    assert.equal(frame.vertices, cubeCatmullClark(3).vertices);
    report.cpuMs = Number((await dataset()).cpuMs);
    await setLevel(2);
    await shows({ level: 2, ...cubeCatmullClark(2) }, 'level 2 while animating');
    await framesAtLeast((await frames()) + 60);
    report.cpuMsLevel2 = Number((await dataset()).cpuMs);
    console.log(`  animate (CPU): ${await frames()} frames so far, ${await page.locator('#frame-times').textContent()} (cube level 2)`);
    // Off again: the still result is back where the frames were.
    await page.uncheck('#animate');
    await afterFrames();
    const frozen = await frames();
    assert.equal((await dataset()).animate, 'false');
    assert.equal((await shot('still-after-animation')).hash, still.hash, 'the still picture is back');
    await afterFrames();
    assert.equal(await frames(), frozen, 'no frames while not animating');

    // ---- the page as a visitor first sees it, for the README
    const fresh = await context.newPage();
    fresh.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    await fresh.goto(url);
    await fresh.waitForFunction(() => window.subsurfReady === true, null, { timeout: 60_000 });
    await fresh.screenshot({ path: join(artifacts, 'demo-page.png') });
    if (process.env.UPDATE_SCREENSHOT) {
      mkdirSync(join(root, 'docs'), { recursive: true });
      copyFileSync(join(artifacts, 'demo-page.png'), join(root, 'docs', 'demo.png'));
      console.log('  wrote docs/demo.png');
    }
    report.subdivideTimes = subdivideTimes;

    await checkWebGpu(url, problems, report);
  } finally {
    await browser.close();
    server?.close();
  }
  const times = report.subdivideTimes ?? [];
  const largest = times.reduce((a, b) => (b.faces > (a?.faces ?? -1) ? b : a), null);
  if (largest) {
    console.log(`  subdivision times shown: ${times.length} results, median ${median(times.map((t) => t.ms)).toFixed(1)} ms; ` +
      `largest ${largest.faces.toLocaleString('en-US')} faces in ${largest.ms.toFixed(1)} ms`);
  }
  for (const problem of problems) fail(problem);
}

/**
 * The animation's GPU path, in a second browser with a WebGPU adapter (SwiftShader's Vulkan):
 * the GPU toggle is offered, the GPU evaluator's buffers are drawn on the WebGPU canvas (a
 * shaded surface that moves), its output equals the CPU evaluator's, and the GPU time is
 * shown, from timestamp queries and (with ?gpu-timing=work-done) from onSubmittedWorkDone.
 */
async function checkWebGpu(url, problems, report) {
  const browser = await launchChromium({ args: WEBGPU_ARGS });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    page.on('pageerror', (error) => problems.push(`WebGPU page error: ${error.message}`));
    page.on('console', (message) => message.type() === 'error' && problems.push(`WebGPU console error: ${message.text()}`));
    const dataset = () => page.evaluate(() => ({ ...document.documentElement.dataset }));
    const frames = async () => Number((await dataset()).frames ?? 0);
    const framesAtLeast = (n) => page.waitForFunction((want) => Number(document.documentElement.dataset.frames ?? 0) >= want, n, { timeout: 30_000 });
    const gpuShot = async (name) => {
      const png = await page.locator('#view-gpu').screenshot();
      writeFileSync(join(artifacts, `demo-${name}.png`), png);
      return analyze(page, png);
    };
    const start = async (query) => {
      await page.goto(url + query);
      await page.waitForFunction(() => window.subsurfReady === true && document.documentElement.dataset.gpu, null, { timeout: 60_000 });
      const data = await dataset();
      assert.equal(data.gpu, 'off', `WebGPU is available (${await page.locator('#gpu-note').textContent()})`);
      assert.ok(!(await page.locator('#gpu').isDisabled()), 'the GPU toggle is enabled');
      assert.equal(data.normals, 'limit');
      await page.check('#animate');
      await page.check('#gpu');
      await page.waitForFunction(() => document.documentElement.dataset.gpu === 'on', null, { timeout: 30_000 });
      await framesAtLeast((await frames()) + 10);
      assert.ok(await page.locator('#view-gpu').isVisible(), 'the WebGPU canvas is shown');
      await page.waitForFunction(() => document.documentElement.dataset.gpuMs !== undefined, null, { timeout: 30_000 });
    };

    await start('');
    assert.equal((await dataset()).gpuTiming, 'timestamp-query', 'SwiftShader has timestamp queries');
    const pictures = [await gpuShot('webgpu-1')];
    await framesAtLeast((await frames()) + 5);
    pictures.push(await gpuShot('webgpu-2'));
    for (const picture of pictures) {
      const share = picture.mesh / picture.total;
      assert.ok(share > 0.05 && share < 0.9, `the WebGPU canvas shows the mesh (${(100 * share).toFixed(1)}% of it)`);
      assert.ok(picture.shades >= 4, `the WebGPU surface is shaded (${picture.shades} shades)`);
    }
    assert.notEqual(pictures[0].hash, pictures[1].hash, 'the WebGPU surface moves');
    // The GPU evaluator's output for a deformed cage equals the CPU evaluator's (read back here
    // for the test only; the page draws from the buffers).
    const agreement = await page.evaluate(async () => {
      const animator = window.subsurfDemo.animator;
      // A cage of its own (the frame's, stretched and moved), so that the buffers cannot hold it already.
      const cage = animator.prepared.deformed.map((x, i) => 1.3 * x + (i % 3 === 1 ? 0.25 : 0));
      const cpu = animator.prepared.evaluator.evaluate(cage);
      const gpu = animator.gpuState.evaluator;
      gpu.evaluate(cage);
      const back = await gpu.readBack(); // submitted before this task yields: no frame comes between
      const worst = (a, b) => a.reduce((m, x, i) => Math.max(m, Math.abs(x - b[i])), 0);
      return {
        vertices: gpu.numVertices, hasNormals: gpu.hasNormals, positions: worst(cpu.positions, back.positions), normals: worst(cpu.normals, back.normals),
      };
    });
    assert.equal(agreement.vertices, 98);
    assert.ok(agreement.hasNormals, 'the GPU evaluator computes the limit normals');
    assert.ok(agreement.positions < 1e-5 && agreement.normals < 1e-4, `GPU and CPU frames agree (${JSON.stringify(agreement)})`);
    const gpuMs = Number((await dataset()).gpuMs);
    assert.ok(Number.isFinite(gpuMs) && gpuMs >= 0, `data-gpu-ms is a number (${gpuMs})`);
    assert.match(await page.locator('#frame-times').textContent(), /GPU: \d+\.\d\d ms\/frame/);
    await framesAtLeast((await frames()) + 60);
    report.gpuMs = Number((await dataset()).gpuMs);
    console.log(`  animate (WebGPU, SwiftShader): ${await frames()} frames so far, ${await page.locator('#frame-times').textContent()} ` +
      `(cube level 2; GPU time from timestamp queries); GPU vs CPU frame within ${agreement.positions.toExponential(1)}`);

    // The GPU toggle off: the CPU path draws the animation on the WebGL canvas again.
    await page.uncheck('#gpu');
    await page.waitForFunction(() => document.documentElement.dataset.gpu === 'off');
    const cpuFrom = Number((await dataset()).frames);
    await framesAtLeast(cpuFrom + 10);
    assert.ok(await page.locator('#view-gpu').isHidden(), 'the WebGPU canvas is hidden on the CPU path');

    // Without timestamp queries the GPU time comes from onSubmittedWorkDone.
    await start('?gpu-timing=work-done');
    assert.equal((await dataset()).gpuTiming, 'submitted-work-done');
    await page.waitForFunction(() => Number(document.documentElement.dataset.gpuMs) > 0, null, { timeout: 30_000 });
    await framesAtLeast((await frames()) + 60);
    report.gpuWorkDoneMs = Number((await dataset()).gpuMs);
    console.log(`  animate (WebGPU, onSubmittedWorkDone timing): ${await page.locator('#frame-times').textContent()}`);
    assert.ok((await gpuShot('webgpu-work-done')).shades >= 4, 'the WebGPU surface is drawn');
  } finally {
    await browser.close();
  }
}

function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted.length ? sorted[Math.floor(sorted.length / 2)] : NaN;
}

const started = Date.now();
try {
  await run();
  if (!process.exitCode) console.log(`e2e demo: ok (${((Date.now() - started) / 1000).toFixed(1)} s; screenshots in artifacts/)`);
} catch (error) {
  fail(error.stack ?? error);
}
