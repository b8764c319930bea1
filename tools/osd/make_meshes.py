#!/usr/bin/env python3
"""Procedural test and benchmark meshes for subsurf, written as OBJ (`v` and `f` lines, and `vt`
with `f v/vt` corners for a mesh that has UVs).

    make_meshes.py tests OUTDIR
        The small meshes under tests/meshes/ that the OpenSubdiv fixtures are made from.
    make_meshes.py repeated OUTDIR
        The small meshes with faces that repeat a vertex (tests/meshes/osd_nonmanifold/own_*).
    make_meshes.py torus --major U --minor V [--major-radius R] [--minor-radius r]
                         [--triangles] OUT.obj
        One torus (the benchmark meshes of tools/osd/far_perf.sh).

Torus layout (the same for every size, so other benchmarks can rebuild identical meshes):

- U segments around the main (z) axis, V segments around the tube; defaults R = 1.0, r = 0.25.
- Vertex (i, j), i in 0..U around the z axis, j in 0..V around the tube, has 0-based index
  i * V + j and position ((R + r cos b) cos a, (R + r cos b) sin a, r sin b) with
  a = 2 pi i / U and b = 2 pi j / V. Vertices are written in index order.
- Face (i, j) is written in the order i = 0..U-1 (outer), j = 0..V-1 (inner), as the quad
  (i, j), (i+1, j), (i+1, j+1), (i, j+1) (indices mod U and V; counter-clockwise seen from
  outside), or with --triangles as the two triangles (i, j), (i+1, j), (i+1, j+1) and
  (i, j), (i+1, j+1), (i, j+1), in that order.
- So a torus has U*V vertices and U*V quads (2*U*V triangles): 1000 x 1000 gives 1,000,000
  quads; 250 x 200 with --triangles gives 100,000 triangles.

Coordinates are printed with repr(), the shortest string that reads back as the same double.
"""

import argparse
import math
import os
import sys


def fmt(x):
    # Avoid "-0.0" so that files do not depend on the sign of a rounded zero.
    if x == 0.0:
        x = 0.0
    return repr(float(x))


def write_obj(path, vertices, faces, comment, uvs=None, face_uvs=None):
    with open(path, "w", encoding="ascii", newline="\n") as out:
        for line in comment.strip().splitlines():
            out.write("# " + line + "\n")
        for v in vertices:
            out.write("v " + " ".join(fmt(c) for c in v) + "\n")
        for uv in uvs or []:
            out.write("vt " + " ".join(fmt(c) for c in uv) + "\n")
        for k, f in enumerate(faces):
            if face_uvs is None:
                out.write("f " + " ".join(str(i + 1) for i in f) + "\n")
            else:
                out.write("f " + " ".join(f"{i + 1}/{t + 1}" for i, t in zip(f, face_uvs[k])) + "\n")


def torus(major, minor, major_radius=1.0, minor_radius=0.25, triangles=False):
    vertices = []
    for i in range(major):
        a = 2.0 * math.pi * i / major
        for j in range(minor):
            b = 2.0 * math.pi * j / minor
            ring = major_radius + minor_radius * math.cos(b)
            vertices.append((ring * math.cos(a), ring * math.sin(a), minor_radius * math.sin(b)))
    faces = []
    for i in range(major):
        for j in range(minor):
            p = i * minor + j
            q = ((i + 1) % major) * minor + j
            r = ((i + 1) % major) * minor + (j + 1) % minor
            s = i * minor + (j + 1) % minor
            if triangles:
                faces.append((p, q, r))
                faces.append((p, r, s))
            else:
                faces.append((p, q, r, s))
    return vertices, faces


def torus_uv(major, minor):
    """The torus's `vt` grid and each quad's corners in it, as subsurf's `shapes::torus_uv`:
    value (i, j) = (i / U, j / V) for i in 0..=U, j in 0..=V, so the first and last rows and
    columns meet at seams."""
    uvs = [(i / major, j / minor) for i in range(major + 1) for j in range(minor + 1)]
    value = lambda i, j: i * (minor + 1) + j
    face_uvs = [
        (value(i, j), value(i + 1, j), value(i + 1, j + 1), value(i, j + 1))
        for i in range(major)
        for j in range(minor)
    ]
    return uvs, face_uvs


