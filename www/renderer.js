// WebGL2 drawing of the demo: the refined surface (smooth or flat shading, with a UV checker
// texture when the mesh has UVs), its wireframe and the control cage. Only drawing happens here;
// every position, normal, UV and edge comes from subsurf: from the worker, and while the page
// animates from an Evaluator on the page (animation.js), whose frames overwrite the vertex
// buffers in place (updateRefined, updateCage) while the index buffers stay.
//
// The surface and the wireframe have vertex buffers of their own: with UVs the surface is
// subsurf's toDrawable mesh, whose vertices are split along UV seams (one index buffer for
// positions, normals and UVs), while the wireframe's edges index the refined mesh itself.
//
// Edges are drawn as line layers made of groups, each group an index buffer with its own
// colour. The cage has its edges, its creased edges split by sharpness ('sharp': infinitely
// sharp, 'semi': semi-sharp), its sharp corners and the edge under the pointer ('hover'). WebGL
// draws lines one pixel wide on most systems, so the creased ones are drawn a few times, a
// pixel apart, to stand out.

const SURFACE_VS = `#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 viewProjection;
out vec3 worldPosition;
out vec3 smoothNormal;
out vec2 surfaceUv;
void main() {
  worldPosition = position;
  smoothNormal = normal;
  surfaceUv = uv;
  gl_Position = viewProjection * vec4(position, 1.0);
}`;

// Smooth shading uses the vertex normals from subsurf (subdivide's normals: the limit surface's
// where the last scheme has limit masks, else from the faces); flat shading (and any vertex without a
// normal) uses the triangle's own normal from screen-space derivatives.
const SURFACE_FS = `#version 300 es
precision highp float;
in vec3 worldPosition;
in vec3 smoothNormal;
in vec2 surfaceUv;
uniform vec3 eye;
uniform vec3 light;
uniform bool smoothShading;
uniform bool textured;
uniform sampler2D checker;
out vec4 color;
void main() {
  vec3 flatNormal = normalize(cross(dFdx(worldPosition), dFdy(worldPosition)));
  vec3 normal = flatNormal;
  if (smoothShading && dot(smoothNormal, smoothNormal) > 1e-12) {
    normal = normalize(smoothNormal) * (gl_FrontFacing ? 1.0 : -1.0);
  }
  vec3 toEye = normalize(eye - worldPosition);
  float key = max(dot(normal, light), 0.0);
  float fill = 0.3 * max(dot(normal, toEye), 0.0);
  float specular = pow(max(dot(normal, normalize(light + toEye)), 0.0), 48.0);
  // The outside is warm, the inside (seen through holes and open boundaries) cool; with UVs the
  // checker shows through both, tinted.
  vec3 base = gl_FrontFacing ? vec3(0.88, 0.58, 0.3) : vec3(0.45, 0.55, 0.72);
  if (textured) base = texture(checker, surfaceUv).rgb * (gl_FrontFacing ? vec3(1.0) : vec3(0.6, 0.7, 0.95));
  color = vec4(base * (0.16 + 0.66 * key + fill) + 0.22 * specular, 1.0);
}`;

const LINE_VS = `#version 300 es
layout(location = 0) in vec3 position;
uniform mat4 viewProjection;
uniform float pointSize;
uniform vec2 offset; // in clip units, to thicken lines by drawing them again beside themselves
void main() {
  gl_Position = viewProjection * vec4(position, 1.0);
  gl_Position.xy += offset * gl_Position.w;
  gl_PointSize = pointSize;
}`;

const LINE_FS = `#version 300 es
precision highp float;
uniform vec4 tint;
uniform bool roundPoints;
out vec4 color;
void main() {
  if (roundPoints && length(gl_PointCoord - 0.5) > 0.5) discard;
  color = tint;
}`;

export const COLORS = {
  background: [0.11, 0.122, 0.141],
  wireframe: [0.08, 0.06, 0.05, 0.5],
  sharp: [0.95, 0.2, 0.55, 1], // infinitely sharp creases and corners (style.css: --sharp)
  semi: [1, 0.55, 0.78, 1], // semi-sharp creases (style.css: --semi)
  sharpHidden: [0.95, 0.2, 0.55, 0.3],
  hover: [1, 1, 1, 1],
  cage: [0.35, 0.78, 1, 0.95],
  cageHidden: [0.35, 0.78, 1, 0.16],
  cageDense: [0.35, 0.78, 1, 0.1],
};

