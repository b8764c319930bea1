// What the end-to-end tests in tests/e2e/ share: a static file server, headless Chromium, and
// a counter of checks.
//   const { origin, close } = await serveStatic({ routes: { '/pkg/': pkg }, pages: { '/': PAGE } });
//   const browser = await launchChromium({ args: SWIFTSHADER_WEBGL });
//   const errors = collectErrors(page);
//   const { check, finish } = checks('three e2e');  check(name, ok, detail) ...  finish();
import { createServer } from 'node:http';
import { existsSync, readFileSync, statSync } from 'node:fs';
import { dirname, extname, join, normalize, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

/** The repository's root. */
export const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
/** The built package: pkg/, or PKG_DIR. */
export const pkg = process.env.PKG_DIR ?? join(root, 'pkg');

const TYPES = {
  '.html': 'text/html; charset=utf-8',
  '.js': 'text/javascript; charset=utf-8',
  '.mjs': 'text/javascript; charset=utf-8',
  '.css': 'text/css; charset=utf-8',
  '.wasm': 'application/wasm',
  '.json': 'application/json',
  '.ts': 'text/plain; charset=utf-8',
};
const typeOf = (path) => TYPES[extname(path) || '.html'] ?? 'application/octet-stream';
const NOT_FOUND = { status: 404, type: 'text/plain', body: 'not found' };

/**
 * Serves, on 127.0.0.1 and a free port, `pages` (path -> text, typed by the path's extension, an
 * extensionless path as HTML) and `routes` (URL prefix -> directory, the first prefix matching
 * decides; a directory's index.html stands for it, so { '/': www } serves www/ as a site).
 * Anything else is a 404; /favicon.ico a 204. Returns { origin, respond, close }: respond(path)
 * is the { status, type, body } the server answers a GET of the path with (for page.route).
 */
export async function serveStatic({ routes = {}, pages = {} }) {
  function respond(path) {
    if (Object.hasOwn(pages, path)) return { status: 200, type: typeOf(path), body: pages[path] };
    const prefix = Object.keys(routes).find((prefix) => path.startsWith(prefix));
    if (prefix !== undefined) {
      const dir = routes[prefix];
      let file = normalize(join(dir, path.slice(prefix.length)));
      if (file !== dir && !file.startsWith(dir + sep)) return NOT_FOUND;
      if (existsSync(file) && statSync(file).isDirectory()) file = join(file, 'index.html');
      if (existsSync(file) && !statSync(file).isDirectory()) return { status: 200, type: typeOf(file), body: readFileSync(file) };
    }
    if (path === '/favicon.ico') return { status: 204, type: 'image/x-icon', body: '' };
    return NOT_FOUND;
  }
  const server = createServer((request, response) => {
    const { status, type, body } = respond(decodeURIComponent(new URL(request.url, 'http://localhost').pathname));
    response.writeHead(status, { 'content-type': type, 'cache-control': 'no-store' });
    response.end(body);
  });
  await new Promise((resolve) => server.listen(0, '127.0.0.1', resolve));
  return { origin: `http://127.0.0.1:${server.address().port}`, respond, close: () => server.close() };
}

/** Flags for WebGL on SwiftShader (ANGLE), no GPU needed. */
export const SWIFTSHADER_WEBGL = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'];

/** Headless Chromium (CHROMIUM, or /usr/bin/chromium) with a quiet profile, plus the test's own `args`. */
export function launchChromium({ args = [] } = {}) {
  return chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    headless: true,
    args: ['--no-sandbox', ...args, '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync'],
  });
}

/** The page's errors and console errors (but those matching `except`), as they come. */
export function collectErrors(page, { except } = {}) {
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  page.on('console', (message) => {
    if (message.type() === 'error' && !except?.test(message.text())) errors.push(message.text());
  });
  return errors;
}

/**
 * A counter of checks for the test named `label`: check(name, ok, detail) prints "ok   name
 * (detail)" or "FAIL name (detail)" and returns ok; finish() prints "label: ok (N checks, T s)"
 * or "label: F of N check(s) FAILED" and then sets a non-zero exit code.
 */
export function checks(label) {
  const started = performance.now();
  let passed = 0;
  let failed = 0;
  function check(name, ok, detail) {
    console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail === undefined || detail === '' ? '' : ` (${detail})`}`);
    if (ok) passed++;
    else failed++;
    return ok;
  }
  function finish() {
    if (failed) {
      console.error(`${label}: ${failed} of ${passed + failed} check(s) FAILED`);
      process.exitCode = 1;
    } else {
      console.log(`${label}: ok (${passed} checks, ${((performance.now() - started) / 1000).toFixed(1)} s)`);
    }
  }
  return { check, finish };
}
