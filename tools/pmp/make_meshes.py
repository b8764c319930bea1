#!/usr/bin/env python3
"""Mixed quad/triangle input meshes for the pmp-library fixtures (tools/pmp/make_fixtures.sh).

    python3 tools/pmp/make_meshes.py OUTPUT_DIR

Writes, deterministically (coordinates rounded to 6 decimals):

- pmp_house: subsurf's `shapes::house` (closed; four quad walls, a quad floor, a pyramid roof of
  four triangles): the eave vertices mix quads and triangles, the apex is all triangles.
- pmp_cylinder_tricaps: a closed cylinder of 8 x 2 quads whose caps are fans of 8 triangles
  around a centre vertex: the rims mix, the middle ring is all quads, the cap centres are all
  triangles (valence 8).
- pmp_grid_mixed: an open 5 x 4 grid on a bump, every third cell split into two triangles (the
  diagonal alternating): boundary vertices and edges of both kinds, interior vertices of every
  mix, and two corner triangles with two boundary edges each (cells (0, 0) and (0, 3)).
- pmp_torus_banded: a closed 8 x 6 torus whose first two rings of cells are triangulated and the
  others quads: one ring of all-triangle vertices (valence 6), two rings of mixed ones.
- pmp_prism5_mixed: a closed pentagonal prism whose odd sides are split into two triangles:
  pentagon face points and mixed vertices of valence 3 and 4.
"""
import math
import os
import sys


def write(path, name, positions, faces, note):
    with open(os.path.join(path, name + ".obj"), "w") as out:
        out.write(f"# {name}: {note} (tools/pmp/make_meshes.py)\n")
        for p in positions:
            out.write("v " + " ".join(f"{round(c, 6):.6f}".rstrip("0").rstrip(".") for c in p) + "\n")
        for f in faces:
            out.write("f " + " ".join(str(i + 1) for i in f) + "\n")


def house():
    positions = []
    for y in (-1.0, 0.3):
        positions += [(-1, y, -1), (1, y, -1), (1, y, 1), (-1, y, 1)]
    positions.append((0, 1.2, 0))
    faces = [(0, 1, 2, 3), (3, 2, 6, 7), (1, 0, 4, 5), (2, 1, 5, 6), (0, 3, 7, 4),
             (7, 6, 8), (6, 5, 8), (5, 4, 8), (4, 7, 8)]
    return positions, faces


def cylinder_tricaps(n=8):
    positions = []
    for z in (-1.0, 0.0, 1.0):
        for k in range(n):
            a = 2 * math.pi * k / n
            positions.append((math.cos(a), math.sin(a), z))
    bottom, top = len(positions), len(positions) + 1
    positions += [(0, 0, -1.4), (0, 0, 1.4)]
    faces = []
    for r in range(2):
        for k in range(n):
            k1 = (k + 1) % n
            faces.append((r * n + k, r * n + k1, (r + 1) * n + k1, (r + 1) * n + k))
    for k in range(n):
        k1 = (k + 1) % n
        faces.append((k1, k, bottom))
        faces.append((2 * n + k, 2 * n + k1, top))
    return positions, faces


def grid_mixed(nx=5, ny=4):
    positions = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = i / nx * 2 - 1, j / ny * 2 - 1
            positions.append((x, y, 0.3 * math.sin(2 * x) * math.cos(1.5 * y) + 0.05 * i * j / (nx * ny)))
    v = lambda i, j: j * (nx + 1) + i
    faces = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
            if (i + 2 * j) % 3 == 0:
                if (i + j) % 2 == 0:
                    faces += [(a, b, d), (b, c, d)]
                else:
                    faces += [(a, b, c), (a, c, d)]
            else:
                faces.append((a, b, c, d))
    return positions, faces


def torus_banded(u=8, w=6, major=1.0, minor=0.35):
    positions = []
    for i in range(u):
        for j in range(w):
            a, b = 2 * math.pi * i / u, 2 * math.pi * j / w
            r = major + minor * math.cos(b)
            positions.append((r * math.cos(a), r * math.sin(a), minor * math.sin(b)))
    v = lambda i, j: (i % u) * w + (j % w)
    faces = []
    for i in range(u):
        for j in range(w):
            a, b, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
            if j < 2:
                faces += [(a, b, c), (a, c, d)]
            else:
                faces.append((a, b, c, d))
    return positions, faces


def prism5_mixed(n=5):
    positions = []
    for z in (-1.0, 1.0):
        for k in range(n):
            a = 2 * math.pi * k / n
            positions.append((math.cos(a), math.sin(a), z * (1 + 0.1 * k)))
    faces = [tuple(reversed(range(n))), tuple(range(n, 2 * n))]
    for k in range(n):
        k1 = (k + 1) % n
        a, b, c, d = k, k1, n + k1, n + k
        faces += [(a, b, c), (a, c, d)] if k % 2 else [(a, b, c, d)]
    return positions, faces


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    write(out, "pmp_house", *house(), "closed, quads and triangles (subsurf shapes::house)")
    write(out, "pmp_cylinder_tricaps", *cylinder_tricaps(), "closed cylinder, triangle-fan caps")
    write(out, "pmp_grid_mixed", *grid_mixed(), "open 5 x 4 grid, every third cell two triangles")
    write(out, "pmp_torus_banded", *torus_banded(), "closed 8 x 6 torus, two rings triangulated")
    write(out, "pmp_prism5_mixed", *prism5_mixed(), "closed pentagonal prism, odd sides triangulated")


if __name__ == "__main__":
    main()