/**
 * Above this many cage edges the cage is drawn faint, as lines only: drawn in full, with a dot
 * per vertex and its hidden lines, a dense scan (a 97k-triangle horse has about 145k edges)
 * covers its own surface in solid blue. The cage checkbox still hides it altogether.
 */
export const DENSE_CAGE_EDGES = 20_000;

function compile(gl, type, source) {
  const shader = gl.createShader(type);
  gl.shaderSource(shader, source);
  gl.compileShader(shader);
  if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(shader));
  return shader;
}

function program(gl, vertexSource, fragmentSource, uniforms) {
  const p = gl.createProgram();
  gl.attachShader(p, compile(gl, gl.VERTEX_SHADER, vertexSource));
  gl.attachShader(p, compile(gl, gl.FRAGMENT_SHADER, fragmentSource));
  gl.linkProgram(p);
  if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
  return { program: p, ...Object.fromEntries(uniforms.map((name) => [name, gl.getUniformLocation(p, name)])) };
}

/**
 * The UV checker: 8 × 8 squares per unit of UV, light ones shaded from orange (u = 0) to gold
 * (u = 1) and dark ones from slate to blue along v, so that the direction of the layout and its
 * seams show; drawn on a canvas, no image file.
 */
function checkerCanvas(size = 512, squares = 8) {
  const canvas = new OffscreenCanvas(size, size);
  const context = canvas.getContext('2d');
  const cell = size / squares;
  for (let j = 0; j < squares; j++) {
    for (let i = 0; i < squares; i++) {
      const [u, v] = [(i + 0.5) / squares, (j + 0.5) / squares];
      context.fillStyle = (i + j) % 2 === 0
        ? `rgb(${235 - 10 * u} ${150 + 60 * u} ${80 - 40 * u})`
        : `rgb(${55 + 10 * v} ${62 + 20 * v} ${80 + 70 * v})`;
      // Canvas rows run down; UV v runs up.
      context.fillRect(i * cell, size - (j + 1) * cell, cell, cell);
    }
  }
  return canvas;
}

/** Positions, optional normals and UVs, and index groups on one vertex array each. */
class MeshBuffers {
  constructor(gl) {
    this.gl = gl;
    this.positions = gl.createBuffer();
    this.normals = gl.createBuffer();
    this.uvs = gl.createBuffer();
    this.vertexCount = 0;
    this.hasUvs = false;
    this.groups = new Map(); // name → { vao, buffer, count }
  }

  setVertices(positions, normals, uvs = null) {
    const { gl } = this;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.positions);
    gl.bufferData(gl.ARRAY_BUFFER, positions, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.normals);
    gl.bufferData(gl.ARRAY_BUFFER, normals ?? new Float32Array(positions.length), gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, this.uvs);
    gl.bufferData(gl.ARRAY_BUFFER, uvs ?? new Float32Array((positions.length / 3) * 2), gl.STATIC_DRAW);
    this.vertexCount = positions.length / 3;
    this.hasUvs = uvs !== null;
  }

  /**
   * New positions (and normals) for the same vertices, written over the buffers in place: the
   * animation's frames. The index groups stay.
   */
  updateVertices(positions, normals = null) {
    const { gl } = this;
    if (positions.length !== 3 * this.vertexCount) {
      throw new Error(`updateVertices: ${positions.length / 3} vertices for buffers of ${this.vertexCount}`);
    }
    gl.bindBuffer(gl.ARRAY_BUFFER, this.positions);
    gl.bufferSubData(gl.ARRAY_BUFFER, 0, positions);
    if (normals) {
      gl.bindBuffer(gl.ARRAY_BUFFER, this.normals);
      gl.bufferSubData(gl.ARRAY_BUFFER, 0, normals);
    }
  }

  /** Sets the index buffer of group `name` (triangles, edge pairs, ...); null removes it. */
  setGroup(name, indices) {
    const { gl } = this;
    let group = this.groups.get(name);
    if (!indices || indices.length === 0) {
      if (group) group.count = 0;
      return;
    }
    if (!group) {
      const vao = gl.createVertexArray();
      const buffer = gl.createBuffer();
      gl.bindVertexArray(vao);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.positions);
      gl.enableVertexAttribArray(0);
      gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.normals);
      gl.enableVertexAttribArray(1);
      gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.uvs);
      gl.enableVertexAttribArray(2);
      gl.vertexAttribPointer(2, 2, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffer);
      gl.bindVertexArray(null);
      group = { vao, buffer, count: 0 };
      this.groups.set(name, group);
    }
    gl.bindVertexArray(group.vao);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    gl.bindVertexArray(null);
    group.count = indices.length;
  }

  /** Draws group `name`; `allVertices` draws every vertex as a point instead of its indices. */
  draw(name, mode, { allVertices = false } = {}) {
    const group = this.groups.get(name);
    if (!group || group.count === 0) return;
    const { gl } = this;
    gl.bindVertexArray(group.vao);
    if (allVertices) gl.drawArrays(gl.POINTS, 0, this.vertexCount);
    else gl.drawElements(mode, group.count, gl.UNSIGNED_INT, 0);
    gl.bindVertexArray(null);
  }
}

