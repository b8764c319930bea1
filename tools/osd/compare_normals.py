#!/usr/bin/env python3
"""How far one OBJ's vertex normals (`vn`) are from a reference's, vertex by vertex, where both
are the same uniform refinement of one base mesh numbered by different libraries: subsurf's
`--limit` output against `osd_refine --limit` (OpenSubdiv), or OpenSubdiv's float build against
its double one. Prints the largest difference of a normal component and how many components
differ by more than 1e-5 and 1e-4.

    tools/osd/compare_normals.py --scheme catmark|loop --levels N BASE.obj REFERENCE.obj OTHER.obj

The vertices are matched through the faces, as DEVELOPERS.md ("How our output corresponds to
OpenSubdiv's") describes: Loop numbers faces and their corners alike in both; Catmull-Clark's
child faces match by index at level 1, each quad parent's child at corner k rotated by k, and
deeper the child at corner j of a face rotated by r is the other's child at corner (j + r) mod 4,
rotated by that. Two outputs of one library (the same numbering) match with `--same`.
"""
import argparse


def read(path):
    normals, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith('vn '):
                normals.append(tuple(map(float, line.split()[1:4])))
            elif line.startswith('f '):
                faces.append([int(c.split('/')[0]) - 1 for c in line.split()[1:]])
    return normals, faces


def base_sizes(path):
    with open(path) as f:
        return [len(line.split()) - 1 for line in f if line.startswith('f ')]


def catmark_order(sizes, levels):
    """Per face of subsurf's last level, the index of OpenSubdiv's matching face."""
    rotations = [k if n == 4 else 0 for n in sizes for k in range(n)]
    order = list(range(len(rotations)))
    for _ in range(levels - 1):
        order = [4 * q + (j + r) % 4 for q, r in zip(order, rotations) for j in range(4)]
        rotations = [(j + r) % 4 for r in rotations for j in range(4)]
    return order, rotations


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--scheme', choices=['catmark', 'loop'], required=True)
    parser.add_argument('--levels', type=int, required=True)
    parser.add_argument('--same', action='store_true', help='both files number alike')
    parser.add_argument('base')
    parser.add_argument('reference')
    parser.add_argument('other')
    args = parser.parse_args()
    ref_normals, ref_faces = read(args.reference)
    normals, faces = read(args.other)
    if len(ref_faces) != len(faces):
        raise SystemExit(f'{len(ref_faces)} faces against {len(faces)}: not the same refinement')
    if args.same or args.scheme == 'loop':
        order, rotations = range(len(faces)), [0] * len(faces)
    else:
        order, rotations = catmark_order(base_sizes(args.base), args.levels)
    to_ref = {}
    for face, at, r in zip(faces, order, rotations):
        ref = ref_faces[at]
        for m, v in enumerate(face):
            to_ref[v] = ref[(m + r) % len(ref)]
    largest, over5, over4 = 0.0, 0, 0
    for v, w in to_ref.items():
        for a, b in zip(normals[v], ref_normals[w]):
            d = abs(a - b)
            largest = max(largest, d)
            over5 += d > 1e-5
            over4 += d > 1e-4
    print(f'{args.other} against {args.reference}: {len(to_ref)} vertices, largest difference '
          f'{largest:.2e}, components over 1e-5: {over5}, over 1e-4: {over4}')


if __name__ == '__main__':
    main()