def compact(vertices, faces):
    """Drops vertices no face uses and renumbers, keeping the order of the rest."""
    used = sorted({i for f in faces for i in f})
    new_index = {old: k for k, old in enumerate(used)}
    return [vertices[i] for i in used], [tuple(new_index[i] for i in f) for f in faces]


def grid_with_hole(n=8, hole=(3, 5)):
    """An n x n grid of unit quads in the xy plane (z a gentle bump), without the cells
    hole[0] <= x, y < hole[1]: an outer boundary and an inner one."""
    vertices = []
    for y in range(n + 1):
        for x in range(n + 1):
            z = 0.1 * math.sin(0.7 * x) * math.cos(0.5 * y)
            vertices.append((float(x), float(y), z))
    faces = []
    for y in range(n):
        for x in range(n):
            if hole[0] <= x < hole[1] and hole[0] <= y < hole[1]:
                continue
            a = y * (n + 1) + x
            faces.append((a, a + 1, a + n + 2, a + n + 1))
    return compact(vertices, faces)


def mixed_ngons_open():
    """A hexagon ringed by quads and pentagons, with triangles hanging off the quads: faces of
    3, 4, 5 and 6 sides and one boundary loop."""
    vertices = []
    hexagon = []
    for k in range(6):
        a = math.pi * k / 3.0
        hexagon.append(len(vertices))
        vertices.append((math.cos(a), math.sin(a), 0.15 * (k % 2)))
    outer = []
    for k in range(6):
        a = math.pi * k / 3.0
        outer.append(len(vertices))
        vertices.append((2.2 * math.cos(a), 2.2 * math.sin(a), -0.2 + 0.1 * (k % 3)))
    faces = [tuple(hexagon)]
    for k in range(6):
        k1 = (k + 1) % 6
        mid = 0.5 * (2 * k + 1) * math.pi / 3.0
        if k % 2 == 0:
            faces.append((hexagon[k], outer[k], outer[k1], hexagon[k1]))
            tip = len(vertices)
            vertices.append((3.2 * math.cos(mid), 3.2 * math.sin(mid), 0.3))
            faces.append((outer[k1], outer[k], tip))
        else:
            m = len(vertices)
            vertices.append((2.6 * math.cos(mid), 2.6 * math.sin(mid), 0.1))
            faces.append((hexagon[k], outer[k], m, outer[k1], hexagon[k1]))
    return vertices, faces


def prism_mixed_closed():
    """A closed hexagonal prism: a hexagon on top, the bottom split into a triangle and a
    pentagon, and one side quad split into two triangles."""
    vertices = []
    for z, radius in ((0.0, 1.0), (1.5, 0.8)):
        for k in range(6):
            a = math.pi * k / 3.0 + 0.1 * z
            vertices.append((radius * math.cos(a), radius * math.sin(a), z + 0.05 * (k % 2)))
    bottom = list(range(6))
    top = list(range(6, 12))
    faces = [tuple(top), (bottom[2], bottom[1], bottom[0]), (bottom[0], bottom[5], bottom[4], bottom[3], bottom[2])]
    for k in range(6):
        k1 = (k + 1) % 6
        a, b, c, d = bottom[k], bottom[k1], top[k1], top[k]
        if k == 3:
            faces.append((a, b, c))
            faces.append((a, c, d))
        else:
            faces.append((a, b, c, d))
    return vertices, faces


def pentagonal_prism_closed():
    vertices = []
    for z in (0.0, 1.0):
        for k in range(5):
            a = 2.0 * math.pi * k / 5.0
            vertices.append((math.cos(a), math.sin(a), z))
    faces = [tuple(range(4, -1, -1)), tuple(range(5, 10))]
    for k in range(5):
        k1 = (k + 1) % 5
        faces.append((k, k1, 5 + k1, 5 + k))
    return vertices, faces


def check_oriented_manifold(name, vertices, faces):
    """Every directed edge used once, every edge by at most two faces, every vertex used."""
    directed = set()
    for f in faces:
        for k in range(len(f)):
            e = (f[k], f[(k + 1) % len(f)])
            if e in directed:
                raise SystemExit(f"{name}: directed edge {e} used twice (bad orientation)")
            directed.add(e)
    used = {i for f in faces for i in f}
    if len(used) != len(vertices):
        raise SystemExit(f"{name}: {len(vertices) - len(used)} unused vertices")


