#!/usr/bin/env python3
"""Converts a PLY (ascii or binary_little_endian) or OFF mesh to OBJ with `v` and `f` lines only.

    mesh_to_obj.py IN.ply|IN.off OUT.obj [--comment TEXT]...

PLY: the vertex element's x, y, z (other vertex properties, e.g. normals, are read and dropped)
and the face element's vertex index list (`vertex_indices` or `vertex_index`). OFF: the usual
`OFF` / counts / vertices / `n i0 i1 ...` layout. Both index vertices from 0; OBJ from 1, so every
index is written plus one. Single-precision inputs are written with the fewest significant digits
that read back as the same float; doubles with repr(). Vertex and face order are kept.
"""

import argparse
import struct
import sys

PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B",
    "short": "h", "int16": "h", "ushort": "H", "uint16": "H",
    "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


def read_ply(data):
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if header[0] != "ply":
        raise SystemExit("not a PLY file")
    fmt = None
    elements = []  # (name, count, [(name, type) or (name, ("list", count type, item type))])
    for line in header[1:]:
        words = line.split()
        if not words or words[0] in ("comment", "obj_info", "end_header"):
            continue
        if words[0] == "format":
            fmt = words[1]
        elif words[0] == "element":
            elements.append((words[1], int(words[2]), []))
        elif words[0] == "property":
            if words[1] == "list":
                elements[-1][2].append((words[4], ("list", words[2], words[3])))
            else:
                elements[-1][2].append((words[2], words[1]))
    if fmt not in ("ascii", "binary_little_endian"):
        raise SystemExit(f"PLY format {fmt} is not supported")
    vertices, faces, single = [], [], True
    pos = end
    tokens = data[end:].split() if fmt == "ascii" else None
    tok = 0
    for name, count, props in elements:
        for _ in range(count):
            record = {}
            for pname, ptype in props:
                if isinstance(ptype, tuple):
                    if fmt == "ascii":
                        n = int(tokens[tok]); tok += 1
                        items = [int(t) for t in tokens[tok:tok + n]]; tok += n
                    else:
                        c = "<" + PLY_TYPES[ptype[1]]
                        (n,) = struct.unpack_from(c, data, pos); pos += struct.calcsize(c)
                        i = "<%d%s" % (n, PLY_TYPES[ptype[2]])
                        items = list(struct.unpack_from(i, data, pos)); pos += struct.calcsize(i)
                    record[pname] = items
                else:
                    if fmt == "ascii":
                        value = float(tokens[tok]); tok += 1
                    else:
                        c = "<" + PLY_TYPES[ptype]
                        (value,) = struct.unpack_from(c, data, pos); pos += struct.calcsize(c)
                    record[pname] = value
            if name == "vertex":
                single = single and all(dict(props)[k] in ("float", "float32") for k in "xyz")
                vertices.append((record["x"], record["y"], record["z"]))
            elif name == "face":
                faces.append(record.get("vertex_indices", record.get("vertex_index")))
    return vertices, faces, single


def read_off(text):
    words = [w for line in text.splitlines() for w in line.split("#")[0].split()]
    if words[0] != "OFF":
        raise SystemExit("not an OFF file")
    nv, nf = int(words[1]), int(words[2])
    at = 4
    vertices = []
    for _ in range(nv):
        vertices.append(tuple(float(w) for w in words[at:at + 3]))
        at += 3
    faces = []
    for _ in range(nf):
        n = int(words[at])
        faces.append([int(w) for w in words[at + 1:at + 1 + n]])
        at += 1 + n
    return vertices, faces, False


def shortest_float32(x):
    exact = struct.pack("<f", x)
    for digits in range(1, 10):
        text = "%.*g" % (digits, x)
        if struct.pack("<f", float(text)) == exact:
            return text
    raise AssertionError(x)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--comment", action="append", default=[])
    args = parser.parse_args(argv)
    with open(args.input, "rb") as f:
        data = f.read()
    if data.startswith(b"ply"):
        vertices, faces, single = read_ply(data)
    else:
        vertices, faces, single = read_off(data.decode("ascii"))
    for face in faces:
        if len(face) < 3 or min(face) < 0 or max(face) >= len(vertices):
            raise SystemExit(f"bad face {face}")
    fmt = shortest_float32 if single else repr
    with open(args.output, "w", encoding="ascii", newline="\n") as out:
        for line in args.comment:
            out.write("# " + line + "\n")
        for v in vertices:
            out.write("v " + " ".join(fmt(c) for c in v) + "\n")
        for face in faces:
            out.write("f " + " ".join(str(i + 1) for i in face) + "\n")
    print(f"{args.output}: {len(vertices)} vertices, {len(faces)} faces", file=sys.stderr)


if __name__ == "__main__":
    main(sys.argv[1:])
