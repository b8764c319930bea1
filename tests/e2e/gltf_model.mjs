// A real textured glTF model through subsurf/three, in headless Chromium (WebGL on SwiftShader):
//   node tests/e2e/gltf_model.mjs                   (after scripts/build-pkg.sh)
//
// The model: models/pmndrs.glb of the npm package @pmndrs/assets (a pinned devDependency,
// CC0-1.0; the module's default export is the .glb as a data: URL), the pmndrs logo: one mesh,
// POSITION, TEXCOORD_0 and NORMAL compressed with KHR_draco_mesh_compression, a JPEG base colour
// texture. A page imports three, its GLTFLoader and DRACOLoader (the Draco decoder three ships,
// examples/jsm/libs/draco/gltf/) through an import map, and subsurf's web entry and
// subsurf/three; it loads the model and, for each mesh primitive, runs subdivideGeometry with
// Loop and with `quads: true` Catmull-Clark, at levels 1 and 2, and checks:
//   - the output has UVs, all within the input's UV bounding box (both schemes' weights are
//     positive, so every refined UV is a convex combination of input UVs);
//   - face counts: Loop 4^levels × the input's triangles; Catmull-Clark with quads, for some
//     number q of joined quads (one q for both levels), 2 × 4^(levels - 1) × (4q + 3(t - 2q))
//     triangles, and q > 0;
//   - watertight where the input is: welded by position, the output's boundary edges are
//     2^levels × the input's, in as many loops, every other edge used once each way;
//   - drawn by a real THREE.WebGLRenderer (orthographic, from the front, above and right;
//     MeshBasicMaterial, no lights), pixels read back. With the model's own texture: drawn,
//     more than one colour. With an 8 x 8 checker texture through the model's UVs (the model's
//     own is a baked ambient-occlusion map, nearly one grey): the subdivided model covers 85% to
//     101% of the pixels the input model covers (a subdivision surface shrinks towards the
//     inside of its cage; this model's blocks have support loops, so it hardly does), it is
//     textured (luminance spread over 20 of 255 and at least half the input's, where the same
//     surface untextured has none), and the texture lands where it does on the input (mean
//     difference from the input's render where both cover under 10%, against over twice that
//     with the UVs scrambled).
// Exits non-zero on failure.
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { SWIFTSHADER_WEBGL, checks, collectErrors, launchChromium, pkg, root, serveStatic } from './harness.mjs';

const three = join(root, 'node_modules', 'three');
const assets = join(root, 'node_modules', '@pmndrs', 'assets');
const MODEL = 'models/pmndrs.glb.js';
const PAGE = `<!doctype html><meta charset="utf-8"><title>subsurf glTF model test</title>
<script type="importmap">{ "imports": { "three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/" } }</script>
<body style="margin:0"></body>`;

