// End-to-end test of the glTF page (www/gltf.html, three.js and subsurf/three) in headless
// Chromium (WebGL on SwiftShader, no GPU needed):
//   node tests/e2e/gltf.mjs                    (after scripts/build-pkg.sh)
//   PKG_DIR=/elsewhere/pkg node tests/e2e/gltf.mjs
//
// Serves www/ as scripts/demo.sh does (/pkg/ from the built package, /vendor/three/ from
// node_modules/three, the whole package, so that the test can use three's GLTFExporter too) and:
//   - the built-in model: drawn on both sides, Catmull-Clark with quads at level 2 gives 16
//     triangles per input triangle (every triangle pair is a quad, each quad 16 at level 2);
//   - a textured .glb made here (three's TorusKnotGeometry, a four-colour checker texture,
//     written by GLTFExporter) opened through the file input: Loop at level 2 gives 16 × the
//     input triangles, 4× at level 1 and 64× at level 3 (the level slider); the right viewport
//     shows the texture's four hues over the object (a lost UV channel would show one);
//   - the same kind of model as a .gltf with its .bin and .png as separate files (resolved
//     through the page's URL modifier), and the .gltf alone refused with a message naming the
//     missing .bin, the last model staying;
//   - a skinned, morphed, animated .glb: the result is a SkinnedMesh bound to the right side's
//     own bones, keeps its morph target, and follows the animation as the original does (their
//     skinned bounding boxes at a posed time agree, and differ from the rest pose);
//   - a dense model (more than 20,000 cage edges): the cage is drawn faint, the surface's colour
//     dominates the right viewport; while level 3 is made in the worker the status tells "level
//     1/3" and the page takes a slider move to level 1, which aborts the job (the level-1 result
//     is the next drawn); level 4 is over the page's 2M-triangle guard and level 3 is shown with
//     a message;
//   - the WebGL2 page (index.html) with a dense OBJ grid: its cage no longer covers the surface
//     (most drawn pixels are the surface's orange, not the cage's blue);
//   - no page or console errors, other than the refused .gltf's failed request.
// Screenshots go to artifacts/gltf-*.png. Exits non-zero on failure.
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { SWIFTSHADER_WEBGL, checks, collectErrors, launchChromium, pkg, root, serveStatic } from './harness.mjs';

const artifacts = join(root, 'artifacts');
/** A page that only maps three for the test's own exporting. */
const EXPORT_PAGE = `<!doctype html><meta charset="utf-8"><title>export</title>
<script type="importmap">{ "imports": { "three": "/vendor/three/build/three.module.js", "three/addons/": "/vendor/three/examples/jsm/" } }</script>`;

const { check, finish } = checks('gltf e2e');

/**
 * Makes the test's models with three.js and its GLTFExporter, in the browser (the exporter
 * draws the texture on a canvas): returns base64 files.
 */
