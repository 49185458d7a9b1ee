#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""How far the thesis's published blocks lie from the input they decompose.

The authors' result folders (github.com/alemuntoni/HeightFieldDecomposition,
misc/results/MODEL.zip) hold the input (OriginalMesh.obj), the blocks
(Heightfield*.obj) and, for the statues decomposed after the thesis's
pre-filter (Section 4.3.5), the smoothed mesh they decomposed (smooth.obj).
The blocks are written in the frame the authors' orientation chose: a signed
permutation of the input's axes here, found by matching vertices, then
refined by a translation (nearest-vertex ICP), kept when it brings the
blocks closer to the input than no translation.

Prints, as fractions of the input's bounding-box diagonal:
  - input -> blocks: the distance from every input vertex to the nearest
    face of a block (all block faces, cut faces included, so each value is at
    most the distance to the union's surface): its maximum is a LOWER bound of
    the symmetric Hausdorff distance between the blocks' union and the input;
  - smooth <-> input (when smooth.obj exists): vertex-to-surface distances
    both ways, the pre-filter's own deviation.

Pure Python (no numpy), a uniform grid over the faces; seconds per model.
Usage: thesis_blocks_deviation.py RESULT_DIR [RESULT_DIR ...]
(RESULT_DIR: an unzipped misc/results/MODEL folder)
"""
import glob
import itertools
import math
import os
import random
import sys


def load_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith('v '):
                vertices.append(tuple(map(float, line.split()[1:4])))
            elif line.startswith('f '):
                idx = [int(t.split('/')[0]) for t in line.split()[1:]]
                idx = [i - 1 if i > 0 else len(vertices) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return vertices, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def closest_on_triangle(p, a, b, c):
    """Closest point of triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5)."""
    try:
        return closest_on_nondegenerate(p, a, b, c)
    except ZeroDivisionError:  # a degenerate triangle: its vertices are close enough for a lower-bound measure
        return min((a, b, c), key=lambda q: math.dist(p, q))


def along(a, d, t):
    return (a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2])


def closest_on_nondegenerate(p, a, b, c):
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return a
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        return along(a, ab, d1 / (d1 - d3))
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        return along(a, ac, d2 / (d2 - d6))
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        return along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))
    den = va + vb + vc
    return along(along(a, ab, vb / den), ac, vc / den)


class FaceGrid:
    """Faces binned by the grid cells their bounding boxes meet."""

    def __init__(self, vertices, faces, cell):
        self.v, self.f, self.cell, self.bins = vertices, faces, cell, {}
        for fi, face in enumerate(faces):
            pts = [vertices[i] for i in face]
            lo = [math.floor(min(p[k] for p in pts) / cell) for k in range(3)]
            hi = [math.floor(max(p[k] for p in pts) / cell) for k in range(3)]
            for key in itertools.product(*(range(lo[k], hi[k] + 1) for k in range(3))):
                self.bins.setdefault(key, []).append(fi)

    def distance(self, q):
        """Distance from q to the nearest face (rings of cells until one is found and provably nearest)."""
        key = [math.floor(c / self.cell) for c in q]
        best, seen = math.inf, set()
        for ring in range(0, 64):
            for d in itertools.product(range(-ring, ring + 1), repeat=3):
                if max(abs(x) for x in d) != ring:
                    continue
                for fi in self.bins.get((key[0] + d[0], key[1] + d[1], key[2] + d[2]), ()):
                    if fi in seen:
                        continue
                    seen.add(fi)
                    a, b, c = (self.v[i] for i in self.f[fi])
                    best = min(best, math.dist(q, closest_on_triangle(q, a, b, c)))
            if best <= ring * self.cell:  # every face farther than that lies outside the rings seen
                return best
        return best


def transformed(vertices, perm, signs, offset=(0.0, 0.0, 0.0)):
    return [tuple(signs[i] * v[perm[i]] + offset[i] for i in range(3)) for v in vertices]


def register(model, blocks, cell):
    """Signed axis permutation (and then a translation) mapping the model's vertices onto the blocks'."""
    random.seed(1)
    sample = random.sample(blocks, min(2000, len(blocks)))

    def nearest_of(points):
        """For each sample point, the nearest of `points` within a cell's neighbourhood (or None)."""
        bins = {}
        for p in points:
            bins.setdefault(tuple(math.floor(c / cell) for c in p), []).append(p)
        out = []
        for q in sample:
            k = [math.floor(c / cell) for c in q]
            cands = [p for d in itertools.product((-1, 0, 1), repeat=3)
                     for p in bins.get((k[0] + d[0], k[1] + d[1], k[2] + d[2]), ())]
            out.append((q, min(cands, key=lambda p: math.dist(p, q)) if cands else None))
        return out

    def near_count(points, radius):
        return sum(1 for q, p in nearest_of(points) if p is not None and math.dist(p, q) < radius)

    best = max(((near_count(transformed(model, perm, signs), cell / 2), perm, signs)
                for perm in itertools.permutations(range(3))
                for signs in itertools.product((1, -1), repeat=3)), key=lambda t: t[0])
    _, perm, signs = best
    offset = [0.0, 0.0, 0.0]
    for _ in range(10):  # translation-only ICP on nearest vertices
        acc, n = [0.0, 0.0, 0.0], 0
        for q, p in nearest_of(transformed(model, perm, signs, offset)):
            if p is not None and math.dist(p, q) < cell / 2:
                acc = [acc[i] + q[i] - p[i] for i in range(3)]
                n += 1
        step = [a / max(n, 1) for a in acc]
        offset = [offset[i] + step[i] for i in range(3)]
        if max(abs(s) for s in step) < 1e-6 * cell:
            break
    return perm, signs, offset, best[0] / len(sample)


