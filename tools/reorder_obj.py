#!/usr/bin/env python3
"""Rewrites an OBJ (its v and f lines only) with its faces in another order and its vertices
renamed in the order the faces first name them, to measure how much a cage's vertex and face
order costs a frame (DEVELOPERS.md, twenty-ninth session).

    python3 tools/reorder_obj.py IN.obj OUT.obj firstuse|morton

firstuse keeps the faces in order; morton sorts them by a 30-bit Morton code of their
centroids. Prints the vertex and face counts and how many steps between consecutive corners of
a face jump more than 1024 vertices."""
import sys


def read(path):
    vertices, faces = [], []
    for line in open(path):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == 'v':
            vertices.append(tuple(map(float, parts[1:4])))
        elif parts[0] == 'f':
            faces.append([int(c.split('/')[0]) - 1 for c in parts[1:]])
    return vertices, faces


def morton(cell):
    """Interleaves the bits of three 10-bit coordinates."""
    code = 0
    for bit in range(10):
        for axis, c in enumerate(cell):
            code |= ((c >> bit) & 1) << (3 * bit + axis)
    return code


def main():
    source, target, mode = sys.argv[1:4]
    vertices, faces = read(source)
    if mode == 'morton':
        low = [min(v[i] for v in vertices) for i in range(3)]
        high = [max(v[i] for v in vertices) for i in range(3)]

        def key(face):
            centre = [sum(vertices[v][i] for v in face) / len(face) for i in range(3)]
            span = [high[i] - low[i] or 1.0 for i in range(3)]
            return morton([int(1023 * (centre[i] - low[i]) / span[i]) for i in range(3)])

        faces.sort(key=key)
    elif mode != 'firstuse':
        sys.exit(f'reorder_obj: unknown order {mode!r}; use firstuse or morton')
    label, order = {}, []
    for v in [v for face in faces for v in face] + list(range(len(vertices))):
        if v not in label:
            label[v] = len(order)
            order.append(v)
    with open(target, 'w') as out:
        for v in order:
            out.write('v %r %r %r\n' % vertices[v])
        for face in faces:
            out.write('f ' + ' '.join(str(label[v] + 1) for v in face) + '\n')
    jumps = sum(abs(label[a] - label[b]) > 1024 for face in faces for a, b in zip(face, face[1:]))
    print(len(vertices), 'vertices,', len(faces), 'faces,', jumps, 'jumps')


main()