async function makeModels(page) {
  return page.evaluate(async () => {
    const THREE = await import('three');
    const { GLTFExporter } = await import('three/addons/exporters/GLTFExporter.js');
    // 4 × 4 squares in four saturated hues, so that the texture is told apart by hue.
    const canvas = document.createElement('canvas');
    canvas.width = canvas.height = 64;
    const context = canvas.getContext('2d');
    const hues = ['#e02020', '#20c020', '#2040e0', '#e0d020'];
    for (let j = 0; j < 4; j++) for (let i = 0; i < 4; i++) {
      context.fillStyle = hues[(i + j) % 4];
      context.fillRect(16 * i, 16 * j, 16, 16);
    }
    const texture = new THREE.CanvasTexture(canvas);
    texture.colorSpace = THREE.SRGBColorSpace;
    const textured = () => new THREE.MeshStandardMaterial({ map: texture, roughness: 0.8 });
    const exporter = new GLTFExporter();
    const base64 = (buffer) => {
      const bytes = new Uint8Array(buffer);
      let text = '';
      for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
      return btoa(text);
    };
    const glb = async (scene, animations = []) => base64(await exporter.parseAsync(scene, { binary: true, animations }));

    const knot = new THREE.Mesh(new THREE.TorusKnotGeometry(1, 0.35, 64, 8), textured());
    knot.name = 'knot';
    const box = new THREE.Mesh(new THREE.BoxGeometry(1.5, 1, 1), textured());
    box.name = 'box';
    // A node transform the framing must follow: the box far from the origin.
    box.position.set(5, 2, -3);
    const gltf = await exporter.parseAsync(box, { binary: false });

    // A bending tube: two bones, weights by height, one morph target (wider), an animation
    // that bends the upper bone and swells the morph.
    const tube = new THREE.CylinderGeometry(0.3, 0.3, 2, 12, 8);
    const position = tube.getAttribute('position');
    const skinIndex = [];
    const skinWeight = [];
    const wide = [];
    for (let i = 0; i < position.count; i++) {
      const w = Math.min(1, Math.max(0, position.getY(i) + 0.5));
      skinIndex.push(0, 1, 0, 0);
      skinWeight.push(1 - w, w, 0, 0);
      wide.push(position.getX(i) * 1.6, position.getY(i), position.getZ(i) * 1.6);
    }
    tube.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(skinIndex, 4));
    tube.setAttribute('skinWeight', new THREE.Float32BufferAttribute(skinWeight, 4));
    tube.morphAttributes.position = [new THREE.Float32BufferAttribute(wide, 3)];
    const lower = new THREE.Bone();
    lower.name = 'lower';
    lower.position.y = -1;
    const upper = new THREE.Bone();
    upper.name = 'upper';
    upper.position.y = 1;
    lower.add(upper);
    const skinned = new THREE.SkinnedMesh(tube, textured());
    skinned.name = 'tube';
    skinned.add(lower);
    skinned.bind(new THREE.Skeleton([lower, upper]));
    skinned.updateMorphTargets();
    const bent = new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 0, 1), Math.PI / 2).toArray();
    const clip = new THREE.AnimationClip('bend', 2, [
      new THREE.QuaternionKeyframeTrack('upper.quaternion', [0, 1, 2], [0, 0, 0, 1, ...bent, 0, 0, 0, 1]),
      new THREE.NumberKeyframeTrack('tube.morphTargetInfluences', [0, 1, 2], [0, 1, 0]),
    ]);
    const group = new THREE.Group();
    group.add(skinned);

    // Dense: about 14,000 triangles, 21,000 edges; one plain colour (no texture).
    const dense = new THREE.Mesh(new THREE.SphereGeometry(1, 120, 60), new THREE.MeshStandardMaterial({ color: 0xe08020, roughness: 0.7 }));
    dense.name = 'dense';

    return {
      knot: await glb(knot),
      box: gltf, // JSON with data: URIs, split into files in Node
      skinned: await glb(group, [clip]),
      dense: await glb(dense),
    };
  });
}

/** Splits a .gltf whose buffers and images are data: URIs into the .gltf, a .bin and .png files. */
function splitGltf(json, name) {
  const files = [];
  const take = (item, file) => {
    const [, type, data] = item.uri.match(/^data:([^;,]*)(?:;base64)?,(.*)$/s);
    files.push({ name: file, mimeType: type || 'application/octet-stream', buffer: Buffer.from(data, 'base64') });
    item.uri = file;
  };
  (json.buffers ?? []).forEach((buffer, i) => take(buffer, `${name}${i ? i : ''}.bin`));
  (json.images ?? []).forEach((image, i) => image.uri && take(image, `${name}-texture${i}.png`));
  return [{ name: `${name}.gltf`, mimeType: 'model/gltf+json', buffer: Buffer.from(JSON.stringify(json)) }, ...files];
}

