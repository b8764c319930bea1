// A TypeScript consumer of the installed package: tests/js/pkg_smoke.mjs copies it next to
// node_modules/subsurf and type-checks it with the pinned `tsc` (strict, no skipLibCheck), so
// the shipped declarations compile and say what the API accepts. Each `@ts-expect-error` marks a
// misuse the types must refuse: tsc fails if the line after it type-checks.
import init, { BaseMesh, Evaluator, readObj, shape, subdivide, toDrawable, type DrawableMesh, type EvaluatedFrame, type FVarLinearMode, type StencilArrays, type SubdivideResult } from 'subsurf';
import { subdivide as subdivideInNode } from 'subsurf/node';

await init();

const cube = {
  positions: new Float32Array(24),
  indices: new Uint32Array(24),
  faceSizes: new Uint32Array([4, 4, 4, 4, 4, 4]),
};
const out: SubdivideResult = subdivide(cube, { scheme: 'catmull-clark', levels: 2, boundary: 'edge-only' });
const triangles: Uint32Array = out.triangles;
const again: SubdivideResult = subdivide(cube, { levels: 2 }, out);
subdivideInNode(cube, { scheme: ['doo-sabin', 'loop'], creases: { edges: new Uint32Array([0, 1]), sharpness: new Float32Array([2]) } });

const colored = { ...cube, attributes: { color: { array: new Float32Array(24), itemSize: 3 } } };
const colors: Float32Array | undefined = subdivide(colored, { levels: 1 }).attributes?.color.array;

const base = new BaseMesh(colored);
base.setAttribute('color', new Float32Array(24));
const vertices: number = base.numVertices + base.numFaces;
const faces: Float64Array = base.predictCounts({ levels: 3 }).faces;
base.setPositions(new Float32Array(3 * vertices));
const moved: SubdivideResult = base.subdivide({ levels: 1 }, again);
base.free();

const obj = readObj('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n');
subdivide(obj, { ...obj.tags, levels: 1 });
const uvIndices: Uint32Array | undefined = obj.attributes?.uv.indices;

const mode: FVarLinearMode = 'boundaries';
const textured = shape('cube');
const refinedUv = subdivide(textured, { levels: 2, fvarLinear: mode });
const drawable: DrawableMesh = toDrawable(refinedUv);
const origins: Uint32Array = drawable.origins;
const uvs: Float32Array | undefined = drawable.attributes.uv?.array;

const limit: SubdivideResult = subdivide(cube, { levels: 2, limit: true, normals: true });
const limitNormals: Float32Array | undefined = limit.normals;
const evaluator: Evaluator = new BaseMesh(cube).evaluator({ levels: 2, limit: true, normals: true });
let frame: EvaluatedFrame = evaluator.evaluate(new Float32Array(24));
frame = evaluator.evaluate(new Float32Array(24), frame);
frame = evaluator.evaluateView(new Float32Array(24));
const frameNormals: Float32Array | undefined = frame.normals;
const table: StencilArrays = evaluator.stencils();
const tangents: [Float32Array, Float32Array] | undefined = table.tangentWeights;
const built: SubdivideResult = evaluator.result();
const colours: Float32Array = evaluator.evaluateAttribute(new Float32Array(24), 3);
const counts: number = evaluator.numVertices + evaluator.numControlVertices + evaluator.stencilBytes + evaluator.bytes;
const hasNormals: boolean = evaluator.hasNormals;
evaluator.free();

// @ts-expect-error: evaluate takes a Float32Array
evaluator.evaluate([0, 0, 0]);
// @ts-expect-error: limit is a boolean
subdivide(cube, { limit: 'yes' });
// @ts-expect-error: an unknown scheme name
subdivide(cube, { scheme: 'butterfly' });
// @ts-expect-error: positions must be a Float32Array
subdivide({ positions: [0, 0, 0], indices: new Uint32Array(3) });
// @ts-expect-error: a misspelt option
subdivide(cube, { level: 2 });
// @ts-expect-error: setPositions takes a Float32Array
base.setPositions([0, 0, 0]);
// @ts-expect-error: numFaces is read-only
base.numFaces = 3;
// @ts-expect-error: an attribute channel's array must be a Float32Array
subdivide({ ...cube, attributes: { color: { array: [0, 0, 0], itemSize: 3 } } });
// @ts-expect-error: setAttribute takes a Float32Array
base.setAttribute('color', [0, 0, 0]);
// @ts-expect-error: an unknown fvarLinear mode
subdivide(cube, { fvarLinear: 'linear' });
// @ts-expect-error: face-varying indices must be a Uint32Array
subdivide({ ...cube, attributes: { uv: { array: new Float32Array(8), itemSize: 2, indices: [0, 1, 2] } } });

export const used = [triangles, moved, faces, colors, uvIndices, origins, uvs, limitNormals, frameNormals, tangents, built, colours, counts, hasNormals];
