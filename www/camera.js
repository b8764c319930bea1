// An orbit camera (yaw, pitch and distance around a target) and its mouse, touch and keyboard
// controls. Matrices are column-major Float32Arrays, as WebGL wants them.

const FOV_Y = Math.PI / 4;

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / (Math.hypot(...a) || 1));

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

/** The centre and radius of the bounding box of `positions` (x, y, z per vertex). */
export function boundsOf(positions) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const x = positions[i + k];
      if (x < lo[k]) lo[k] = x;
      if (x > hi[k]) hi[k] = x;
    }
  }
  if (!(lo[0] <= hi[0])) return { center: [0, 0, 0], radius: 1 };
  return { center: scale(add(lo, hi), 0.5), radius: Math.max(Math.hypot(...sub(hi, lo)) / 2, 1e-6) };
}

export class OrbitCamera {
  constructor() {
    this.target = [0, 0, 0];
    this.radius = 1.8; // of the framed mesh: scales zoom limits, clipping planes and panning
    this.distance = 6;
    this.yaw = 0.6;
    this.pitch = 0.45;
  }

  /** Looks at the whole of `bounds` ({ center, radius }) from the current direction. */
  frame({ center, radius }) {
    this.target = [...center];
    this.radius = radius;
    this.distance = (1.15 * radius) / Math.sin(FOV_Y / 2);
  }

  /** Unit vectors of the view: `back` points from the target to the eye. */
  basis() {
    const { yaw, pitch } = this;
    const back = [Math.cos(pitch) * Math.sin(yaw), Math.sin(pitch), Math.cos(pitch) * Math.cos(yaw)];
    const right = normalize(cross([0, 1, 0], back));
    const up = cross(back, right);
    return { back, right, up };
  }

  eye() {
    return add(this.target, scale(this.basis().back, this.distance));
  }

  orbit(dx, dy) {
    this.yaw -= dx * 0.008;
    this.pitch = Math.max(-1.55, Math.min(1.55, this.pitch + dy * 0.008));
  }

  /** Moves the target so that the point under the cursor follows it; `height` in CSS pixels. */
  pan(dx, dy, height) {
    const { right, up } = this.basis();
    const perPixel = (2 * this.distance * Math.tan(FOV_Y / 2)) / Math.max(height, 1);
    this.target = add(this.target, add(scale(right, -dx * perPixel), scale(up, dy * perPixel)));
  }

  zoom(factor) {
    this.distance = Math.max(this.radius * 0.05, Math.min(this.radius * 60, this.distance * factor));
  }

  /** How many pixels the framed mesh's radius spans on a viewport `heightPixels` high. */
  projectedRadius(heightPixels) {
    return (this.radius / (this.distance * Math.tan(FOV_Y / 2))) * (heightPixels / 2);
  }

  /** The view-projection matrix and what the shaders need for lighting. */
  view(aspect) {
    const { back, right, up } = this.basis();
    const eye = this.eye();
    const view = new Float32Array([
      right[0], up[0], back[0], 0,
      right[1], up[1], back[1], 0,
      right[2], up[2], back[2], 0,
      -dot(right, eye), -dot(up, eye), -dot(back, eye), 1,
    ]);
    // Clipping planes around the framed mesh, wide enough for panning away from it.
    const near = Math.max(this.distance - 8 * this.radius, this.distance / 500);
    const far = this.distance + 8 * this.radius;
    // A key light above and to the left of the viewer, so the visible side is always lit.
    const light = normalize(add(add(scale(right, -0.45), scale(up, 0.75)), scale(back, 0.55)));
    return { viewProjection: multiply(perspective(FOV_Y, aspect, near, far), view), eye, light };
  }
}

/**
 * Mouse: drag to orbit, right-drag / middle-drag / shift-drag to pan, wheel to zoom,
 * double-click to frame. Touch: one finger orbits, two fingers pinch to zoom and move to pan.
 * Keyboard on the canvas: arrows orbit, +/- zoom, F frames. Calls `changed()` after each move
 * and `frame()` when asked to frame.
 */
export function attachCameraControls(canvas, camera, { changed, frame }) {
  const pointers = new Map(); // pointerId → { x, y, pan }
  let gesture = null; // two-finger state: { distance, x, y }

  const twoFingers = () => {
    const [a, b] = [...pointers.values()];
    return { distance: Math.hypot(a.x - b.x, a.y - b.y), x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 };
  };

  canvas.addEventListener('pointerdown', (event) => {
    canvas.focus({ preventScroll: true });
    try {
      canvas.setPointerCapture(event.pointerId);
    } catch {
      // A pointer that is no longer active (or a synthetic one) cannot be captured; fine.
    }
    const pan = event.button === 1 || event.button === 2 || event.shiftKey;
    pointers.set(event.pointerId, { x: event.clientX, y: event.clientY, pan });
    gesture = pointers.size === 2 ? twoFingers() : null;
  });

  canvas.addEventListener('pointermove', (event) => {
    const pointer = pointers.get(event.pointerId);
    if (!pointer) return;
    const dx = event.clientX - pointer.x;
    const dy = event.clientY - pointer.y;
    pointer.x = event.clientX;
    pointer.y = event.clientY;
    if (pointers.size === 1) {
      if (pointer.pan) camera.pan(dx, dy, canvas.clientHeight);
      else camera.orbit(dx, dy);
    } else if (pointers.size === 2 && gesture) {
      const now = twoFingers();
      if (now.distance > 0 && gesture.distance > 0) camera.zoom(gesture.distance / now.distance);
      camera.pan(now.x - gesture.x, now.y - gesture.y, canvas.clientHeight);
      gesture = now;
    }
    changed();
  });

  const release = (event) => {
    pointers.delete(event.pointerId);
    gesture = pointers.size === 2 ? twoFingers() : null;
  };
  canvas.addEventListener('pointerup', release);
  canvas.addEventListener('pointercancel', release);
  canvas.addEventListener('contextmenu', (event) => event.preventDefault());
  canvas.addEventListener('dblclick', () => frame());

  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    const pixels = event.deltaMode === 1 ? event.deltaY * 16 : event.deltaMode === 2 ? event.deltaY * 400 : event.deltaY;
    camera.zoom(Math.exp(pixels * 0.0015));
    changed();
  }, { passive: false });

  canvas.addEventListener('keydown', (event) => {
    const step = 12;
    const actions = {
      ArrowLeft: () => camera.orbit(-step, 0),
      ArrowRight: () => camera.orbit(step, 0),
      ArrowUp: () => camera.orbit(0, -step),
      ArrowDown: () => camera.orbit(0, step),
      '+': () => camera.zoom(1 / 1.15),
      '=': () => camera.zoom(1 / 1.15),
      '-': () => camera.zoom(1.15),
      f: () => frame(),
      F: () => frame(),
    };
    const action = actions[event.key];
    if (!action) return;
    event.preventDefault();
    action();
    changed();
  });
}
