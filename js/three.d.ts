// subsurf/three: subdivision of a three.js BufferGeometry. The three.js types come from
// @types/three (install it beside three for TypeScript).
import type { BufferGeometry } from 'three';
import type { SubdivideOptions, SubdivideProgress } from './subsurf.js';
import type { SubsurfWorker } from './worker.js';

/** Thresholds of `quads` (Blender's "Tris to Quads"), in radians. */
export interface QuadJoinOptions {
  /** The largest angle between the normals of the two triangles joined. Default 40° (0.698). */
  faceAngle?: number;
  /**
   * The largest angle between the normals of the two triangles of the quad's other diagonal (a
   * skinny or folded quad exceeds it). Default 40° (0.698).
   */
  shapeAngle?: number;
}

/**
 * Every option of `subdivide` (scheme, levels, boundary, fvarLinear, limit, creases, corners,
 * holes, maxFaces, ...), and those of the geometry adapter. `creases` and `corners` name vertices
 * of the input geometry (values of its index), `holes` its triangles (index offset / 3).
 * `onProgress` is told after each level of the surface's subdivision, once per level.
 */
export interface SubdivideGeometryOptions extends Omit<SubdivideOptions, 'normals'> {
  /**
   * Positions nearer than this distance are welded into one vertex (a grid of this
   * cell size; each position joins the nearest earlier one within the distance). Default 0:
   * only bit-identical positions are welded.
   */
  weld?: number;
  /**
   * Join pairs of triangles into quads before subdividing (Blender's "Tris to Quads": greedy by
   * its join error, never across a crease, a UV or other face-varying seam, a group boundary or a
   * hole; consecutive triangles first, as exporters write a quad's two). A triangulated quad
   * mesh gets its own quads back where they pass the thresholds. Needs a scheme whose first level takes
   * quads ('catmull-clark', 'quad-triangle', 'bilinear', 'doo-sabin'). Default false.
   */
  quads?: boolean | QuadJoinOptions;
  /** Edges whose faces' normals differ by more than this angle (radians) become sharp creases. */
  creaseAngle?: number;
  /**
   * Edges where the input split its vertices because their `normal`s differ (by more than about
   * 1°, at both ends) become sharp creases: a flat-shaded glTF keeps its hard edges. Default false.
   */
  sharpNormalSplits?: boolean;
  /**
   * The output `normal` attribute: `true` (default) the limit surface's normals (subdivide's
   * `normals: true`; with `limit: true` the points are on the limit surface too), `'faces'` the
   * area-weighted normals of the refined faces, `false` none. Along sharp creases each side gets
   * its own normal, from its faces.
   */
  normals?: boolean | 'faces';
}

/**
 * Subdivides a triangle `BufferGeometry` (indexed or not) and returns a new indexed
 * `BufferGeometry`; the input is never modified. Vertices with bit-identical positions are
 * welded first (undoing glTF's seam splits); attributes that differ between welded copies (uv,
 * color, ...) are refined as face-varying data, the others vertex-varying; `normal` is
 * recomputed (see `normals`), `tangent` dropped (call `computeTangents()` on the result);
 * `skinIndex`/`skinWeight` are interpolated as weights and cut to the four largest,
 * renormalised; `morphAttributes` are carried (relative ones stay relative), `groups` keep their
 * faces. Throws an Error naming the problem for bad input.
 *
 * Ready on import from 'subsurf/three' (Node, bundlers, plain pages); from 'subsurf/three/init', call
 * `await init()` from 'subsurf/init' once before.
 */
export function subdivideGeometry(geometry: BufferGeometry, options?: SubdivideGeometryOptions): BufferGeometry;

/** Where and how `subdivideGeometryAsync` runs. */
export interface SubdivideGeometryCall {
  /**
   * The thread to run in: `createWorker()` of 'subsurf/worker' (or one started with `spawn`
   * whose table spreads `functions` of 'subsurf/worker-thread'). Required: the worker is yours
   * to share with other calls and to `terminate()`. Calls on one worker run one at a time.
   */
  worker: SubsurfWorker;
  /**
   * Aborting it rejects the call with the signal's reason (a `DOMException` named 'AbortError').
   * A running call's thread is terminated and a fresh one started for the worker's next call.
   */
  signal?: AbortSignal;
  /**
   * Told after each level of the subdivision, `{ level, levels, faces, vertices }`, levels in
   * order (the extra passes for morph normals tell nothing). Wins over `options.onProgress`.
   * What it throws rejects the call with that.
   */
  onProgress?: (progress: SubdivideProgress) => void;
}

/**
 * `subdivideGeometry` with its work in a worker thread, so the page stays responsive: the same
 * `BufferGeometry`, attribute for attribute and byte for byte. The geometry is read on the
 * calling thread (copies of its arrays go to the worker; the input is never modified or
 * detached), the result's arrays come back transferred. Bad input rejects with the `Error`
 * `subdivideGeometry` would throw. Imported from 'subsurf/three/init' it needs no `init()` on the
 * page: the worker instantiates its own wasm.
 */
export function subdivideGeometryAsync(
  geometry: BufferGeometry,
  options: SubdivideGeometryOptions | undefined,
  call: SubdivideGeometryCall,
): Promise<BufferGeometry>;
