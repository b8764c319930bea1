// WebGPU drawing of the animation's GPU path: the surface that subsurf/webgpu's GpuEvaluator
// computes, drawn straight from its `positions` and `normals` GPUBuffers (vertex buffers; nothing
// is read back), indexed by the result's `triangles`, with the same camera matrices and the
// same lighting as renderer.js (no UV checker, no wireframe), and the deformed control cage as
// lines from the control buffer the evaluator reads.

// The camera's matrix is WebGL's, whose clip z runs from -w to w; WebGPU's depth runs from 0 to
// w, hence the remap in toClip. WebGPU's framebuffer y runs down where WebGL's window y runs up,
// so the flat normal is cross(dpdy, dpdx) here (cross(dFdx, dFdy) in renderer.js).
const SHADER = /* wgsl */ `
struct View {
  viewProjection: mat4x4<f32>,
  eye: vec4<f32>,
  light: vec4<f32>,
  tint: vec4<f32>,
}
@group(0) @binding(0) var<uniform> view: View;

struct Surface {
  @builtin(position) clip: vec4<f32>,
  @location(0) world: vec3<f32>,
  @location(1) normal: vec3<f32>,
}

fn toClip(p: vec3<f32>) -> vec4<f32> {
  var clip = view.viewProjection * vec4<f32>(p, 1.0);
  clip.z = 0.5 * (clip.z + clip.w);
  return clip;
}

@vertex
fn surfaceVertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>) -> Surface {
  return Surface(toClip(position), position, normal);
}

// Without limit normals (the evaluator's table has no tangent weights): flat shading.
@vertex
fn flatVertex(@location(0) position: vec3<f32>) -> Surface {
  return Surface(toClip(position), position, vec3<f32>(0.0));
}

@fragment
fn surfaceFragment(in: Surface, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
  var normal = normalize(cross(dpdy(in.world), dpdx(in.world)));
  if (dot(in.normal, in.normal) > 1e-12) {
    normal = normalize(in.normal) * select(-1.0, 1.0, front);
  }
  let light = view.light.xyz;
  let toEye = normalize(view.eye.xyz - in.world);
  let key = max(dot(normal, light), 0.0);
  let fill = 0.3 * max(dot(normal, toEye), 0.0);
  let specular = pow(max(dot(normal, normalize(light + toEye)), 0.0), 48.0);
  let base = select(vec3<f32>(0.45, 0.55, 0.72), vec3<f32>(0.88, 0.58, 0.3), front);
  return vec4<f32>(base * (0.16 + 0.66 * key + fill) + 0.22 * specular, 1.0);
}

@vertex
fn lineVertex(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
  return toClip(position);
}

@fragment
fn lineFragment() -> @location(0) vec4<f32> {
  return view.tint;
}
`;

const SAMPLES = 4;
const DEPTH_FORMAT = 'depth24plus';
const UNIFORM_BYTES = 112; // mat4 + 3 vec4
const BACKGROUND = { r: 0.11, g: 0.122, b: 0.141, a: 1 }; // renderer.js COLORS.background
const CAGE = [0.35, 0.78, 1, 0.95]; // renderer.js COLORS.cage
const CAGE_HIDDEN = [0.35, 0.78, 1, 0.16]; // renderer.js COLORS.cageHidden
const CAGE_DENSE = [0.35, 0.78, 1, 0.1]; // renderer.js COLORS.cageDense, above DENSE_CAGE_EDGES
const DENSE_CAGE_EDGES = 20_000; // renderer.js DENSE_CAGE_EDGES

// GPUBufferUsage and GPUTextureUsage values (fixed by the WebGPU specification).
const USAGE = { INDEX: 0x10, UNIFORM: 0x40, COPY_DST: 0x08, RENDER_ATTACHMENT: 0x10 };

const vec3Buffer = (location) => ({ arrayStride: 12, attributes: [{ shaderLocation: location, offset: 0, format: 'float32x3' }] });

