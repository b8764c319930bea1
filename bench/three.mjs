// subsurf/three against three-subdivide (the npm package three.js users use since three removed
// its SubdivisionModifier), on the same BufferGeometry, in Node:
//   - Loop at level 1 on a 300k-triangle TorusKnotGeometry (1000 x 150 segments, UV seams);
//   - Loop at level 2 on a 16k-triangle TorusKnotGeometry with UVs (256 x 32), three-subdivide
//     with `uvSmooth: true` (its UVs are otherwise not refined but copied linearly);
//   - Loop at level 2 on a glTF model with UVs: tests/fixtures/gltf/catmark_lefthanded.glb
//     (OpenSubdiv's hand, 868 triangles, UV seams between its islands; tools/gltf/make-fixtures.mjs)
//     read by three's GLTFLoader, its interleaved position/uv copied into plain attributes
//     (three-subdivide reads `.array`), the same input for both.
// three-subdivide runs with `split: false` (plain Loop; its default first splits coplanar
// triangles, which changes the mesh) and, for reference, with its defaults. subsurf runs
// subdivideGeometry with its defaults (limit normals, UVs face-varying) plus the scheme and levels.
// Time: calls rotating in one process, the first round left out as warm-up, best and median ms.
// Peak memory: each (case, library) once in a fresh child process, the growth of the process's
// peak resident set (VmHWM) over its value just before the call (after the input geometry is
// built and the modules are loaded): what the call needs at its peak, wasm memory included.
//   node bench/three.mjs [ROUNDS] [CASE...]   (needs pkg/: scripts/build-pkg.sh; CASE: a key of CASES, all by default)
import { spawnSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

import * as THREE from 'three';
// Its src/ ES module (the package's "main" is a UMD build that would load a second, CommonJS three).
import { LoopSubdivision } from 'three-subdivide/src/index.js';

import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const { subdivideGeometry } = await import(pathToFileURL(join(root, 'pkg', 'three-node.js')).href);

/** The first mesh's geometry of a .glb, read by GLTFLoader, with plain (not interleaved) attributes. */
async function gltfGeometry(file) {
  const bytes = readFileSync(join(root, file));
  const gltf = await new GLTFLoader().parseAsync(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength), '');
  const loaded = gltf.scene.getObjectByProperty('isMesh', true).geometry;
  const geometry = new THREE.BufferGeometry();
  for (const [name, a] of Object.entries(loaded.attributes)) {
    const array = new Float32Array(a.count * a.itemSize);
    for (let i = 0; i < a.count; i++) for (let k = 0; k < a.itemSize; k++) array[i * a.itemSize + k] = a.getComponent(i, k);
    geometry.setAttribute(name, new THREE.BufferAttribute(array, a.itemSize));
  }
  geometry.setIndex(new THREE.BufferAttribute(loaded.index.array.slice(), 1));
  return geometry;
}

const CASES = {
  'loop-300k-level1': {
    what: 'Loop, level 1, TorusKnotGeometry(1, 0.3, 1000, 150): 300,000 triangles',
    geometry: () => new THREE.TorusKnotGeometry(1, 0.3, 1000, 150),
    runs: {
      subsurf: (g) => subdivideGeometry(g, { scheme: 'loop', levels: 1 }),
      'three-subdivide': (g) => LoopSubdivision.modify(g, 1, { split: false }),
      'three-subdivide (split)': (g) => LoopSubdivision.modify(g, 1),
    },
  },
  'loop-uv-level2': {
    what: 'Loop, level 2, TorusKnotGeometry(1, 0.3, 256, 32) with UVs: 16,384 triangles',
    geometry: () => new THREE.TorusKnotGeometry(1, 0.3, 256, 32),
    runs: {
      subsurf: (g) => subdivideGeometry(g, { scheme: 'loop', levels: 2 }),
      'three-subdivide': (g) => LoopSubdivision.modify(g, 2, { split: false, uvSmooth: true }),
      'three-subdivide (split)': (g) => LoopSubdivision.modify(g, 2, { uvSmooth: true }),
      'subsurf, quads: true (Catmull-Clark)': (g) => subdivideGeometry(g, { levels: 2, quads: true }),
    },
  },
  'gltf-uv-level2': {
    what: 'Loop, level 2, a glTF model with UVs (tests/fixtures/gltf/catmark_lefthanded.glb): 868 triangles',
    geometry: () => gltfGeometry('tests/fixtures/gltf/catmark_lefthanded.glb'),
    runs: {
      subsurf: (g) => subdivideGeometry(g, { scheme: 'loop', levels: 2 }),
      'three-subdivide': (g) => LoopSubdivision.modify(g, 2, { split: false, uvSmooth: true }),
      'three-subdivide (split)': (g) => LoopSubdivision.modify(g, 2, { uvSmooth: true }),
      'subsurf, quads: true (Catmull-Clark)': (g) => subdivideGeometry(g, { levels: 2, quads: true }),
    },
  },
};

