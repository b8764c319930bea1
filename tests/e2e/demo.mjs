// End-to-end test of the demo page in headless Chromium (Playwright, playwright-core):
//   node tests/e2e/demo.mjs          (after scripts/build-pkg.sh)
// Serves www/ (with /pkg/ mapped to the freshly built pkg/) on a free port, loads the page,
// checks that the canvas shows a shaded mesh, changes the level with the keyboard and the
// slider and checks the face and vertex counts (cube level L: 6·4^L faces, 6·4^L + 2 vertices),
// orbits with a mouse drag, and saves screenshots into artifacts/. Exits non-zero on failure.
import assert from 'node:assert/strict';
import { createServer } from 'node:http';
import { mkdirSync, readFileSync, existsSync, statSync } from 'node:fs';
import { dirname, extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const artifacts = join(root, 'artifacts');
const CHROMIUM = process.env.CHROMIUM ?? '/usr/bin/chromium';
const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.wasm': 'application/wasm',
  '.css': 'text/css; charset=utf-8',
  '.json': 'application/json',
  '.ts': 'text/plain; charset=utf-8',
};

/** A static server for www/, with /pkg/ served from the built package. */
function serve() {
  const server = createServer((request, response) => {
    const path = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    const [base, rest] = path.startsWith('/pkg/') ? [join(root, 'pkg'), path.slice(5)] : [join(root, 'www'), path.slice(1)];
    let file = normalize(join(base, rest || 'index.html'));
    if (file !== base && !file.startsWith(base + sep)) return void response.writeHead(403).end();
    if (existsSync(file) && statSync(file).isDirectory()) file = join(file, 'index.html');
    if (!existsSync(file)) return void response.writeHead(404).end('not found');
    response.writeHead(200, { 'content-type': TYPES[extname(file)] ?? 'application/octet-stream', 'cache-control': 'no-store' });
    response.end(readFileSync(file));
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

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
    let hash = 0;
    const shades = new Set();
    for (let i = 0; i < data.length; i += 4) {
      const difference = Math.abs(data[i] - background[0]) + Math.abs(data[i + 1] - background[1]) + Math.abs(data[i + 2] - background[2]);
      if (difference > 30) {
        mesh++;
        shades.add(data[i] >> 3);
        hash = (hash * 31 + (i >> 2)) | 0;
      }
    }
    return { total: data.length / 4, mesh, shades: shades.size, hash, background };
  }, png.toString('base64'));
}

function fail(message) {
  console.error(`e2e demo: FAILED ${message}`);
  process.exitCode = 1;
}

const expectedCounts = (level) => ({ faces: 6 * 4 ** level, vertices: 6 * 4 ** level + 2 });

async function run() {
  if (!existsSync(join(root, 'pkg', 'subsurf_bg.wasm'))) throw new Error('pkg/ is not built; run scripts/build-pkg.sh');
  mkdirSync(artifacts, { recursive: true });
  const server = await serve();
  const url = `http://127.0.0.1:${server.address().port}/`;
  const browser = await chromium.launch({
    executablePath: CHROMIUM,
    headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const problems = [];
  try {
    const page = await browser.newPage({ viewport: { width: 1000, height: 700 } });
    page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
    page.on('console', (message) => message.type() === 'error' && problems.push(`console error: ${message.text()}`));
    page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()}`));

    await page.goto(url);
    await page.waitForFunction(() => window.subsurfReady === true || document.documentElement.dataset.error, null, { timeout: 30_000 });
    const error = await page.evaluate(() => document.documentElement.dataset.error);
    assert.equal(error, undefined, `the page reported an error: ${error}`);

    const canvas = page.locator('#view');
    const showLevel = async (level) => {
      const { faces, vertices } = expectedCounts(level);
      await page
        .waitForFunction((f) => document.documentElement.dataset.faces === String(f), faces, { timeout: 15_000 })
        .catch(async () => {
          const shown = await page.evaluate(() => ({ ...document.documentElement.dataset }));
          throw new Error(`level ${level}: expected ${faces} faces drawn; the page says ${JSON.stringify(shown)}`);
        });
      assert.equal(await page.locator('#faces').textContent(), faces.toLocaleString('en-US'), `faces shown at level ${level}`);
      assert.equal(await page.locator('#vertices').textContent(), vertices.toLocaleString('en-US'), `vertices shown at level ${level}`);
      assert.equal(await page.locator('#level-value').textContent(), String(level));
      const png = await canvas.screenshot({ path: join(artifacts, `demo-level${level}.png`) });
      const pixels = await analyze(page, png);
      const share = pixels.mesh / pixels.total;
      console.log(`  level ${level}: ${faces} faces, ${vertices} vertices; mesh covers ${(100 * share).toFixed(1)}% of the canvas in ${pixels.shades} shades`);
      assert.ok(share > 0.05 && share < 0.9, `level ${level}: mesh pixels ${(100 * share).toFixed(1)}% of the canvas`);
      assert.ok(pixels.shades >= 3, `level ${level}: only ${pixels.shades} shades; the mesh should be shaded`);
      return pixels;
    };

    // The page starts at level 1.
    const level1 = await showLevel(1);

    // Keyboard on the slider, as a user would: two steps right.
    await page.locator('#level').focus();
    await page.keyboard.press('ArrowRight');
    await page.keyboard.press('ArrowRight');
    const level3 = await showLevel(3);
    assert.notEqual(level3.hash, level1.hash, 'the image changes between levels 1 and 3');

    // The slider's ends.
    for (const level of [5, 0]) {
      await page.locator('#level').evaluate((input, value) => {
        input.value = value;
        input.dispatchEvent(new Event('input', { bubbles: true }));
      }, String(level));
      await showLevel(level);
    }

    // Orbit: a drag must change the picture.
    await page.locator('#level').evaluate((input) => {
      input.value = '2';
      input.dispatchEvent(new Event('input', { bubbles: true }));
    });
    const before = await showLevel(2);
    const box = await canvas.boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2 + 40, { steps: 8 });
    await page.mouse.up();
    await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
    const after = await analyze(page, await canvas.screenshot({ path: join(artifacts, 'demo-orbit.png') }));
    assert.notEqual(after.hash, before.hash, 'dragging the mouse orbits the view');
    assert.ok(after.mesh / after.total > 0.05, 'the mesh is still visible after orbiting');
    await page.screenshot({ path: join(artifacts, 'demo-page.png') });
  } finally {
    await browser.close();
    server.close();
  }
  for (const problem of problems) fail(problem);
}

const started = Date.now();
try {
  await run();
  if (!process.exitCode) console.log(`e2e demo: ok (${((Date.now() - started) / 1000).toFixed(1)} s; screenshots in artifacts/)`);
} catch (error) {
  fail(error.stack ?? error);
}
