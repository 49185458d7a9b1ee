#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the PLY and STL sample files of data/formats/ from real models of
data/ (cross.off, part.off, decimated_knight.off).

Independent of subfab's own C++ writers on purpose: the reader tests compare
what subfab reads from these files with what it reads from the source OFF
files, so a bug shared by our writer and reader cannot hide.
Only the standard library (struct) is used. Deterministic output.

    python3 scripts/make_format_samples.py   # from the repository root
"""
import os
import struct
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data")
OUT = os.path.join(DATA, "formats")


def read_off(path):
    """Minimal OFF reader (OFF keyword, counts, one record per line, triangles)."""
    with open(path) as f:
        tokens_lines = [line.split("#")[0].split() for line in f]
    lines = [t for t in tokens_lines if t]
    assert lines[0][0] == "OFF", path
    header = lines[0][1:] or lines[1]
    rest = lines[1:] if lines[0][1:] else lines[2:]
    nv, nf = int(header[0]), int(header[1])
    vertices = [tuple(float(x) for x in rest[i][:3]) for i in range(nv)]
    faces = []
    for i in range(nf):
        rec = rest[nv + i]
        n = int(rec[0])
        assert n == 3, "sample sources are triangle meshes"
        faces.append(tuple(int(x) for x in rec[1:4]))
    return vertices, faces


def f32(x):
    return struct.unpack("<f", struct.pack("<f", x))[0]


def normal(vertices, face):
    a, b, c = (vertices[i] for i in face)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    length = sum(x * x for x in n) ** 0.5
    return [x / length for x in n] if length > 0 else [0.0, 0.0, 0.0]


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(OUT, name), mode, newline="" if mode == "w" else None) as f:
        f.write(data)


def ply_ascii_with_extras(vertices, faces):
    """ascii, double coordinates (repr: exact), per-vertex colour, a face
    flag after the list, and an extra element with a list (both skipped)."""
    lines = ["ply", "format ascii 1.0", "comment from data/cross.off by scripts/make_format_samples.py",
             "element vertex %d" % len(vertices), "property double x", "property double y",
             "property double z", "property uchar red", "property uchar green", "property uchar blue",
             "element face %d" % len(faces), "property list uchar int vertex_indices",
             "property uchar flags", "element material 2", "property list uchar float values",
             "property int id", "end_header"]
    for i, (x, y, z) in enumerate(vertices):
        lines.append("%r %r %r %d %d %d" % (x, y, z, i % 256, 128, 255))
    for face in faces:
        lines.append("3 %d %d %d 7" % face)
    lines.append("3 0.5 0.25 1 1")
    lines.append("0 2")
    return "\n".join(lines) + "\n"


def ply_binary_le(vertices, faces):
    """binary little endian, double x y z then float normals (skipped),
    int32 indices, a uchar after the list, then an 'edge' element (skipped)."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment from data/part.off\n"
              "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
              "property float nx\nproperty float ny\nproperty float nz\n"
              "element face %d\nproperty list uchar int vertex_indices\nproperty uchar flags\n"
              "element edge 3\nproperty int vertex1\nproperty int vertex2\nend_header\n"
              % (len(vertices), len(faces)))
    body = bytearray()
    for x, y, z in vertices:
        body += struct.pack("<3d3f", x, y, z, 0.0, 0.0, 1.0)
    for face in faces:
        body += struct.pack("<B3iB", 3, *face, 1)
    for e in range(3):
        body += struct.pack("<2i", e, e + 1)
    return header.encode() + bytes(body)


def ply_binary_be(vertices, faces):
    """binary big endian, 'float32' coordinates, an int16 property between
    them, list 'uint8 uint32 vertex_index' (the other naming)."""
    header = ("ply\r\nformat binary_big_endian 1.0\r\ncomment from data/decimated_knight.off\r\n"
              "element vertex %d\r\nproperty float32 x\r\nproperty int16 quality\r\nproperty float32 y\r\n"
              "property float32 z\r\nelement face %d\r\nproperty list uint8 uint32 vertex_index\r\nend_header\r\n"
              % (len(vertices), len(faces)))
    body = bytearray()
    for x, y, z in vertices:
        body += struct.pack(">fhff", x, -3, y, z)
    for face in faces:
        body += struct.pack(">B3I", 3, *face)
    return header.encode() + bytes(body)


