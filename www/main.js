// The subsurf demo: a cube refined by Catmull-Clark in WebAssembly, drawn with WebGL2.
// The page only draws: every vertex it shows comes from subdivide(). Flat shading comes from
// screen-space derivatives in the fragment shader, so no normals are computed here.
//
// Ready signal for tests: window.subsurfReady === true and <html data-ready="true">, with
// data-level / data-faces / data-vertices updated after each level is drawn; data-error on failure.
import init, { subdivide, version } from './pkg/subsurf.js';

const CUBE = {
  positions: new Float32Array([-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1, -1, -1, 1, 1, -1, 1, -1, 1, 1, 1, 1, 1]),
  indices: new Uint32Array([0, 2, 3, 1, 4, 5, 7, 6, 0, 1, 5, 4, 2, 6, 7, 3, 0, 4, 6, 2, 1, 3, 7, 5]),
  faceSizes: new Uint32Array([4, 4, 4, 4, 4, 4]),
};
const BACKGROUND = [0.11, 0.122, 0.141];

const VERTEX_SHADER = `#version 300 es
in vec3 position;
uniform mat4 viewProjection;
out vec3 worldPosition;
void main() {
  worldPosition = position;
  gl_Position = viewProjection * vec4(position, 1.0);
}`;

const FRAGMENT_SHADER = `#version 300 es
precision highp float;
in vec3 worldPosition;
uniform vec3 eye;
out vec4 color;
void main() {
  vec3 normal = normalize(cross(dFdx(worldPosition), dFdy(worldPosition)));
  vec3 toEye = normalize(eye - worldPosition);
  vec3 light = normalize(vec3(0.5, 0.9, 0.4));
  float key = max(dot(normal, light), 0.0);
  float fill = 0.35 * max(dot(normal, toEye), 0.0);
  float specular = pow(max(dot(normal, normalize(light + toEye)), 0.0), 40.0);
  vec3 base = vec3(0.86, 0.56, 0.28);
  color = vec4(base * (0.12 + 0.7 * key + fill) + 0.25 * specular, 1.0);
}`;

const $ = (id) => document.getElementById(id);
const root = document.documentElement;

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
  return shader;
}

function createProgram(gl) {
  const program = gl.createProgram();
  gl.attachShader(program, compile(gl, gl.VERTEX_SHADER, VERTEX_SHADER));
  gl.attachShader(program, compile(gl, gl.FRAGMENT_SHADER, FRAGMENT_SHADER));
  gl.bindAttribLocation(program, 0, 'position');
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
  return program;
}

// Column-major 4x4 matrices, as WebGL wants them.
function perspective(fovY, aspect, near, far) {
  const f = 1 / Math.tan(fovY / 2);
  const m = new Float32Array(16);
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (far + near) / (near - far);
  m[11] = -1;
  m[14] = (2 * far * near) / (near - far);
  return m;
}

function lookAt(eye, target, up) {
  const sub = (a, b) => a.map((x, i) => x - b[i]);
  const normalize = (a) => a.map((x) => x / Math.hypot(...a));
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const z = normalize(sub(eye, target));
  const x = normalize(cross(up, z));
  const y = cross(z, x);
  return new Float32Array([x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0, -dot(x, eye), -dot(y, eye), -dot(z, eye), 1]);
}

function multiply(a, b) {
  const m = new Float32Array(16);
  for (let col = 0; col < 4; col++) {
    for (let row = 0; row < 4; row++) {
      let sum = 0;
      for (let k = 0; k < 4; k++) sum += a[k * 4 + row] * b[col * 4 + k];
      m[col * 4 + row] = sum;
    }
  }
  return m;
}

