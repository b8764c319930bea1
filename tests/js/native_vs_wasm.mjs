// Native vs wasm: runs the built npm package (pkg/, from scripts/build-pkg.sh) on the seeded
// random meshes that the native test `native_vs_wasm_fixture` (tests/properties.rs) wrote with
// its own results, and compares: face lists exactly, positions within the fixture's relative
// tolerance (1e-6 of max(|a|, |b|, 1)).
//
//   cargo test --release --test properties native_vs_wasm_fixture
//   node tests/js/native_vs_wasm.mjs [artifacts/native-vs-wasm.json]
//
// Exits non-zero on a missing fixture or any disagreement; closes with "N passed, N failed".
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..', '..');
const fixturePath = process.argv[2] ?? join(root, 'artifacts', 'native-vs-wasm.json');
if (!existsSync(fixturePath)) {
  console.error(`native_vs_wasm: ${fixturePath} is missing; run the native test native_vs_wasm_fixture first`);
  process.exit(1);
}
const { subdivide } = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);
const fixture = JSON.parse(readFileSync(fixturePath, 'utf8'));
const tolerance = fixture.tolerance;

const floats = (bits) => new Float32Array(new Uint32Array(bits).buffer);

function compare(name, native, wasm) {
  for (const key of ['indices', 'faceSizes']) {
    const a = native[key];
    const b = wasm[key];
    if (a.length !== b.length) return `${key}: ${a.length} entries natively, ${b.length} in wasm`;
    for (let i = 0; i < a.length; i++) {
      if (a[i] !== b[i]) return `${key}[${i}]: ${a[i]} natively, ${b[i]} in wasm`;
    }
  }
  const a = floats(native.positionBits);
  const b = wasm.positions;
  if (a.length !== b.length) return `positions: ${a.length} natively, ${b.length} in wasm`;
  let worst = 0;
  for (let i = 0; i < a.length; i++) {
    const scale = Math.max(Math.abs(a[i]), Math.abs(b[i]), 1);
    const error = Math.abs(a[i] - b[i]) / scale;
    if (!(error <= tolerance)) {
      return `positions[${i}] (vertex ${Math.floor(i / 3)}): ${a[i]} natively, ${b[i]} in wasm`;
    }
    worst = Math.max(worst, error);
  }
  maxError = Math.max(maxError, worst);
  return null;
}

let passed = 0;
let failed = 0;
let maxError = 0;
for (const c of fixture.cases) {
  const input = {
    positions: floats(c.input.positionBits),
    indices: new Uint32Array(c.input.indices),
    faceSizes: new Uint32Array(c.input.faceSizes),
  };
  let problem;
  try {
    problem = compare(c.name, c.native, subdivide(input, c.options));
  } catch (error) {
    problem = `wasm threw: ${error.message}`;
  }
  if (problem) {
    failed++;
    console.error(`native_vs_wasm: FAILED ${c.name} ${JSON.stringify(c.options)}: ${problem}`);
  } else {
    passed++;
  }
}
if (fixture.cases.length === 0) failed++;
console.log(`native_vs_wasm: ${fixture.cases.length} cases, largest relative difference ${maxError}`);
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