/**
 * The process's peak resident set in kB: Linux's VmHWM (of this process image; getrusage's
 * maxRSS would carry the spawning parent's peak over exec), elsewhere maxRSS.
 */
function peakKb() {
  try {
    return Number(readFileSync('/proc/self/status', 'utf8').match(/^VmHWM:\s+(\d+) kB/m)[1]);
  } catch {
    return process.resourceUsage().maxRSS;
  }
}

if (process.argv[2] === '--peak') {
  // Child: one call, and the peak RSS it added.
  const [name, lib] = process.argv.slice(3);
  const c = CASES[name];
  const geometry = await c.geometry();
  if (global.gc) global.gc();
  const before = peakKb();
  const out = c.runs[lib](geometry);
  const after = peakKb();
  console.log(JSON.stringify({ kb: after - before, triangles: (out.index ? out.index.count : out.getAttribute('position').count) / 3 }));
  process.exit(0);
}

const rounds = Math.max(2, Number(process.argv[2] ?? 5));
const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const mb = (kb) => (kb / 1024).toFixed(0);
console.log(`node ${process.version}, three ${THREE.REVISION}, ${rounds} rounds (the first left out)`);
const only = process.argv.slice(3);
for (const name of only) if (!CASES[name]) throw new Error(`unknown case '${name}'; cases: ${Object.keys(CASES).join(', ')}`);
for (const [name, c] of Object.entries(CASES)) {
  if (only.length && !only.includes(name)) continue;
  console.log(`\n${c.what}`);
  const geometry = await c.geometry();
  const libs = Object.keys(c.runs);
  const times = Object.fromEntries(libs.map((l) => [l, []]));
  const triangles = {};
  for (let r = 0; r < rounds; r++) {
    for (const lib of libs) {
      const start = performance.now();
      const out = c.runs[lib](geometry);
      const ms = performance.now() - start;
      if (r > 0) times[lib].push(ms);
      triangles[lib] = (out.index ? out.index.count : out.getAttribute('position').count) / 3;
      out.dispose();
    }
  }
  const rows = libs.map((lib) => {
    const child = spawnSync(process.execPath, ['--expose-gc', fileURLToPath(import.meta.url), '--peak', name, lib], { encoding: 'utf8' });
    if (child.status !== 0) throw new Error(`${lib}: ${child.stderr}`);
    const { kb } = JSON.parse(child.stdout.trim().split('\n').pop());
    return { lib, best: Math.min(...times[lib]), median: median(times[lib]), kb };
  });
  const ours = rows[0];
  for (const row of rows) {
    console.log(`  ${row.lib.padEnd(38)} ${String(triangles[row.lib]).padStart(9)} triangles  best ${row.best.toFixed(0).padStart(6)} ms` +
      `  median ${row.median.toFixed(0).padStart(6)} ms  peak +${mb(row.kb).padStart(5)} MB` +
      (row === ours ? '' : `  (time ${(row.median / ours.median).toFixed(1)}x, memory ${(row.kb / ours.kb).toFixed(1)}x subsurf's)`));
  }
}
