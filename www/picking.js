// Picking a cage edge under the pointer, for crease editing. This is user interface, not mesh
// geometry, so it lives in the page: the edges come from subsurf's edgeList, and they are
// projected with the same view-projection matrix the renderer draws them with.

/**
 * Projects `positions` (x, y, z per vertex) onto a canvas `width` × `height` CSS pixels:
 * x and y from its top left corner, and the depth (-1 near to 1 far), per vertex. A vertex at
 * or behind the eye gets NaN, so that no edge through it is picked.
 */
export function projectVertices(positions, viewProjection, width, height) {
  const m = viewProjection; // column-major
  const screen = new Float64Array(positions.length);
  for (let i = 0; i < positions.length; i += 3) {
    const x = positions[i];
    const y = positions[i + 1];
    const z = positions[i + 2];
    const w = m[3] * x + m[7] * y + m[11] * z + m[15];
    if (!(w > 1e-9)) {
      screen.fill(NaN, i, i + 3);
      continue;
    }
    screen[i] = ((m[0] * x + m[4] * y + m[8] * z + m[12]) / w + 1) * 0.5 * width;
    screen[i + 1] = (1 - (m[1] * x + m[5] * y + m[9] * z + m[13]) / w) * 0.5 * height;
    screen[i + 2] = (m[2] * x + m[6] * y + m[10] * z + m[14]) / w;
  }
  return screen;
}

/**
 * The index of the edge (`edges`: vertex pairs) nearest to the point (x, y) on screen, if it is
 * within `radius` pixels; -1 otherwise. `screen` is what projectVertices returned. Edges less
 * than a pixel farther than the nearest count as near as it, and of those the frontmost wins:
 * where a front and a back edge of the cage cross on screen, the user means the front one.
 */
export function pickEdge(edges, screen, x, y, radius) {
  const near = [];
  let nearest = Infinity;
  for (let e = 0; e < edges.length / 2; e++) {
    const a = 3 * edges[2 * e];
    const b = 3 * edges[2 * e + 1];
    const [ax, ay, bx, by] = [screen[a], screen[a + 1], screen[b], screen[b + 1]];
    if (Number.isNaN(ax) || Number.isNaN(bx)) continue;
    const dx = bx - ax;
    const dy = by - ay;
    const length2 = dx * dx + dy * dy;
    const t = length2 > 0 ? Math.min(1, Math.max(0, ((x - ax) * dx + (y - ay) * dy) / length2)) : 0;
    const distance = Math.hypot(ax + t * dx - x, ay + t * dy - y);
    if (distance > radius) continue;
    near.push({ e, distance, depth: screen[a + 2] + t * (screen[b + 2] - screen[a + 2]) });
    nearest = Math.min(nearest, distance);
  }
  let best = null;
  for (const candidate of near) {
    if (candidate.distance <= nearest + 1 && (!best || candidate.depth < best.depth)) best = candidate;
  }
  return best ? best.e : -1;
}

/** The canonical key of the edge between vertices a and b, either order. */
export const edgeKey = (a, b) => (a < b ? `${a},${b}` : `${b},${a}`);