/** Counts drawn pixels (not the clear colour) of a PNG, by hue, decoded in the page. */
async function analyze(page, png, region) {
  return page.evaluate(async ({ base64, region }) => {
    const blob = await (await fetch(`data:image/png;base64,${base64}`)).blob();
    const image = await createImageBitmap(blob);
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const x0 = Math.floor(region[0] * image.width), x1 = Math.floor(region[1] * image.width);
    const { data, width, height } = context.getImageData(x0, 0, x1 - x0, image.height);
    const background = [data[0], data[1], data[2]]; // a corner is always background
    let drawn = 0;
    let blue = 0; // the cage's blue: blue well over red and over green
    const hues = new Array(6).fill(0); // saturated pixels in six 60° hue sectors
    for (let i = 0; i < data.length; i += 4) {
      const [r, g, b] = [data[i], data[i + 1], data[i + 2]];
      if (Math.abs(r - background[0]) + Math.abs(g - background[1]) + Math.abs(b - background[2]) <= 30) continue;
      drawn++;
      if (b > r + 40 && b > g) blue++;
      const max = Math.max(r, g, b), min = Math.min(r, g, b);
      if (max - min < 40) continue;
      const h = max === r ? ((g - b) / (max - min) + 6) % 6 : max === g ? (b - r) / (max - min) + 2 : (r - g) / (max - min) + 4;
      hues[Math.floor(h) % 6]++;
    }
    return { total: width * height, drawn, blue, hues };
  }, { base64: png.toString('base64'), region });
}