const { check, finish } = checks('gltf_model e2e');
const version = JSON.parse(readFileSync(join(assets, 'package.json'), 'utf8')).version;
// / is the page, /pkg/ the built package, /three/ three, /assets/ the model package, /tests/
// the shared edge counts.
const server = await serveStatic({ pages: { '/': PAGE }, routes: { '/pkg/': pkg, '/three/': three, '/assets/': assets, '/tests/': join(root, 'tests', 'js') } });
const browser = await launchChromium({ args: SWIFTSHADER_WEBGL });
try {
  const page = await browser.newPage();
  const errors = collectErrors(page);
  await page.goto(`${server.origin}/`);
  const result = await page.evaluate(async (model) => {
    const THREE = await import('three');
    const { GLTFLoader } = await import('three/addons/loaders/GLTFLoader.js');
    const { DRACOLoader } = await import('three/addons/loaders/DRACOLoader.js');
    const { default: init } = await import('/pkg/subsurf.js');
    const { subdivideGeometry } = await import('/pkg/three.js');
    await init();
    const { default: url } = await import(`/assets/${model}`);
    const draco = new DRACOLoader().setDecoderPath('/three/examples/jsm/libs/draco/gltf/');
    const gltf = await new GLTFLoader().setDRACOLoader(draco).loadAsync(url);
    draco.dispose();

    const { edgeCounts: edges } = await import('/tests/edges.mjs');
    const uvBox = (geometry) => {
      const uv = geometry.getAttribute('uv');
      const box = [Infinity, Infinity, -Infinity, -Infinity];
      for (let i = 0; i < uv.count; i++) {
        box[0] = Math.min(box[0], uv.getX(i)); box[1] = Math.min(box[1], uv.getY(i));
        box[2] = Math.max(box[2], uv.getX(i)); box[3] = Math.max(box[3], uv.getY(i));
      }
      return box;
    };

    // The view: orthographic, from the front, above and to the right (sides and bevels show),
    // the model's bounding sphere filling it.
    const SIZE = 256;
    const box = new THREE.Box3().setFromObject(gltf.scene);
    const centre = box.getCenter(new THREE.Vector3()), radius = box.getSize(new THREE.Vector3()).length() / 2;
    const camera = new THREE.OrthographicCamera(-radius, radius, radius, -radius, 0.01, 4 * radius);
    camera.position.copy(centre).addScaledVector(new THREE.Vector3(1, 0.8, 1.6).normalize(), 2 * radius);
    camera.lookAt(centre);
    // An 8 x 8 checker (red/blue and yellow/white alternating), nearest filtering: through the
    // model's UVs it shows where every UV lands.
    const checker = new Uint8Array(4 * 64);
    for (let i = 0; i < 64; i++) checker.set(((i >> 3) + i) % 2 ? [255, 40, 40, 255] : i % 3 ? [40, 40, 255, 255] : [255, 255, 255, 255], 4 * i);
    const checkerMap = new THREE.DataTexture(checker, 8, 8);
    checkerMap.magFilter = checkerMap.minFilter = THREE.NearestFilter;
    checkerMap.needsUpdate = true;
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = SIZE;
    document.body.append(canvas);
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.setSize(SIZE, SIZE, false);
    renderer.setClearColor(0x000000, 0);
    /** RGBA pixels of the geometry drawn with the material, rows bottom up. */
    const draw = (geometry, material) => {
      const scene = new THREE.Scene();
      scene.add(new THREE.Mesh(geometry, material));
      renderer.render(scene, camera);
      const gl = renderer.getContext();
      const pixels = new Uint8Array(4 * SIZE * SIZE);
      gl.readPixels(0, 0, SIZE, SIZE, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      return pixels;
    };
    const luminance = (px, i) => 0.2126 * px[4 * i] + 0.7152 * px[4 * i + 1] + 0.0722 * px[4 * i + 2];
    /** Covered pixels (alpha 255) and their luminance's standard deviation. */
    const stats = (px) => {
      let n = 0, s = 0, s2 = 0;
      const colours = new Set();
      for (let i = 0; i < SIZE * SIZE; i++) {
        if (px[4 * i + 3] !== 255) continue;
        n++;
        const l = luminance(px, i);
        s += l; s2 += l * l;
        colours.add((px[4 * i] << 16) | (px[4 * i + 1] << 8) | px[4 * i + 2]);
      }
      return { covered: n, spread: n ? Math.sqrt(Math.max(0, s2 / n - (s / n) ** 2)) : 0, colours: colours.size };
    };
    /** Mean |RGB difference| / 255 over the pixels both cover. */
    const difference = (a, b) => {
      let n = 0, d = 0;
      for (let i = 0; i < SIZE * SIZE; i++) {
        if (a[4 * i + 3] !== 255 || b[4 * i + 3] !== 255) continue;
        n++;
        for (let k = 0; k < 3; k++) d += Math.abs(a[4 * i + k] - b[4 * i + k]);
      }
      return d / (3 * 255 * Math.max(1, n));
    };

    const meshes = [];
    gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
    const out = [];
    for (const mesh of meshes) {
      const g = mesh.geometry;
      const map = mesh.material.map;
      const record = {
        name: mesh.name, triangles: g.index ? g.index.count / 3 : g.getAttribute('position').count / 3,
        vertices: g.getAttribute('position').count, attributes: Object.keys(g.attributes).sort(),
        hasMap: !!map, mapSize: map ? [map.image.width, map.image.height] : null,
        inputEdges: edges(g), uvBox: uvBox(g), runs: [],
      };
      const own = new THREE.MeshBasicMaterial({ map, side: THREE.DoubleSide });
      const material = new THREE.MeshBasicMaterial({ map: checkerMap, side: THREE.DoubleSide });
      const inputPixels = draw(g, material);
      record.input = stats(inputPixels);
      record.inputOwn = stats(draw(g, own));
      for (const [label, options] of [['Loop', { scheme: 'loop' }], ['quads: true, Catmull-Clark', { quads: true }]]) {
        for (const levels of [1, 2]) {
          const start = performance.now();
          const s = subdivideGeometry(g, { ...options, levels });
          const ms = performance.now() - start;
          const run = { label, levels, ms, triangles: s.index.count / 3, hasUv: !!s.getAttribute('uv'), edges: edges(s) };
          if (run.hasUv) run.uvBox = uvBox(s);
          const px = draw(s, material);
          run.render = stats(px);
          run.own = stats(draw(s, own));
          run.difference = difference(px, inputPixels);
          if (levels === 2 && label === 'Loop') {
            // The same surface with its UVs scrambled (each vertex another's): must look different.
            const scrambled = s.clone();
            const uv = scrambled.getAttribute('uv');
            const copy = uv.array.slice();
            for (let i = 0; i < uv.count; i++) {
              const j = (i * 7919) % uv.count;
              uv.array[2 * i] = copy[2 * j];
              uv.array[2 * i + 1] = copy[2 * j + 1];
            }
            run.scrambledDifference = difference(draw(scrambled, material), inputPixels);
            run.flat = stats(draw(s, new THREE.MeshBasicMaterial({ color: 0xffffff, side: THREE.DoubleSide })));
          }
          record.runs.push(run);
        }
      }
      out.push(record);
    }
    return { renderer: renderer.getContext() instanceof WebGL2RenderingContext ? 'WebGL2' : 'WebGL1', meshes: out };
  }, MODEL);

  console.log(`gltf_model e2e: @pmndrs/assets ${version} ${MODEL}, ${result.renderer}, ${result.meshes.length} mesh(es)`);
  check('the model has meshes', result.meshes.length > 0);
  for (const m of result.meshes) {
    const where = `mesh '${m.name}'`;
    console.log(`  ${where}: ${m.triangles} triangles, ${m.vertices} vertices, attributes ${m.attributes.join(' ')}, texture ${m.mapSize?.join('x')}, ` +
      `UVs in [${m.uvBox.map((x) => x.toFixed(3)).join(', ')}], input edges ${JSON.stringify(m.inputEdges)}, covers ${m.input.covered} px`);
    check(`${where}: textured, with UVs`, m.hasMap && m.attributes.includes('uv'));
    check(`${where}: the input is a manifold triangle mesh by position`, typeof m.inputEdges === 'object', JSON.stringify(m.inputEdges));
    const q = {};
    for (const r of m.runs) {
      const what = `${where}, ${r.label}, level ${r.levels}`;
      console.log(`  ${what}: ${r.triangles} triangles, ${r.ms.toFixed(0)} ms, covers ${r.render.covered} px ` +
        `(${((100 * r.render.covered) / m.input.covered).toFixed(1)}% of the input's), ${r.render.colours} colours, ` +
        `luminance spread ${r.render.spread.toFixed(1)} (input ${m.input.spread.toFixed(1)}), difference from the input ${(100 * r.difference).toFixed(1)}%, ` +
        `own texture ${r.own.colours} colours (input ${m.inputOwn.colours})` +
        (r.scrambledDifference !== undefined ? `, UVs scrambled ${(100 * r.scrambledDifference).toFixed(1)}%, untextured spread ${r.flat.spread.toFixed(1)}` : ''));
      check(`${what}: UVs present and within the input's UV box`, r.hasUv &&
        r.uvBox[0] >= m.uvBox[0] - 1e-6 && r.uvBox[1] >= m.uvBox[1] - 1e-6 && r.uvBox[2] <= m.uvBox[2] + 1e-6 && r.uvBox[3] <= m.uvBox[3] + 1e-6,
      JSON.stringify(r.uvBox));
      if (r.label === 'Loop') {
        check(`${what}: 4^levels × the input's triangles`, r.triangles === 4 ** r.levels * m.triangles, `${r.triangles} vs ${4 ** r.levels * m.triangles}`);
      } else {
        // 2 × 4^(levels - 1) × (4q + 3(t - 2q)) = 2 × 4^(levels - 1) × (3t - 2q)
        const joined = (3 * m.triangles - r.triangles / (2 * 4 ** (r.levels - 1))) / 2;
        q[r.levels] = joined;
        check(`${what}: 2 × 4^(levels - 1) × (4q + 3(t - 2q)) triangles for a whole q in (0, t/2]`,
          Number.isInteger(joined) && joined > 0 && joined <= m.triangles / 2, `q = ${joined}`);
      }
      if (typeof m.inputEdges === 'object') {
        const ok = typeof r.edges === 'object' && r.edges.boundary === m.inputEdges.boundary * 2 ** r.levels && r.edges.loops === m.inputEdges.loops;
        check(`${what}: watertight where the input is (boundary edges 2^levels × the input's, same loops)`, ok, JSON.stringify(r.edges));
      }
      const coverage = r.render.covered / m.input.covered;
      check(`${what}: covers 85-101% of the input's pixels`, coverage >= 0.85 && coverage <= 1.01, `${(100 * coverage).toFixed(1)}%`);
      check(`${what}: drawn with the model's own texture, covering what the checker render covers, not one flat colour`,
        r.own.covered === r.render.covered && r.own.colours > 1, `${r.own.covered} px, ${r.own.colours} colours`);
      check(`${what}: textured (checker), not one flat colour`, r.render.spread >= 0.5 * m.input.spread && r.render.spread > 20, `spread ${r.render.spread.toFixed(1)}`);
      check(`${what}: the texture lands where it does on the input`, r.difference < 0.1, `${(100 * r.difference).toFixed(1)}%`);
      if (r.scrambledDifference !== undefined) {
        check(`${what}: with scrambled UVs it does not`, r.scrambledDifference > 2 * r.difference, `${(100 * r.scrambledDifference).toFixed(1)}%`);
        check(`${what}: untextured it is one flat colour (so the spread is the texture's)`, r.flat.spread < 1, `spread ${r.flat.spread.toFixed(2)}`);
      }
    }
    check(`${where}: quads: true joins the same quads at levels 1 and 2`, q[1] === q[2], `${q[1]}, ${q[2]}`);
  }
  check('no page errors', errors.length === 0, errors.join('; '));
} finally {
  await browser.close();
  server.close();
}
finish();