def single_triangle():
    return [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.25, 0.8, 0.1)], [(0, 1, 2)]


def single_pentagon():
    vertices = []
    for k in range(5):
        a = 2.0 * math.pi * k / 5.0 + 0.3
        vertices.append((math.cos(a), 0.8 * math.sin(a), 0.1 * (k % 2)))
    return vertices, [tuple(range(5))]


def cone_uv(n=80):
    """A closed cone as three.js's ConeGeometry lays out its UVs, welded: an apex joining n
    triangles, a band of n quads, and a base of n triangles round a centre. The apex has a UV
    per face (n values at one vertex), the band a seam where u wraps from 1 to 0, and the base a
    disc of UVs of its own (a seam along the base ring). Both hubs have valence n."""
    vertices = [(0.0, 1.0, 0.0)]
    for y, r in ((0.0, 0.6), (-0.5, 1.0)):
        for i in range(n):
            a = 2.0 * math.pi * i / n
            vertices.append((r * math.sin(a), y, r * math.cos(a)))
    vertices.append((0.0, -0.5, 0.0))
    top, low, centre = 1, 1 + n, 1 + 2 * n
    uvs, faces, face_uvs = [], [], []
    for i in range(n):
        uvs.append(((i + 0.5) / n, 1.0))
    for row, v in ((top, 0.6), (low, 0.0)):
        for i in range(n + 1):
            uvs.append((i / n, v))
    disc = len(uvs)
    for i in range(n):
        a = 2.0 * math.pi * i / n
        # Radius 0.45: no disc value equals a band value (by index they are a seam either way,
        # but a renderer's split copies with equal UVs are one vertex again).
        uvs.append((0.5 + 0.45 * math.sin(a), 0.5 + 0.45 * math.cos(a)))
    uvs.append((0.5, 0.5))
    side_uv = lambda row, i: n + row * (n + 1) + i
    for i in range(n):
        j = (i + 1) % n
        faces.append((0, top + i, top + j))
        face_uvs.append((i, side_uv(0, i), side_uv(0, i + 1)))
        faces.append((top + i, low + i, low + j, top + j))
        face_uvs.append((side_uv(0, i), side_uv(1, i), side_uv(1, i + 1), side_uv(0, i + 1)))
        faces.append((centre, low + j, low + i))
        face_uvs.append((disc + n, disc + j, disc + i))
    return vertices, faces, uvs, face_uvs


TEST_MESHES = {
    "own_torus_12x8": (lambda: torus(12, 8), "quad torus, 12 x 8 (see make_meshes.py for the layout)"),
    "own_grid_hole": (grid_with_hole, "8 x 8 quad grid with a 2 x 2 hole: two boundary loops"),
    "own_mixed_ngons_open": (mixed_ngons_open, "open mesh of triangles, quads, pentagons and a hexagon"),
    "own_prism_mixed_closed": (prism_mixed_closed, "closed hexagonal prism with triangles, quads, a pentagon"),
    "own_pentagonal_prism": (pentagonal_prism_closed, "closed pentagonal prism"),
    "own_single_triangle": (single_triangle, "one triangle"),
    "own_single_pentagon": (single_pentagon, "one pentagon"),
    "own_cone_uv": (cone_uv, "closed cone with UVs as three.js lays them out: two hubs of valence 80, one with a UV per face"),
}


def repeat_pole():
    """A closed cone over a hexagon whose apex quad repeats the apex: the degenerate edge is
    the only sharp edge at the apex, whose other edges are smooth."""
    vertices = []
    for k in range(6):
        a = 2.0 * math.pi * k / 6.0
        r = 1.0 + 0.1 * (k % 3)
        vertices.append((r * math.cos(a), r * math.sin(a), 0.05 * k))
    vertices.append((0.1, -0.05, 1.0))
    faces = [(0, 1, 6, 6)] + [(k, (k + 1) % 6, 6) for k in range(1, 6)] + [(0, 5, 4, 3, 2, 1)]
    return vertices, faces