const server = await serveStatic({
  pages: { '/export.html': EXPORT_PAGE },
  routes: { '/pkg/': pkg, '/vendor/three/': join(root, 'node_modules', 'three'), '/': join(root, 'www') },
});
mkdirSync(artifacts, { recursive: true });
const browser = await launchChromium({ args: SWIFTSHADER_WEBGL });
try {
  const exportPage = await browser.newPage();
  await exportPage.goto(`${server.origin}/export.html`);
  const models = await makeModels(exportPage);
  await exportPage.close();
  const file = (name, base64, mimeType = 'model/gltf-binary') => ({ name, mimeType, buffer: Buffer.from(base64, 'base64') });

  const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  // The refused .gltf below makes two requests fail (its .bin and texture) and GLTFLoader say
  // so; those, and only those, are expected, whenever they arrive.
  const EXPECTED = /status of 404|Couldn't load texture box-texture0\.png|Failed to load buffer "box\.bin"/;
  const errors = collectErrors(page, { except: EXPECTED });
  const missed = [];
  page.on('response', (response) => { if (response.status() === 404) missed.push(new URL(response.url()).pathname); });
  const dataset = () => page.evaluate(() => ({ ...document.documentElement.dataset }));
  /** Waits for a drawn result after `job` (the data-job before the change) matching `want`. */
  const shows = async (job, want, what) => {
    try {
      await page.waitForFunction(({ job, want }) => {
        const data = document.documentElement.dataset;
        return data.job !== job && !data.busy && Object.entries(want).every(([key, value]) => data[key] === String(value));
      }, { job, want }, { timeout: 120_000 });
    } catch {
      throw new Error(`${what}: expected ${JSON.stringify(want)}; the page shows ${JSON.stringify(await dataset())}`);
    }
    return dataset();
  };
  const shot = async (name, region = [0.5, 1]) => {
    const url = await page.locator('#view').evaluate((canvas) => canvas.toDataURL('image/png'));
    const png = Buffer.from(url.slice(url.indexOf(',') + 1), 'base64');
    writeFileSync(join(artifacts, `gltf-${name}.png`), png);
    await page.screenshot({ path: join(artifacts, `gltf-${name}-page.png`) });
    return analyze(page, png, region);
  };
  const setLevel = (level) => page.locator('#level').evaluate((input, value) => {
    input.value = String(value);
    input.dispatchEvent(new Event('input', { bubbles: true }));
  }, level);
  /** At least three of the six hue sectors each hold 3% of the drawn pixels: a texture's colours. */
  const textureHues = (stats) => stats.hues.filter((n) => n > 0.03 * stats.drawn).length;

  // ---- the built-in model
  await page.goto(`${server.origin}/gltf.html`);
  let data = await shows(undefined, { ready: true }, 'the built-in model');
  check('built-in model: no error', data.error === undefined && data.fatal === undefined, data.error ?? data.fatal);
  check('built-in model: Catmull-Clark with quads, level 2: 16 triangles per input triangle',
    data.scheme === 'catmull-clark' && data.quads === 'true' && data.level === '2' && Number(data.trianglesOut) === 16 * Number(data.trianglesIn),
    `${data.trianglesIn} in, ${data.trianglesOut} out`);
  // The built-in model turns; stop it so that the pictures below are of one pose.
  await page.uncheck('#animate');
  let stats = await shot('built-in', [0, 1]);
  check('built-in model: drawn on the canvas', stats.drawn > 0.05 * stats.total, `${stats.drawn} of ${stats.total} pixels`);

  // ---- a textured .glb through the file input, Loop
  await page.selectOption('#scheme', 'loop');
  data = await shows(data.job, { scheme: 'loop', quads: false }, 'Loop on the built-in model');
  check('quads disabled for Loop', await page.locator('#quads').isDisabled());
  await page.setInputFiles('#file', file('knot.glb', models.knot));
  data = await shows(data.job, { model: 'knot.glb', level: 2 }, 'knot.glb');
  const knotTriangles = Number(data.trianglesIn);
  check('knot.glb: 1024 input triangles (TorusKnotGeometry 64 × 8)', knotTriangles === 1024, data.trianglesIn);
  check('knot.glb: Loop level 2 gives 16 × the triangles', Number(data.trianglesOut) === 16 * knotTriangles, data.trianglesOut);
  check('knot.glb: the counts are on screen', (await page.locator('#triangles-out').textContent()) === (16 * knotTriangles).toLocaleString('en-US'));
  check('knot.glb: the time of subdivideGeometryAsync is given', Number(data.subdivideMs) > 0, data.subdivideMs);
  await page.uncheck('#cage');
  await page.waitForFunction(() => document.documentElement.dataset.cage === 'hidden');
  await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
  stats = await shot('knot-loop2');
  check('knot.glb: the right viewport shows the object', stats.drawn > 0.03 * stats.total, `${stats.drawn} of ${stats.total} pixels`);
  check('knot.glb: the right viewport shows the texture (three or more hues)', textureHues(stats) >= 3, JSON.stringify(stats.hues));
  const leftStats = await shot('knot-loop2-left', [0, 0.5]);
  check('knot.glb: the left viewport shows the textured original', textureHues(leftStats) >= 3, JSON.stringify(leftStats.hues));
  // Dropped on the page, as from a file manager: the same model again, a new result.
  const transfer = await page.evaluateHandle((base64) => {
    const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
    const dataTransfer = new DataTransfer();
    dataTransfer.items.add(new File([bytes], 'dropped-knot.glb', { type: 'model/gltf-binary' }));
    return dataTransfer;
  }, models.knot);
  await page.dispatchEvent('#stage', 'drop', { dataTransfer: transfer });
  data = await shows(data.job, { model: 'dropped-knot.glb', level: 2 }, 'dropped-knot.glb');
  check('a .glb dropped on the page is opened and subdivided', Number(data.trianglesOut) === 16 * knotTriangles, data.trianglesOut);
  for (const [level, factor] of [[1, 4], [3, 64]]) {
    await setLevel(level);
    data = await shows(data.job, { model: 'dropped-knot.glb', level }, `knot.glb level ${level}`);
    check(`knot.glb: level ${level} gives ${factor} × the triangles`, Number(data.trianglesOut) === factor * knotTriangles, data.trianglesOut);
  }
  await setLevel(2);
  data = await shows(data.job, { level: 2 }, 'knot.glb level 2 again');

  // ---- a .gltf with its .bin and texture as separate files
  const boxFiles = splitGltf(models.box, 'box');
  await page.setInputFiles('#file', boxFiles);
  data = await shows(data.job, { model: 'box.gltf' }, 'box.gltf with its files');
  check('box.gltf + .bin + .png: 12 triangles, Loop level 2 gives 192', data.trianglesIn === '12' && data.trianglesOut === '192', `${data.trianglesIn} → ${data.trianglesOut}`);
  check('box.gltf: nothing missing', !(await page.locator('#message').textContent()).includes('Missing'), await page.locator('#message').textContent());
  stats = await shot('box-gltf');
  check('box.gltf: the texture from its own file shows', textureHues(stats) >= 3, JSON.stringify(stats.hues));
  const framed = await page.evaluate(() => {
    const { THREE, camera, controls, left } = window.subsurfGltf;
    const box = new THREE.Box3().setFromObject(left.root);
    const center = box.getCenter(new THREE.Vector3());
    return { target: controls.target.distanceTo(center), up: camera.up.toArray(), size: box.getSize(new THREE.Vector3()).length(), centerX: center.x };
  });
  check('box.gltf: framed on its node\'s position, +Y up', framed.target < 1e-6 && Math.abs(framed.centerX - 5) < 1e-3 &&
    framed.up.join() === '0,1,0', JSON.stringify(framed));
  // Crease angle: Catmull-Clark rounds the box into a blob; with a 30° crease angle its
  // edges are sharp creases and it stays a box of the input's size.
  const boxSize = () => page.evaluate(() => {
    const { THREE, model } = window.subsurfGltf;
    const { source, target } = model.meshes[0];
    const size = (geometry) => { geometry.computeBoundingBox(); return geometry.boundingBox.getSize(new THREE.Vector3()).toArray(); };
    return { input: size(source.geometry), output: size(target.geometry) };
  });
  await page.selectOption('#scheme', 'catmull-clark');
  data = await shows(data.job, { model: 'box.gltf', scheme: 'catmull-clark', quads: true, creaseAngle: 'off' }, 'box.gltf, Catmull-Clark');
  check('box.gltf, Catmull-Clark with quads: 6 quads, 16 triangles per input triangle', data.trianglesOut === '192', data.trianglesOut);
  const rounded = await boxSize();
  await page.check('#crease');
  data = await shows(data.job, { model: 'box.gltf', creaseAngle: 30 }, 'box.gltf, crease angle 30°');
  const creased = await boxSize();
  const near = (a, b) => a.every((x, i) => Math.abs(x - b[i]) < 1e-4);
  check('box.gltf: without a crease angle Catmull-Clark shrinks the box', rounded.output.every((x, i) => x < 0.95 * rounded.input[i]), JSON.stringify(rounded));
  check('box.gltf: with a crease angle of 30° it stays the box', near(creased.output, creased.input), JSON.stringify(creased));
  await page.uncheck('#crease');
  await page.selectOption('#scheme', 'loop');
  data = await shows(data.job, { model: 'box.gltf', scheme: 'loop', creaseAngle: 'off' }, 'box.gltf, Loop again');

  // The .gltf alone: its .bin cannot be found; the page says which file is missing.
  await page.setInputFiles('#file', boxFiles[0]);
  await page.waitForFunction(() => document.documentElement.dataset.error);
  data = await dataset();
  check('box.gltf alone: refused, naming the missing box.bin', data.error.includes('Missing: box.bin'), data.error);
  check('box.gltf alone: the last model stays', data.model === 'box.gltf' && data.trianglesOut === '192', `${data.model} ${data.trianglesOut}`);

  // ---- skinned, morphed, animated
  await page.selectOption('#scheme', 'catmull-clark');
  data = await shows(data.job, { scheme: 'catmull-clark' }, 'Catmull-Clark');
  await page.setInputFiles('#file', file('tube.glb', models.skinned));
  data = await shows(data.job, { model: 'tube.glb' }, 'tube.glb');
  check('tube.glb: one skinned mesh with morph targets, the clip playing on load',
    data.skinned === '1' && data.morphed === '1' && data.animation === 'bend', `skinned ${data.skinned}, morphed ${data.morphed}, clip "${data.animation}"`);
  const skin = await page.evaluate(() => {
    const { THREE, left, right, model } = window.subsurfGltf;
    const { source, target } = model.meshes[0];
    const inside = (object, root) => { for (let o = object; o; o = o.parent) if (o === root) return true; return false; };
    /** The skinned, morphed positions' bounding box in world space. */
    const posed = (mesh) => {
      mesh.updateMatrixWorld(true);
      const box = new THREE.Box3();
      const v = new THREE.Vector3();
      for (let i = 0; i < mesh.geometry.getAttribute('position').count; i++) box.expandByPoint(mesh.getVertexPosition(i, v).applyMatrix4(mesh.matrixWorld));
      return box;
    };
    const at = (time) => {
      left.mixer.setTime(time);
      right.mixer.setTime(time);
      left.root.updateMatrixWorld(true);
      right.root.updateMatrixWorld(true);
      return { source: posed(source), target: posed(target), influence: target.morphTargetInfluences[0] };
    };
    const rest = at(0);
    const bent = at(1);
    const centre = (box) => box.getCenter(new THREE.Vector3());
    return {
      skinnedResult: target.isSkinnedMesh && target.geometry !== source.geometry && Boolean(target.geometry.getAttribute('skinIndex')),
      ownBones: target.skeleton.bones.every((bone) => inside(bone, right.root)) && target.skeleton !== source.skeleton,
      boneNames: target.skeleton.bones.map((b) => b.name).join() === source.skeleton.bones.map((b) => b.name).join(),
      morphs: target.geometry.morphAttributes.position?.length ?? 0,
      influence: bent.influence,
      size: rest.source.getSize(new THREE.Vector3()).length(),
      bentApart: centre(bent.source).distanceTo(centre(bent.target)),
      restApart: centre(rest.source).distanceTo(centre(rest.target)),
      moved: centre(bent.target).distanceTo(centre(rest.target)),
      widthBent: bent.target.getSize(new THREE.Vector3()).z,
      widthRest: rest.target.getSize(new THREE.Vector3()).z,
    };
  });
  check('tube.glb: the result is a SkinnedMesh with skin attributes', skin.skinnedResult);
  check('tube.glb: bound to the right side\'s own bones, same names', skin.ownBones && skin.boneNames);
  check('tube.glb: the morph target is kept and animated', skin.morphs === 1 && Math.abs(skin.influence - 1) < 1e-6, `${skin.morphs} target(s), influence ${skin.influence}`);
  check('tube.glb: the bent pose moves the subdivided tube', skin.moved > 0.15 * skin.size, `moved ${skin.moved.toFixed(3)} of size ${skin.size.toFixed(3)}`);
  check('tube.glb: the subdivided tube follows the original (rest and bent)',
    skin.restApart < 0.05 * skin.size && skin.bentApart < 0.05 * skin.size, `apart ${skin.restApart.toFixed(4)} / ${skin.bentApart.toFixed(4)}`);
  check('tube.glb: the morph target widens the subdivided tube', skin.widthBent > 1.3 * skin.widthRest, `${skin.widthRest.toFixed(3)} → ${skin.widthBent.toFixed(3)}`);
  await page.check('#cage');
  stats = await shot('tube-bent', [0, 1]);

  // ---- dense: the cage faint; the triangle guard
  await page.selectOption('#scheme', 'loop');
  data = await shows(data.job, { scheme: 'loop' }, 'Loop');
  await page.setInputFiles('#file', file('dense.glb', models.dense));
  data = await shows(data.job, { model: 'dense.glb', level: 2 }, 'dense.glb');
  check('dense.glb: more than 20,000 cage edges, drawn faint', Number(data.cageEdges) > 20000 && data.cage === 'faint', `${data.cageEdges} edges, ${data.cage}`);
  stats = await shot('dense-cage-faint');
  check('dense.glb: the surface\'s orange, not the cage\'s blue, fills the right viewport', stats.blue < 0.2 * stats.drawn,
    `${stats.blue} blue of ${stats.drawn} drawn pixels`);
  // The work runs in a worker: while level 3 is being made the page shows its progress and
  // handles the slider, whose move aborts the job (the observer moves it, inside the page, as
  // soon as level 1 of 3 is told: before the job can end).
  const beforeSupersede = await dataset();
  await page.evaluate(() => {
    const text = document.getElementById('busy-text');
    window.busyTexts = [];
    const observer = new MutationObserver(() => {
      window.busyTexts.push(text.textContent);
      if (text.textContent.endsWith('level 1/3') && !window.superseded) {
        window.superseded = true;
        const level = document.getElementById('level');
        level.value = '1';
        level.dispatchEvent(new Event('input', { bubbles: true }));
      }
    });
    observer.observe(text, { childList: true, characterData: true, subtree: true });
    window.stopObserving = () => observer.disconnect();
  });
  await setLevel(3);
  data = await shows(beforeSupersede.job, { model: 'dense.glb', level: 1, requestedLevel: 1 }, 'dense.glb level 3, superseded by level 1');
  const busyTexts = await page.evaluate(() => { window.stopObserving(); return window.busyTexts; });
  check('dense.glb level 3: the status tells the job\'s progress ("level 1/3")', busyTexts.includes('Subdividing… level 1/3'), busyTexts.join(' | '));
  check('dense.glb: the slider moved during the job aborts it; the level-1 result is the next drawn',
    Number(data.job) === Number(beforeSupersede.job) + 1 && Number(data.aborted ?? 0) === Number(beforeSupersede.aborted ?? 0) + 1 &&
    Number(data.trianglesOut) === 4 * Number(data.trianglesIn),
    `job ${beforeSupersede.job} → ${data.job}, aborted ${beforeSupersede.aborted ?? 0} → ${data.aborted}, ${data.trianglesOut} triangles`);
  await setLevel(4);
  data = await shows(data.job, { model: 'dense.glb', requestedLevel: 4 }, 'dense.glb level 4');
  check('dense.glb level 4: over the 2M-triangle guard, level 3 shown with a message',
    data.level === '3' && Number(data.trianglesOut) <= 2_000_000 && (await page.locator('#level-hint').textContent()).includes('showing level 3'),
    `level ${data.level}, ${data.trianglesOut} triangles, "${await page.locator('#level-hint').textContent()}"`);
  check('no page or console errors on the glTF page', errors.length === 0, errors.join('; '));
  check('no requests failed but the refused .gltf\'s files', missed.every((path) => ['/box.bin', '/box-texture0.png'].includes(path)), missed.join(', '));
  await page.close();

  // ---- the WebGL2 page: a dense OBJ's cage does not cover its surface
  const main = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  const mainErrors = collectErrors(main);
  await main.goto(`${server.origin}/`);
  await main.waitForFunction(() => document.documentElement.dataset.ready === 'true', null, { timeout: 120_000 });
  // A 110 × 110 grid of quads: 24,420 edges; level 1 keeps the job small.
  const N = 110;
  const lines = [];
  for (let j = 0; j <= N; j++) for (let i = 0; i <= N; i++) lines.push(`v ${i / N - 0.5} ${0.1 * Math.sin(6 * i / N)} ${j / N - 0.5}`);
  for (let j = 0; j < N; j++) for (let i = 0; i < N; i++) {
    const a = j * (N + 1) + i + 1;
    lines.push(`f ${a} ${a + N + 1} ${a + N + 2} ${a + 1}`);
  }
  await main.evaluate(() => {
    const level = document.getElementById('level');
    level.value = '1';
    level.dispatchEvent(new Event('input', { bubbles: true }));
  });
  await main.setInputFiles('#file', { name: 'grid.obj', mimeType: 'text/plain', buffer: Buffer.from(lines.join('\n')) });
  await main.waitForFunction((faces) => document.documentElement.dataset.facesIn === String(faces) && !document.documentElement.dataset.busy,
    N * N, { timeout: 120_000 });
  await main.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve))));
  const mainUrl = await main.locator('#view').evaluate((canvas) => canvas.toDataURL('image/png'));
  const mainPng = Buffer.from(mainUrl.slice(mainUrl.indexOf(',') + 1), 'base64');
  writeFileSync(join(artifacts, 'gltf-main-dense-cage.png'), mainPng);
  const mainStats = await analyze(main, mainPng, [0, 1]);
  check('WebGL2 page, dense OBJ (24,420 cage edges): the cage is faint, the surface shows', mainStats.blue < 0.25 * mainStats.drawn,
    `${mainStats.blue} blue of ${mainStats.drawn} drawn pixels`);
  check('no page or console errors on the WebGL2 page', mainErrors.length === 0, mainErrors.join('; '));
} catch (error) {
  check('the test ran to its end', false, error.stack ?? error);
} finally {
  await browser.close();
  server.close();
}
finish();
