#!/usr/bin/env python3
"""Checks the closed forms of Loop's limit at the children of a regular vertex and of a regular
edge (DEVELOPERS.md, "Loop's regular limit in closed form from the level before") against the
limit positions and normals that the CLI writes.

    subsurf --scheme loop --levels 1 --ignore-uv MESH.obj -o l1.obj
    subsurf --scheme loop --levels 2 --ignore-uv --limit MESH.obj -o l2.obj
    python3 tools/loop_regular_limit.py l1.obj l2.obj

For a closed, untagged triangle mesh. A level-1 vertex's child is level-2 vertex of the same
index (Loop numbers the vertices' children first); an edge's child is found by its position.
"""
import math
import sys


def read_obj(path):
    """Positions, triangles (0-based) and normals of an OBJ file."""
    positions, faces, normals = [], [], []
    with open(path) as f:
        for line in f:
            if line.startswith('v '):
                positions.append(tuple(map(float, line.split()[1:4])))
            elif line.startswith('vn '):
                normals.append(tuple(map(float, line.split()[1:4])))
            elif line.startswith('f '):
                faces.append(tuple(int(t.split('/')[0]) - 1 for t in line.split()[1:]))
    return positions, faces, normals


def add(*points):
    return tuple(sum(x) for x in zip(*points))


def sub(p, q):
    return tuple(x - y for x, y in zip(p, q))


def scale(s, p):
    return tuple(s * x for x in p)


def unit_cross(a, b):
    c = (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
    length = math.sqrt(sum(x * x for x in c))
    return tuple(x / length for x in c)


def angle(a, b):
    return math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b)))))


def vertex_child(v, q):
    """Limit position and normal at a regular vertex's child: `v` with its ring `q`
    counter-clockwise. The tangents are scaled by positive constants, which keeps the normal."""
    position = scale(1 / 12, add(scale(6, v), *q))
    d = [sub(q[k], q[k + 3]) for k in range(3)]
    t1 = add(scale(2, d[0]), d[1], scale(-1, d[2]))
    t2 = add(d[1], d[2])
    return position, unit_cross(t1, t2)


def edge_child(a, b, c, d, a2, a3, a4, b2, b3, b4):
    """Limit position and normal at the child of edge (a, b): c opposite on the left face, d on
    the right; a's ring is b, c, a2, a3, a4, d and b's is a, d, b2, b3, b4, c."""
    position = scale(1 / 192, add(scale(63, add(a, b)), scale(26, add(c, d)),
                                  scale(3, add(a2, a4, b2, b4)), a3, b3))
    t1 = add(scale(13, sub(a, b)), scale(2, sub(add(a2, a4), add(b2, b4))), sub(a3, b3))
    t2 = add(scale(6, sub(d, c)), sub(a4, a2), sub(b2, b4))
    return position, unit_cross(t1, t2)


def main(level1, level2):
    points, faces, _ = read_obj(level1)
    limit, _, limit_normals = read_obj(level2)
    # The third corner of the face that holds directed edge (a, b).
    third = {}
    for a, b, c in faces:
        third[(a, b)], third[(b, c)], third[(c, a)] = c, a, b
    first_out = {}
    for a, b in third:
        first_out.setdefault(a, b)

    def ring(v):
        """v's neighbours counter-clockwise, or None on a boundary."""
        q0 = first_out[v]
        found, q = [q0], q0
        while len(found) <= 12:
            q = third.get((v, q))
            if q is None:
                return None
            if q == q0:
                return found
            found.append(q)
        return None

    def rotated(r, start):
        k = r.index(start)
        return r[k:] + r[:k]

    position_error, angles = [], []

    def compare(got, i):
        position, normal = got
        position_error.append(max(abs(x - y) for x, y in zip(position, limit[i])))
        angles.append(angle(normal, limit_normals[i]))

    regular = {}
    for v in range(len(points)):
        r = ring(v)
        if r is not None and len(r) == 6:
            regular[v] = r
            compare(vertex_child(points[v], [points[i] for i in r]), v)
    vertices = len(angles)

    by_position = {}
    for i, p in enumerate(limit):
        by_position.setdefault(tuple(round(x, 5) for x in p), i)
    unmatched = 0
    for (a, b), c in third.items():
        if a > b or a not in regular or b not in regular:
            continue
        d = third[(b, a)]
        ra, rb = rotated(regular[a], b), rotated(regular[b], a)
        assert ra[1] == c and ra[5] == d and rb[1] == d and rb[5] == c
        got = edge_child(*(points[i] for i in [a, b, c, d, *ra[2:5], *rb[2:5]]))
        i = by_position.get(tuple(round(x, 5) for x in got[0]))
        if i is None:
            unmatched += 1
        else:
            compare(got, i)

    edges = len(angles) - vertices
    ordered = sorted(angles)
    print(f'vertex children {vertices}, edge children {edges} (unmatched {unmatched}): '
          f'{(vertices + edges) / len(limit):.1%} of {len(limit)} points')
    print(f'position: max difference {max(position_error):.2e}')
    print(f'normal: median {ordered[len(ordered) // 2]:.2e} rad, max {ordered[-1]:.2e} rad')


if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