def repeat_pair():
    """A 3 x 2 quad grid in which one quad is replaced by (5, 1, 2, 1): its edge 5-1 is shared
    with the quad next to it the usual way round, but the face uses the pairs 1-5 and 1-2
    twice, so OpenSubdiv splits them and makes 5-1 non-manifold."""
    vertices = [(i + 0.1 * j * j, j + 0.05 * i * i, 0.1 * ((i * j) % 3)) for j in range(3) for i in range(4)]
    v = lambda i, j: 4 * j + i
    faces = []
    for j in range(2):
        for i in range(3):
            faces.append((v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)))
    faces[1] = (5, 1, 2, 1)
    return vertices, faces


def repeat_sphere():
    """A hexagon (0, 1, 2, 0, 3, 4) that lists vertex 0 twice, far apart, closed by the
    triangles (0, 2, 1) and (0, 4, 3): every edge has two faces and vertex 0 one fan of four."""
    vertices = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.2), (0.6, 1.0, 0.1), (-1.0, 0.1, -0.2), (-0.4, -1.0, 0.3)]
    return vertices, [(0, 1, 2, 0, 3, 4), (0, 2, 1), (0, 4, 3)]


def repeat_slit():
    """A quad (0, 1, 0, 2) that runs to vertex 1 and back, and a triangle on its edge 0-2:
    vertex 1 has only the two split edges of the pair 0-1 (non-manifold, one face each)."""
    vertices = [(0.0, 0.0, 0.0), (1.0, 0.2, 0.1), (0.1, 1.0, -0.1), (-0.8, 0.6, 0.2)]
    return vertices, [(0, 1, 0, 2), (2, 0, 3)]


# Meshes whose faces repeat a vertex (no manifold check), for tests/meshes/osd_nonmanifold/.
REPEATED_VERTEX_MESHES = {
    "own_repeat_pole": (repeat_pole, "closed hexagonal cone whose apex quad repeats the apex"),
    "own_repeat_pair": (repeat_pair, "quad grid with a face that uses two vertex pairs twice"),
    "own_repeat_slit": (repeat_slit, "a quad that runs to a vertex and back, and a triangle"),
    "own_repeat_sphere": (repeat_sphere, "closed hexagon-and-triangles sphere with a vertex twice in one face"),
}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    tests = sub.add_parser("tests", help="write the small test meshes into a directory")
    tests.add_argument("outdir")
    repeated = sub.add_parser("repeated", help="write the meshes with faces that repeat a vertex")
    repeated.add_argument("outdir")
    t = sub.add_parser("torus", help="write one torus")
    t.add_argument("--major", type=int, required=True, help="segments around the main axis (U)")
    t.add_argument("--minor", type=int, required=True, help="segments around the tube (V)")
    t.add_argument("--major-radius", type=float, default=1.0)
    t.add_argument("--minor-radius", type=float, default=0.25)
    t.add_argument("--triangles", action="store_true", help="split every quad into two triangles")
    t.add_argument(
        "--uv",
        action="store_true",
        help="quads with vt lines: the (i/U, j/V) grid of subsurf's shapes::torus_uv, seams along both closing loops",
    )
    t.add_argument("out")
    args = parser.parse_args(argv)

    if args.command == "tests":
        os.makedirs(args.outdir, exist_ok=True)
        for name, (make, what) in TEST_MESHES.items():
            vertices, faces, *uv = make()
            check_oriented_manifold(name, vertices, faces)
            path = os.path.join(args.outdir, name + ".obj")
            write_obj(path, vertices, faces, "generated by tools/osd/make_meshes.py: " + what, *uv)
            print(path)
    elif args.command == "repeated":
        os.makedirs(args.outdir, exist_ok=True)
        for name, (make, what) in REPEATED_VERTEX_MESHES.items():
            vertices, faces = make()
            path = os.path.join(args.outdir, name + ".obj")
            write_obj(path, vertices, faces, "generated by tools/osd/make_meshes.py: " + what)
            print(path)
    else:
        if args.uv and args.triangles:
            parser.error("--uv goes with quads only")
        vertices, faces = torus(args.major, args.minor, args.major_radius, args.minor_radius, args.triangles)
        kind = "triangles" if args.triangles else "quads"
        uv = torus_uv(args.major, args.minor) if args.uv else ()
        write_obj(
            args.out,
            vertices,
            faces,
            f"generated by tools/osd/make_meshes.py torus --major {args.major} --minor {args.minor} "
            f"--major-radius {args.major_radius} --minor-radius {args.minor_radius}"
            f"{' --uv' if args.uv else ''}: {len(faces)} {kind}",
            *uv,
        )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