def stats(values):
    values = sorted(values)
    n = len(values)
    return {'median': values[n // 2], 'p99': values[int(0.99 * (n - 1))], 'max': values[-1],
            'mean': sum(values) / n}


def fmt(s):
    return 'max %.2e  p99 %.2e  median %.2e  mean %.2e' % (s['max'], s['p99'], s['median'], s['mean'])


def one_way(points, grid, diagonal):
    return stats([grid.distance(p) / diagonal for p in points])


def main(folders):
    for folder in folders:
        model_v, model_f = load_obj(os.path.join(folder, 'OriginalMesh.obj'))
        used = sorted({i for f in model_f for i in f})
        lo = [min(model_v[i][k] for i in used) for k in range(3)]
        hi = [max(model_v[i][k] for i in used) for k in range(3)]
        diagonal = math.dist(lo, hi)
        cell = diagonal / 100
        block_v, block_f = [], []
        paths = sorted(glob.glob(os.path.join(folder, 'Heightfield*.obj')))
        for path in paths:
            v, f = load_obj(path)
            base = len(block_v)
            block_v += v
            block_f += [(a + base, b + base, c + base) for a, b, c in f]
        b_lo = [min(v[k] for v in block_v) for k in range(3)]
        b_hi = [max(v[k] for v in block_v) for k in range(3)]
        if abs(math.dist(b_lo, b_hi) / diagonal - 1) > 0.1:
            print('%s: blocks in another scale (diagonal %.4g, input %.4g): not measured'
                  % (os.path.basename(os.path.normpath(folder)), math.dist(b_lo, b_hi), diagonal))
            continue
        perm, signs, offset, matched = register([model_v[i] for i in used], block_v, cell)
        blocks = FaceGrid(block_v, block_f, cell)
        # the registration most favourable to the thesis: the ICP's translation or none
        # (blocks made of the input's own vertices match at 0; cut faces bias the ICP a little)
        results = []
        for o in (offset, (0.0, 0.0, 0.0)):
            moved = transformed(model_v, perm, signs, o)
            results.append((one_way([moved[i] for i in used], blocks, diagonal), o))
        measured, offset = min(results, key=lambda r: (r[0]['median'], r[0]['max']))
        name = os.path.basename(os.path.normpath(folder))
        print('%s: %d blocks; frame: axes %s signs %s offset (%.3g, %.3g, %.3g) x diagonal, %.0f%% of block vertices '
              'within %.0e x diagonal of an input vertex' % (name, len(paths), perm, signs, *(o / diagonal for o in offset),
                                                            100 * matched, cell / 2 / diagonal))
        print('  input vertices -> blocks:  ' + fmt(measured))
        smooth_path = os.path.join(folder, 'smooth.obj')
        if os.path.exists(smooth_path):
            sv, sf = load_obj(smooth_path)
            s_used = sorted({i for f in sf for i in f})
            smooth = FaceGrid(sv, sf, cell)
            model = FaceGrid(model_v, model_f, cell)
            print('  smooth.obj (the pre-filtered mesh the blocks decompose, input frame):')
            print('    input vertices -> smooth: ' + fmt(one_way([model_v[i] for i in used], smooth, diagonal)))
            print('    smooth vertices -> input: ' + fmt(one_way([sv[i] for i in s_used], model, diagonal)))


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
