// How far the limit normals of each evaluation path are from the true limit normals of the
// same f32 control points. The reference: the evaluator's composed limit table (`stencils()`,
// rows down to the control points) summed in f64, each tangent on differences from its row's
// first control point. Against it:
// - the CPU evaluator's frame (`evaluate`: the closed forms where they apply, which step the
//   levels in f32 and take the tangents from the last level's points);
// - `subdivide` with `limit` and `normals` (the same closed forms on closed cages);
// - the GPU evaluator's sums (`subsurf/webgpu`'s contract, emulated here in f32: each product and
//   sum rounded, tangents on differences from the row's first control point), on the composed
//   table, and on `levelStencils()` run in turn.
// Prints the largest difference of a normal's component (unit normals: about the angle in
// radians) and how many components differ by more than 1e-5. Figures, not assertions.
//
//   HORSE=/path/horse.obj node bench/normals_accuracy.mjs     (after scripts/build-pkg.sh)
//
// Without $HORSE (or bench/meshes/horse.obj), the built-in torus and icosahedron only.
import { existsSync, readFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const root = join(dirname(fileURLToPath(import.meta.url)), '..');
const S = await import(pathToFileURL(join(root, 'pkg', 'node.js')).href);

/** A table's positions and unit normals, each product and sum rounded by `round`. */
function sumTable({ offsets, indices, weights, tangentWeights }, control, round) {
  const n = offsets.length - 1;
  const positions = new Float64Array(3 * n);
  const normals = new Float64Array(3 * n);
  const [w1, w2] = tangentWeights ?? [];
  for (let i = 0; i < n; i++) {
    const p = [0, 0, 0], a = [0, 0, 0], b = [0, 0, 0];
    const first = offsets[i] < offsets[i + 1] ? 3 * indices[offsets[i]] : 0;
    for (let k = offsets[i]; k < offsets[i + 1]; k++) {
      const c = 3 * indices[k];
      for (let j = 0; j < 3; j++) {
        p[j] = round(p[j] + round(weights[k] * control[c + j]));
        if (!tangentWeights) continue;
        const d = round(control[c + j] - control[first + j]);
        a[j] = round(a[j] + round(w1[k] * d));
        b[j] = round(b[j] + round(w2[k] * d));
      }
    }
    const cross = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const length = Math.hypot(...cross);
    for (let j = 0; j < 3; j++) {
      positions[3 * i + j] = p[j];
      normals[3 * i + j] = length > 0 ? cross[j] / length : 0;
    }
  }
  return { positions, normals };
}

function difference(actual, expected) {
  let worst = 0;
  let over = 0;
  for (let i = 0; i < expected.length; i++) {
    const d = Math.abs(actual[i] - expected[i]);
    worst = Math.max(worst, d);
    if (d > 1e-5) over++;
  }
  return `${worst.toExponential(1)} (${over.toLocaleString('en-US')})`;
}

const meshes = [['torus (built in)', S.shape('torus')], ['icosahedron (built in)', S.shape('icosahedron')]];
const horse = process.env.HORSE ?? join(root, 'bench', 'meshes', 'horse.obj');
if (existsSync(horse)) meshes.push(['horse', S.readObj(readFileSync(horse, 'utf8'))]);

console.log('| mesh | scheme, level | normals | evaluate | subdivide | GPU sums, composed table | GPU sums, level tables |');
console.log('|---|---|---|---|---|---|---|');
for (const [name, m] of meshes) {
  const mesh = { positions: m.positions, indices: m.indices, faceSizes: m.faceSizes };
  const triangles = !mesh.faceSizes || mesh.faceSizes.every((s) => s === 3);
  for (const scheme of triangles ? ['catmull-clark', 'loop'] : ['catmull-clark']) {
    for (const levels of [1, 2]) {
      const options = { scheme, levels, limit: true, normals: true };
      const base = new S.BaseMesh(mesh);
      const evaluator = base.evaluator(options);
      const truth = sumTable(evaluator.stencils(), mesh.positions, (x) => x).normals;
      const gpu = sumTable(evaluator.stencils(), mesh.positions, Math.fround).normals;
      let points = mesh.positions;
      let chain;
      for (const table of evaluator.levelStencils()) {
        chain = sumTable(table, points, Math.fround);
        points = Float32Array.from(chain.positions);
      }
      const cpu = evaluator.evaluate(mesh.positions).normals;
      const sub = S.subdivide(mesh, options).normals;
      console.log(`| ${name} | ${scheme} ${levels} | ${evaluator.numVertices.toLocaleString('en-US')} | ` +
        `${difference(cpu, truth)} | ${difference(sub, truth)} | ${difference(gpu, truth)} | ${difference(chain.normals, truth)} |`);
      evaluator.free();
      base.free();
    }
  }
}
console.log('\nEach cell: the largest difference of a normal component from the f64 sums of the composed table, and (in brackets) how many components differ by more than 1e-5.');
