// subsurf/worker and subsurf/worker-thread as a TypeScript consumer uses them: compiled by
// tests/js/pkg_smoke.mjs with the pinned `tsc` (strict), beside types_check.ts. Each
// `@ts-expect-error` marks a misuse the types must refuse.
import type { SubdivideProgress, SubdivideResult } from 'subsurf';
import { createWorker, type SubsurfWorker } from 'subsurf/worker';
import { expose, functions, type CallContext } from 'subsurf/worker-thread';

const cube = { positions: new Float32Array(24), indices: new Uint32Array(24), faceSizes: new Uint32Array(6).fill(4) };

const worker: SubsurfWorker = createWorker();
const controller = new AbortController();
const levels: number[] = [];
const out: SubdivideResult = await worker.subdivide(cube, { levels: 3 }, {
  signal: controller.signal,
  onProgress: (p: SubdivideProgress) => levels.push(p.level + p.levels + p.faces + p.vertices),
  transfer: true,
});
const text = await worker.call<string>('writeObj', [out]);
const shared = createWorker({ wasm: new URL('https://example.com/subsurf_bg.wasm') });
const fromModule = createWorker({ wasm: WebAssembly.compile(new Uint8Array(8)) });
const ownScript = createWorker({ spawn: () => new Worker(new URL('./my-worker.js', import.meta.url), { type: 'module' }) });
for (const w of [worker, shared, fromModule, ownScript]) w.terminate();

// A worker script of one's own.
expose({
  ...functions,
  twice([value]: [number], { progress }: CallContext) {
    progress?.({ half: value });
    return 2 * value;
  },
});

// @ts-expect-error: progress is told SubdivideProgress, which has no `percent`
worker.subdivide(cube, {}, { onProgress: (p) => p.percent });
// @ts-expect-error: a misspelt option still fails through the worker
worker.subdivide(cube, { level: 2 });
// @ts-expect-error: the signal must be an AbortSignal
worker.subdivide(cube, {}, { signal: controller });
// @ts-expect-error: call takes its arguments as an array
worker.call('readObj', 'v 0 0 0');

export const used = [text, levels];
