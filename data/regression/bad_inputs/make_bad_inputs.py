#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Writes the crafted bad-input corpus of `subfab repair` (issue 13) into this
folder. Deterministic; run again to regenerate: python3 make_bad_inputs.py"""
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))

# Unit cube, outward (counter-clockwise seen from outside).
CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_F = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
          (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def cube(offset=(0, 0, 0), base=0):
    v = [tuple(c + o for c, o in zip(p, offset)) for p in CUBE_V]
    f = [tuple(i + base for i in t) for t in CUBE_F]
    return v, f


def write_obj(name, vertices, faces, comment):
    with open(os.path.join(HERE, name), "w") as out:
        out.write(f"# {comment}\n")
        for p in vertices:
            out.write("v " + " ".join(repr(float(c)) if isinstance(c, float) else str(c) for c in p) + "\n")
        for t in faces:
            out.write("f " + " ".join(str(i + 1) for i in t) + "\n")


def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid = {}

        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(x + y) / 2 for x, y in zip(v[a], v[b])]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                mid[key] = len(v) - 1
            return mid[key]

        g = []
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    return v, f


def main():
    v, f = cube()
    f1 = list(f)
    f1[4] = (f1[4][0], f1[4][2], f1[4][1])
    write_obj("cube_flipped_face.obj", v, f1, "unit cube, one triangle flipped")

    v2, f2 = cube((0.5, 0.3, 0.2), base=8)
    write_obj("two_overlapping_cubes.obj", v + v2, f + f2, "two unit cubes overlapping, one soup")

    write_obj("cube_hole.obj", v, f[:4] + f[6:], "unit cube with one square side missing (a hole of 4 edges)")

    write_obj("cube_duplicated_face.obj", v, f + [f[7]], "unit cube with one triangle listed twice")

    # Vertex 8 = (0.5, 0, 0) on edge 0-1 (shared by the bottom z=0 and the front y=0):
    # the front side uses it, the bottom keeps edge 0-1, and the zero-area
    # triangle (0, 8, 1) closes the seam.
    vs = v + [(0.5, 0, 0)]
    fs = [t for i, t in enumerate(f) if i not in (4, 5)]
    fs += [(0, 8, 4), (8, 5, 4), (8, 1, 5), (0, 1, 8)]
    write_obj("cube_zero_area_sliver.obj", vs, fs, "unit cube with a zero-area sliver triangle along an edge")

    v3, f3 = cube((1, 1, 1), base=8)
    f3 = [tuple(6 if i == 8 else i for i in t) for t in f3]  # share vertex (1,1,1)
    write_obj("two_cubes_touching_at_vertex.obj", v + v3, f3 + f, "two unit cubes sharing one corner vertex")

    sv, sf = icosphere(2)
    write_obj("sphere_inward.obj", sv, [(a, c, b) for a, b, c in sf], "unit icosphere (320 faces), all faces inward")

    write_obj("open_triangle.obj", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)], "a single open triangle")

    open(os.path.join(HERE, "empty.obj"), "w").close()

    rng = random.Random(13)
    with open(os.path.join(HERE, "random_bytes.stl"), "wb") as out:
        out.write(bytes(rng.randrange(256) for _ in range(1000)))

    vn = list(v)
    vn[6] = (float("nan"), 1, 1)
    with open(os.path.join(HERE, "nan_coordinates.obj"), "w") as out:
        out.write("# unit cube, one vertex with a NaN coordinate\n")
        for p in vn:
            out.write("v " + " ".join("nan" if isinstance(c, float) and math.isnan(c) else str(c) for c in p) + "\n")
        for t in f:
            out.write("f " + " ".join(str(i + 1) for i in t) + "\n")


if __name__ == "__main__":
    main()