def triangle_strips(faces):
    """Greedy strips that reproduce exactly the given oriented triangles
    (up to rotation) with the alternating-winding rule: triangle k of a
    strip s is (s[k], s[k+1], s[k+2]) for even k, (s[k+1], s[k], s[k+2]) for odd k."""
    by_edge = {}
    for t, (a, b, c) in enumerate(faces):
        for u, v, w in ((a, b, c), (b, c, a), (c, a, b)):
            by_edge[(u, v)] = (t, w)
    used = [False] * len(faces)
    strips = []
    for t, face in enumerate(faces):
        if used[t]:
            continue
        used[t] = True
        strip = list(face)
        while True:
            x, y = strip[-2], strip[-1]
            odd = (len(strip) - 2) % 2 == 1  # parity of the next triangle
            found = by_edge.get((y, x) if odd else (x, y))
            if found is None or used[found[0]]:
                break
            used[found[0]] = True
            strip.append(found[1])
        strips.append(strip)
    return strips


def ply_tristrips(vertices, faces):
    """binary little endian 'tristrips' element: two records, each a list of
    strips separated by -1."""
    strips = triangle_strips(faces)
    half = len(strips) // 2
    records = []
    for group in (strips[:half], strips[half:]):
        flat = []
        for s in group:
            if flat:
                flat.append(-1)
            flat.extend(s)
        records.append(flat)
    header = ("ply\nformat binary_little_endian 1.0\ncomment from data/part.off, as triangle strips\n"
              "element vertex %d\nproperty float64 x\nproperty float64 y\nproperty float64 z\n"
              "element tristrips %d\nproperty list int int vertex_indices\nend_header\n"
              % (len(vertices), len(records)))
    body = bytearray()
    for x, y, z in vertices:
        body += struct.pack("<3d", x, y, z)
    for flat in records:
        body += struct.pack("<i%di" % len(flat), len(flat), *flat)
    return header.encode() + bytes(body), len(strips)


def stl_ascii(vertices, faces, name):
    """ascii STL with the coordinates in full double precision (repr)."""
    lines = ["solid %s" % name]
    for face in faces:
        lines.append("  facet normal %r %r %r" % tuple(normal(vertices, face)))
        lines.append("    outer loop")
        for i in face:
            lines.append("      vertex %r %r %r" % vertices[i])
        lines.append("    endloop")
        lines.append("  endfacet")
    lines.append("endsolid %s" % name)
    return "\r\n".join(lines) + "\r\n"


def stl_binary(vertices, faces, header_text):
    header = header_text.encode().ljust(80, b" ")[:80]
    body = bytearray(header + struct.pack("<I", len(faces)))
    for face in faces:
        body += struct.pack("<3f", *normal(vertices, face))
        for i in face:
            body += struct.pack("<3f", *vertices[i])
        body += struct.pack("<H", 0)
    return bytes(body)


def main():
    os.makedirs(OUT, exist_ok=True)
    cross = read_off(os.path.join(DATA, "cross.off"))
    part = read_off(os.path.join(DATA, "part.off"))
    knight = read_off(os.path.join(DATA, "decimated_knight.off"))

    write("cross_ascii.ply", ply_ascii_with_extras(*cross))
    write("part_binary_le.ply", ply_binary_le(*part))
    write("knight_binary_be.ply", ply_binary_be(*knight))
    strips, num_strips = ply_tristrips(*part)
    write("part_tristrips.ply", strips)
    write("part_ascii.stl", stl_ascii(*part, "part"))
    write("knight_binary.stl", stl_binary(*knight, "binary STL from data/decimated_knight.off"))
    # A binary STL whose header starts with "solid", as many exporters write.
    write("cross_binary_solid.stl", stl_binary(*cross, "solid cross (binary, from data/cross.off)"))
    print("wrote data/formats/ (part.off as %d triangle strips)" % num_strips, file=sys.stderr)


if __name__ == "__main__":
    main()