function createRenderer(gl) {
  const program = createProgram(gl);
  const viewProjection = gl.getUniformLocation(program, 'viewProjection');
  const eyeUniform = gl.getUniformLocation(program, 'eye');
  const vao = gl.createVertexArray();
  const positionBuffer = gl.createBuffer();
  const indexBuffer = gl.createBuffer();
  gl.bindVertexArray(vao);
  gl.bindBuffer(gl.ARRAY_BUFFER, positionBuffer);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
  gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, indexBuffer);
  gl.bindVertexArray(null);
  let count = 0;

  return {
    upload(mesh) {
      gl.bindBuffer(gl.ARRAY_BUFFER, positionBuffer);
      gl.bufferData(gl.ARRAY_BUFFER, mesh.positions, gl.STATIC_DRAW);
      gl.bindVertexArray(vao);
      gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, mesh.triangles, gl.STATIC_DRAW);
      gl.bindVertexArray(null);
      count = mesh.triangles.length;
    },
    draw(camera) {
      const width = gl.drawingBufferWidth;
      const height = gl.drawingBufferHeight;
      gl.viewport(0, 0, width, height);
      gl.clearColor(...BACKGROUND, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.enable(gl.CULL_FACE);
      const { yaw, pitch, distance } = camera;
      const eye = [distance * Math.cos(pitch) * Math.sin(yaw), distance * Math.sin(pitch), distance * Math.cos(pitch) * Math.cos(yaw)];
      const projection = perspective(Math.PI / 4, width / Math.max(height, 1), 0.05, 100);
      gl.useProgram(program);
      gl.uniformMatrix4fv(viewProjection, false, multiply(projection, lookAt(eye, [0, 0, 0], [0, 1, 0])));
      gl.uniform3fv(eyeUniform, eye);
      gl.bindVertexArray(vao);
      gl.drawElements(gl.TRIANGLES, count, gl.UNSIGNED_INT, 0);
      gl.bindVertexArray(null);
    },
  };
}

function showError(error) {
  console.error(error);
  $('status').textContent = `Error: ${error.message ?? error}`;
  $('status').className = 'error';
  root.dataset.error = String(error.message ?? error);
}

async function main() {
  await init();
  const canvas = $('view');
  // preserveDrawingBuffer keeps the last frame readable (gl.readPixels, screenshots).
  const gl = canvas.getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
  if (!gl) throw new Error('this browser has no WebGL2');
  const renderer = createRenderer(gl);
  const camera = { yaw: 0.6, pitch: 0.45, distance: 6 };
  let pending = false;
  const afterDraw = [];

  // Draws on the next animation frame; `after` runs once that frame has reached the screen.
  function requestDraw(after) {
    if (after) afterDraw.push(after);
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      const width = Math.round(canvas.clientWidth * devicePixelRatio);
      const height = Math.round(canvas.clientHeight * devicePixelRatio);
      if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
      renderer.draw(camera);
      const callbacks = afterDraw.splice(0);
      if (callbacks.length) requestAnimationFrame(() => callbacks.forEach((callback) => callback()));
    });
  }

  function setLevel(level) {
    const start = performance.now();
    const mesh = subdivide(CUBE, { levels: level });
    const milliseconds = performance.now() - start;
    renderer.upload(mesh);
    const faces = mesh.faceSizes.length;
    const vertices = mesh.positions.length / 3;
    $('level-value').textContent = level;
    $('faces').textContent = faces.toLocaleString('en-US');
    $('vertices').textContent = vertices.toLocaleString('en-US');
    $('time').textContent = `${milliseconds.toFixed(1)} ms`;
    requestDraw(() => Object.assign(root.dataset, { level, faces, vertices }));
  }

  $('level').addEventListener('input', (event) => {
    try {
      setLevel(Number(event.target.value));
    } catch (error) {
      showError(error);
    }
  });

  let drag = null;
  canvas.addEventListener('pointerdown', (event) => {
    drag = { x: event.clientX, y: event.clientY };
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    camera.yaw -= (event.clientX - drag.x) * 0.01;
    camera.pitch = Math.max(-1.5, Math.min(1.5, camera.pitch + (event.clientY - drag.y) * 0.01));
    drag = { x: event.clientX, y: event.clientY };
    requestDraw();
  });
  canvas.addEventListener('pointerup', () => (drag = null));
  canvas.addEventListener('pointercancel', () => (drag = null));
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    camera.distance = Math.max(2.5, Math.min(30, camera.distance * Math.exp(event.deltaY * 0.001)));
    requestDraw();
  }, { passive: false });
  new ResizeObserver(() => requestDraw()).observe(canvas);

  setLevel(Number($('level').value));
  $('status').textContent = `subsurf ${version()} · drag to orbit, scroll to zoom`;
  requestDraw(() => {
    root.dataset.ready = 'true';
    window.subsurfReady = true;
  });
}

main().catch(showError);