export class GpuRenderer {
  /** Draws on `canvas` (a canvas of its own: a canvas has one kind of context) with `device`. */
  constructor(device, canvas) {
    this.device = device;
    this.canvas = canvas;
    this.context = canvas.getContext('webgpu');
    if (!this.context) throw new Error('this canvas gives no WebGPU context');
    this.format = navigator.gpu.getPreferredCanvasFormat();
    this.context.configure({ device, format: this.format, alphaMode: 'opaque' });
    const module = device.createShaderModule({ label: 'demo surface', code: SHADER });
    const multisample = { count: SAMPLES };
    const blend = { color: { srcFactor: 'src-alpha', dstFactor: 'one-minus-src-alpha' }, alpha: { srcFactor: 'one', dstFactor: 'one-minus-src-alpha' } };
    const surface = (entryPoint, buffers) => device.createRenderPipeline({
      label: `demo ${entryPoint}`,
      layout: 'auto',
      vertex: { module, entryPoint, buffers },
      fragment: { module, entryPoint: 'surfaceFragment', targets: [{ format: this.format }] },
      primitive: { topology: 'triangle-list', cullMode: 'none', frontFace: 'ccw' },
      // Pushed back a little, as renderer.js's polygon offset, so that cage lines on it win.
      depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: true, depthCompare: 'less-equal', depthBias: 2, depthBiasSlopeScale: 1 },
      multisample,
    });
    const lines = (depthCompare) => device.createRenderPipeline({
      label: `demo cage ${depthCompare}`,
      layout: 'auto',
      vertex: { module, entryPoint: 'lineVertex', buffers: [vec3Buffer(0)] },
      fragment: { module, entryPoint: 'lineFragment', targets: [{ format: this.format, blend }] },
      primitive: { topology: 'line-list' },
      depthStencil: { format: DEPTH_FORMAT, depthWriteEnabled: false, depthCompare },
      multisample,
    });
    this.pipelines = {
      smooth: surface('surfaceVertex', [vec3Buffer(0), vec3Buffer(1)]),
      flat: surface('flatVertex', [vec3Buffer(0)]),
      cageFront: lines('less-equal'),
      cageHidden: lines('greater'),
    };
    // One uniform buffer per draw that needs its own tint: the surface, the hidden and the
    // visible cage.
    this.views = ['smooth', 'cageHidden', 'cageFront'].map((name) => {
      const buffer = device.createBuffer({ label: `demo view ${name}`, size: UNIFORM_BYTES, usage: USAGE.UNIFORM | USAGE.COPY_DST });
      // Every pipeline's layout is 'auto' with the same group 0: the surface's serves 'flat' too.
      const layoutOf = (pipeline) => pipeline.getBindGroupLayout(0);
      const group = (pipeline) => device.createBindGroup({ layout: layoutOf(pipeline), entries: [{ binding: 0, resource: { buffer } }] });
      return { buffer, groups: name === 'smooth' ? { smooth: group(this.pipelines.smooth), flat: group(this.pipelines.flat) } : { [name]: group(this.pipelines[name]) } };
    });
    this.mesh = null;
    this.targets = null; // { width, height, color, depth }
  }

  /**
   * What to draw: `evaluator` (a GpuEvaluator: its positions and normals buffers), the result's
   * `triangles`, and the cage: `cageBuffer` (a GPUBuffer with VERTEX usage, 3 f32 per cage
   * vertex) and `cageEdges` (vertex pairs). The index buffers are uploaded once here.
   */
  setMesh({ evaluator, triangles, cageBuffer, cageEdges }) {
    this.releaseMesh();
    const upload = (label, array) => {
      const buffer = this.device.createBuffer({ label, size: Math.max(4, Math.ceil(array.byteLength / 4) * 4), usage: USAGE.INDEX | USAGE.COPY_DST });
      if (array.byteLength > 0) this.device.queue.writeBuffer(buffer, 0, array);
      return buffer;
    };
    this.mesh = {
      evaluator,
      triangles: upload('demo triangles', triangles),
      triangleCount: triangles.length,
      cageBuffer,
      cageEdges: upload('demo cage edges', cageEdges),
      cageEdgeCount: cageEdges.length,
    };
  }

  releaseMesh() {
    if (!this.mesh) return;
    this.mesh.triangles.destroy();
    this.mesh.cageEdges.destroy();
    this.mesh = null;
  }

  /** The multisampled colour and depth targets, at the canvas's size. */
  ensureTargets() {
    const ratio = Math.min(devicePixelRatio, 2);
    const width = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
    const height = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
    if (this.targets?.width === width && this.targets?.height === height) return this.targets;
    this.targets?.color.destroy();
    this.targets?.depth.destroy();
    Object.assign(this.canvas, { width, height });
    const texture = (format) => this.device.createTexture({ size: [width, height], format, sampleCount: SAMPLES, usage: USAGE.RENDER_ATTACHMENT });
    this.targets = { width, height, color: texture(this.format), depth: texture(DEPTH_FORMAT) };
    return this.targets;
  }

  /** Draws a frame with `camera` (camera.js) and submits it; `cage`: draw the cage too. */
  draw(camera, { cage = true } = {}) {
    const { device } = this;
    const { width, height, color, depth } = this.ensureTargets();
    const { viewProjection, eye, light } = camera.view(width / height);
    // A dense cage, as renderer.js draws it: faint in front, no hidden lines.
    const dense = (this.mesh?.cageEdgeCount ?? 0) / 2 > DENSE_CAGE_EDGES;
    const tints = [[0, 0, 0, 0], CAGE_HIDDEN, dense ? CAGE_DENSE : CAGE];
    this.views.forEach(({ buffer }, i) => {
      const data = new Float32Array(UNIFORM_BYTES / 4);
      data.set(viewProjection, 0);
      data.set(eye, 16);
      data.set(light, 20);
      data.set(tints[i], 24);
      device.queue.writeBuffer(buffer, 0, data);
    });
    const encoder = device.createCommandEncoder({ label: 'demo frame' });
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: color.createView(), resolveTarget: this.context.getCurrentTexture().createView(), clearValue: BACKGROUND, loadOp: 'clear', storeOp: 'discard' }],
      depthStencilAttachment: { view: depth.createView(), depthClearValue: 1, depthLoadOp: 'clear', depthStoreOp: 'store' },
    });
    const mesh = this.mesh;
    if (mesh && mesh.triangleCount > 0) {
      const smooth = Boolean(mesh.evaluator.normals);
      pass.setPipeline(smooth ? this.pipelines.smooth : this.pipelines.flat);
      pass.setBindGroup(0, this.views[0].groups[smooth ? 'smooth' : 'flat']);
      pass.setVertexBuffer(0, mesh.evaluator.positions);
      if (smooth) pass.setVertexBuffer(1, mesh.evaluator.normals);
      pass.setIndexBuffer(mesh.triangles, 'uint32');
      pass.drawIndexed(mesh.triangleCount);
    }
    if (mesh && cage && mesh.cageEdgeCount > 0) {
      for (const [i, name] of dense ? [[2, 'cageFront']] : [[1, 'cageHidden'], [2, 'cageFront']]) {
        pass.setPipeline(this.pipelines[name]);
        pass.setBindGroup(0, this.views[i].groups[name]);
        pass.setVertexBuffer(0, mesh.cageBuffer);
        pass.setIndexBuffer(mesh.cageEdges, 'uint32');
        pass.drawIndexed(mesh.cageEdgeCount);
      }
    }
    pass.end();
    device.queue.submit([encoder.finish()]);
  }

  destroy() {
    this.releaseMesh();
    this.targets?.color.destroy();
    this.targets?.depth.destroy();
    this.targets = null;
    for (const { buffer } of this.views) buffer.destroy();
  }
}
