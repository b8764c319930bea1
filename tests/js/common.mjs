// What tests/js/three.mjs and gltf.mjs share: the built package installed beside three as a
// user's project has it, checks that stop at the first failure, and the glTF-style triangulation
// of a mesh with UVs.
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

/** The repository's root. */
export const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');

/**
 * Installs pkg/'s `files` into node_modules/subsurf of a temporary project (removed at exit),
 * symlinks `links` (package name -> directory, e.g. { three: join(root, 'node_modules', 'three') })
 * beside it, writes `consumer` there as consumer.mjs (a module of the project's) and imports it.
 * Returns { scratch, installed, manifest, consumer }: the project's directory, node_modules/subsurf,
 * the package's package.json and the imported consumer module.
 */
export async function installPackage({ prefix, links, consumer }) {
  const pkgDir = join(root, 'pkg');
  const manifest = JSON.parse(readFileSync(join(pkgDir, 'package.json'), 'utf8'));
  const scratch = mkdtempSync(join(tmpdir(), prefix));
  process.on('exit', () => rmSync(scratch, { recursive: true, force: true }));
  const installed = join(scratch, 'node_modules', 'subsurf');
  mkdirSync(installed, { recursive: true });
  for (const file of [...manifest.files, 'package.json']) cpSync(join(pkgDir, file), join(installed, file));
  for (const [name, dir] of Object.entries(links)) {
    const link = join(scratch, 'node_modules', name);
    mkdirSync(dirname(link), { recursive: true });
    symlinkSync(dir, link, 'dir');
  }
  writeFileSync(join(scratch, 'package.json'), JSON.stringify({ type: 'module' }));
  writeFileSync(join(scratch, 'consumer.mjs'), consumer);
  return { scratch, installed, manifest, consumer: await import(pathToFileURL(join(scratch, 'consumer.mjs')).href) };
}

/**
 * Checks for the test named `label` that stop at the first failure: `await check(name, fn)` runs
 * fn, prints "label: name: detail" when it returns a detail, and on a throw prints "label: FAILED
 * name" and the error and exits 1. finish(note) prints "label: ok (N checks; note; T s)".
 */
export function checks(label) {
  const started = performance.now();
  let passed = 0;
  async function check(name, fn) {
    try {
      const detail = await fn();
      if (detail) console.log(`${label}: ${name}: ${detail}`);
      passed++;
    } catch (error) {
      console.error(`${label}: FAILED ${name}\n${error.stack ?? error}`);
      process.exit(1);
    }
  }
  function finish(note) {
    const seconds = ((performance.now() - started) / 1000).toFixed(1);
    console.log(`${label}: ok (${passed} checks; ${note ? `${note}; ` : ''}${seconds} s)`);
  }
  return { check, finish };
}

/**
 * An indexed subsurf mesh with a uv channel, triangulated as a glTF exporter does: a quad f split
 * along the diagonal from its corner diagonal(f) (0 or 1; 0 by default), other faces fanned from
 * their first corner.
 */
export function triangulated(mesh, diagonal = () => 0) {
  const uv = mesh.attributes.uv;
  const indices = [], uvIndices = [];
  let c = 0;
  mesh.faceSizes.forEach((n, f) => {
    const r = n === 4 ? diagonal(f) : 0;
    for (let i = 1; i + 1 < n; i++) {
      for (const k of [r, (r + i) % n, (r + i + 1) % n]) {
        indices.push(mesh.indices[c + k]);
        uvIndices.push(uv.indices[c + k]);
      }
    }
    c += n;
  });
  return {
    positions: mesh.positions,
    indices: Uint32Array.from(indices),
    faceSizes: new Uint32Array(indices.length / 3).fill(3),
    attributes: { uv: { array: uv.array, itemSize: 2, indices: Uint32Array.from(uvIndices) } },
  };
}