export class Renderer {
  constructor(gl) {
    this.gl = gl;
    this.surface = program(gl, SURFACE_VS, SURFACE_FS, ['viewProjection', 'eye', 'light', 'smoothShading', 'textured', 'checker']);
    this.lines = program(gl, LINE_VS, LINE_FS, ['viewProjection', 'tint', 'pointSize', 'roundPoints', 'offset']);
    this.refined = new MeshBuffers(gl);
    this.surfaceMesh = new MeshBuffers(gl);
    this.cage = new MeshBuffers(gl);
    this.checker = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, this.checker);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, gl.RGBA, gl.UNSIGNED_BYTE, checkerCanvas());
    gl.generateMipmap(gl.TEXTURE_2D);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR_MIPMAP_LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.REPEAT);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.REPEAT);
    const anisotropic = gl.getExtension('EXT_texture_filter_anisotropic');
    if (anisotropic) gl.texParameterf(gl.TEXTURE_2D, anisotropic.TEXTURE_MAX_ANISOTROPY_EXT, 8);
  }

  /**
   * The refined mesh: `surface` ({ positions, normals, uvs?, triangles }) is drawn shaded, the
   * checker on it when it has `uvs`; `edges` (and later `sharpEdges`) of `positions` as lines.
   */
  setRefined({ positions, surface, edges, sharpEdges = null }) {
    this.surfaceMesh.setVertices(surface.positions, surface.normals, surface.uvs ?? null);
    this.surfaceMesh.setGroup('triangles', surface.triangles);
    this.refined.setVertices(positions, null);
    this.refined.setGroup('edges', edges);
    this.refined.setGroup('sharp', sharpEdges);
  }

  /**
   * A frame of the animation: new `positions` of the refined mesh (wireframe) and of the shaded
   * surface (`surfacePositions`, `surfaceNormals`: the same arrays without UVs, else gathered
   * through toDrawable's origins). Same vertices as the last setRefined; the topology stays.
   */
  updateRefined({ positions, surfacePositions, surfaceNormals }) {
    this.refined.updateVertices(positions);
    this.surfaceMesh.updateVertices(surfacePositions, surfaceNormals);
  }

  /** Moves the cage's vertices (the animation's deformed cage); edges and tags stay. */
  updateCage(positions) {
    this.cage.updateVertices(positions);
  }

  /** The control cage: its vertices as dots and its edges as lines; then its tags. */
  setCage({ positions, edges }) {
    this.cage.setVertices(positions, null);
    this.cage.setGroup('edges', edges);
  }

  /**
   * The cage's tags: `sharp` and `semi` edges (vertex pairs), sharp `corners` (vertices) and the
   * `hover` edge; a missing one is removed.
   */
  setCageTags({ sharp = null, semi = null, corners = null, hover = null }) {
    this.cage.setGroup('sharp', sharp);
    this.cage.setGroup('semi', semi);
    this.cage.setGroup('corners', corners);
    this.cage.setGroup('hover', hover);
  }

  /** How many edges the cage has (what the checkbox shows or hides). */
  cageEdgeCount() {
    return (this.cage.groups.get('edges')?.count ?? 0) / 2;
  }

  /**
   * The wireframe colour, fading out as edges get closer on screen than a few pixels, where
   * lines would only darken the surface. The spacing is estimated from the mesh's projected
   * size and its number of edges.
   */
  wireframeColor(camera, heightPixels) {
    const edges = (this.refined.groups.get('edges')?.count ?? 0) / 2;
    const [r, g, b, a] = COLORS.wireframe;
    if (edges === 0) return [r, g, b, 0];
    const radiusPixels = camera.projectedRadius(heightPixels);
    // About half the surface faces the viewer; a quad mesh has about two edges per face.
    const facePixels = (Math.PI * radiusPixels * radiusPixels * 2) / Math.max(edges / 2, 1);
    const spacing = Math.sqrt(facePixels);
    const t = Math.min(1, Math.max(0, (spacing - 3) / 9));
    return [r, g, b, a * t * t * (3 - 2 * t)];
  }

  draw(camera, { smooth = true, wireframe = true, cage = true, texture = true } = {}) {
    const { gl } = this;
    const width = gl.drawingBufferWidth;
    const height = gl.drawingBufferHeight;
    gl.viewport(0, 0, width, height);
    gl.clearColor(...COLORS.background, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    const { viewProjection, eye, light } = camera.view(width / Math.max(height, 1));

    gl.enable(gl.DEPTH_TEST);
    gl.depthFunc(gl.LEQUAL);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
    gl.disable(gl.CULL_FACE); // open meshes show their inside
    // Pushes the surface back a little so that its own edges, drawn on it, win the depth test.
    gl.enable(gl.POLYGON_OFFSET_FILL);
    gl.polygonOffset(1, 2);
    const s = this.surface;
    gl.useProgram(s.program);
    gl.uniformMatrix4fv(s.viewProjection, false, viewProjection);
    gl.uniform3fv(s.eye, eye);
    gl.uniform3fv(s.light, light);
    gl.uniform1i(s.smoothShading, smooth ? 1 : 0);
    gl.uniform1i(s.textured, texture && this.surfaceMesh.hasUvs ? 1 : 0);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, this.checker);
    gl.uniform1i(s.checker, 0);
    this.surfaceMesh.draw('triangles', gl.TRIANGLES);
    gl.disable(gl.POLYGON_OFFSET_FILL);

    const l = this.lines;
    gl.useProgram(l.program);
    gl.uniformMatrix4fv(l.viewProjection, false, viewProjection);
    gl.uniform1i(l.roundPoints, 0);
    gl.uniform1f(l.pointSize, 1);
    gl.uniform2f(l.offset, 0, 0);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.depthMask(false);
    if (wireframe) {
      gl.uniform4fv(l.tint, this.wireframeColor(camera, height));
      this.refined.draw('edges', gl.LINES);
      gl.uniform4fv(l.tint, COLORS.sharp);
      this.refined.draw('sharp', gl.LINES);
    }
    if (cage) {
      const ratio = Math.min(devicePixelRatio, 2);
      const dense = this.cageEdgeCount() > DENSE_CAGE_EDGES;
      // The cage in front of the surface solid, behind it faint: it usually encloses the surface.
      // A dense cage: its front faint, no hidden lines.
      const passes = dense ? [[gl.LEQUAL, COLORS.cageDense]] : [[gl.GREATER, COLORS.cageHidden], [gl.LEQUAL, COLORS.cage]];
      for (const [depthFunc, color] of passes) {
        const front = depthFunc === gl.LEQUAL;
        gl.depthFunc(depthFunc);
        gl.uniform4fv(l.tint, color);
        gl.uniform1f(l.pointSize, 1);
        gl.uniform1i(l.roundPoints, 0);
        this.cage.draw('edges', gl.LINES);
        const thick = (name, tint, pixels) => {
          gl.uniform4fv(l.tint, tint);
          for (let i = 0; i < pixels; i++) {
            for (let j = 0; j < pixels; j++) {
              gl.uniform2f(l.offset, (2 * (i - (pixels - 1) / 2)) / width, (2 * (j - (pixels - 1) / 2)) / height);
              this.cage.draw(name, gl.LINES);
            }
          }
          gl.uniform2f(l.offset, 0, 0);
        };
        const crease = Math.round(2 * ratio);
        thick('semi', front ? COLORS.semi : COLORS.sharpHidden, front ? crease : 1);
        thick('sharp', front ? COLORS.sharp : COLORS.sharpHidden, front ? crease + 1 : 1);
        if (front) thick('hover', COLORS.hover, crease + 1);
        gl.uniform1i(l.roundPoints, 1);
        if (!dense) {
          gl.uniform4fv(l.tint, color);
          gl.uniform1f(l.pointSize, 6 * ratio);
          this.cage.draw('edges', gl.POINTS, { allVertices: true });
        }
        gl.uniform4fv(l.tint, front ? COLORS.sharp : COLORS.sharpHidden);
        gl.uniform1f(l.pointSize, 9 * ratio);
        this.cage.draw('corners', gl.POINTS);
      }
    }
    gl.depthFunc(gl.LEQUAL);
    gl.depthMask(true);
    gl.disable(gl.BLEND);
  }
}
