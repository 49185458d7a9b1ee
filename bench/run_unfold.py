#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Unfoldable-simplification benchmark (thesis Chapter 3, issue 4): runs
`subfab unfold` at default settings on the acceptance models and prints one
Markdown table row per model: facets after marching cubes / masks / deletion,
nets, Hausdorff distance (absolute and in grid spacings), refold error,
refused deletions, wall time, CPU time and peak memory (from /usr/bin/time -v),
and an independent check of the written unfold.json (`check_unfold_json`):
closed and consistently oriented (every directed edge of every facet loop has
exactly one opposite), every facet planar with its normal in the 26-direction
set, no two adjacent facets with the same normal (coplanar), every facet in
exactly one net and the folds a spanning forest (folds = facets - nets), and
each facet's 2D polygon congruent to its 3D polygon (largest difference of
corner-to-corner distances, relative to the bounding-box diagonal) and not
mirrored. Overlaps inside a net are checked exactly by the binary itself
(a run that fails any of its checks exits 3).

Usage: bench/run_unfold.py [--subfab build/subfab] [--models DIR] [--out DIR]
                           [--threads N] [--granularity G] [--only NAME ...]
"""
import argparse
import itertools
import json
import math
import os
import re
import subprocess
import sys
import time

from bench_common import add_common_arguments, peak_rss_mb

MODELS = ["bunny_lowres.off", "spot.obj", "moai.obj", "max_planck.obj", "fandisk.obj"]


def newell(points):
    n = [0.0, 0.0, 0.0]
    for a, b in zip(points, points[1:] + points[:1]):
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return n


def check_unfold_json(path):
    """Returns (ok, description, worst relative 2D/3D congruence error)."""
    j = json.load(open(path))
    facets = j["facets"]
    problems = []
    corners = [tuple(p) for f in facets for p in f["vertices3d"]]
    lo = [min(c[k] for c in corners) for k in range(3)]
    hi = [max(c[k] for c in corners) for k in range(3)]
    diag = math.dist(lo, hi)
    edges = {}
    normals = []
    worst = 0.0
    for f in facets:
        loops3 = [f["vertices3d"]] + f.get("holes3d", [])
        loops2 = [f["vertices2d"]] + f.get("holes2d", [])
        if ("holes3d" in f) != ("holes2d" in f) or [len(l) for l in loops3] != [len(l) for l in loops2]:
            problems.append(f"facet {f['id']}: 3D and 2D corners differ")
            continue
        n = newell([tuple(p) for p in f["vertices3d"]])
        m = max(abs(c) for c in n)
        unit = [c / m for c in n]
        if any(min(abs(c), abs(abs(c) - 1)) > 1e-9 for c in unit):
            problems.append(f"facet {f['id']}: normal {n} not in the 26 directions")
        key = tuple(round(c) for c in unit)
        normals.append(key)
        length = math.sqrt(sum(c * c for c in n))
        p0 = f["vertices3d"][0]
        for loop in loops3:
            for p in loop:
                if abs(sum((p[k] - p0[k]) * n[k] for k in range(3))) / length > 1e-9 * diag:
                    problems.append(f"facet {f['id']}: not planar")
                    break
            for a, b in zip(loop, loop[1:] + loop[:1]):
                edges.setdefault((tuple(a), tuple(b)), []).append(f["id"])
        pts3 = [p for l in loops3 for p in l]
        pts2 = [p for l in loops2 for p in l]
        for a, b in itertools.combinations(range(len(pts3)), 2):
            worst = max(worst, abs(math.dist(pts3[a], pts3[b]) - math.dist(pts2[a], pts2[b])) / diag)
        o = f["vertices2d"]
        if sum(a[0] * b[1] - a[1] * b[0] for a, b in zip(o, o[1:] + o[:1])) <= 0:
            problems.append(f"facet {f['id']}: 2D polygon mirrored")
    for (a, b), owners in edges.items():
        back = edges.get((b, a), [])
        if len(owners) != 1 or len(back) != 1:
            problems.append(f"edge {a}-{b}: {len(owners)} x, opposite {len(back)} x (not closed/oriented)")
        elif normals[owners[0]] == normals[back[0]]:
            problems.append(f"facets {owners[0]} and {back[0]} are adjacent and coplanar")
    nets = {}
    for f in facets:
        nets.setdefault(f["net"], []).append(f["id"])
    if sorted(i for v in nets.values() for i in v) != list(range(len(facets))):
        problems.append("facets not each in exactly one net")
    if len(j["folds"]) != len(facets) - len(nets):
        problems.append(f"{len(j['folds'])} folds for {len(facets)} facets in {len(nets)} nets: not a spanning forest")
    for fold in j["folds"]:
        a, b = fold["facets"]
        if facets[a]["net"] != facets[b]["net"]:
            problems.append(f"fold {a}-{b} joins two nets")
    if worst > 1e-9:
        problems.append(f"2D/3D congruence error {worst:.2e} of the diagonal")
    return (not problems, "; ".join(problems[:3]), worst)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "bench_unfold", with_csv=False)
    ap.add_argument("--granularity", type=float, default=None)
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--no-masks", action="store_true")
    args = ap.parse_args()
    names = [m for m in MODELS if not args.only or any(m.startswith(o) for o in args.only)]
    print("| model | facets MC | after masks | final | nets | Hausdorff | / spacing | after masks / spacing | refold / diagonal | 2D/3D / diagonal | json check | refused | wall (s) | CPU (s) | peak MB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|")
    failed = False
    for name in names:
        out = os.path.join(args.out, os.path.splitext(name)[0])
        cmd = ["/usr/bin/time", "-v", args.subfab, "unfold", os.path.join(args.models, name), "-o", out,
               "--json", "--threads", str(args.threads)]
        if args.no_masks:
            cmd += ["--no-masks"]
        if args.granularity:
            cmd += ["--granularity", str(args.granularity)]
        t0 = time.monotonic()
        r = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.monotonic() - t0
        peak = peak_rss_mb(r.stderr)
        peak = float("nan") if peak is None else peak
        u = re.search(r"User time \(seconds\): ([0-9.]+)", r.stderr)
        sy = re.search(r"System time \(seconds\): ([0-9.]+)", r.stderr)
        cpu = float(u.group(1)) + float(sy.group(1)) if u and sy else float("nan")
        if r.returncode != 0:
            failed = True
            last = [l for l in r.stderr.splitlines() if l.startswith("error") or l.startswith("internal")]
            print(f"| {name} | exit {r.returncode}: {last[-1] if last else ''} |")
            continue
        j = json.loads(r.stdout)
        ok, why, congruence = check_unfold_json(os.path.join(out, "unfold.json"))
        failed = failed or not ok
        print(f"| {name} | {j['facets_mc']} | {j['facets_after_masks']} | {j['facets_final']} | {j['nets']} | "
              f"{j['hausdorff']:.4g} | {j['hausdorff_over_spacing']:.3f} | "
              f"{j['hausdorff_after_masks'] / j['spacing']:.3f} | {j['refold_error'] / j['diagonal']:.1e} | "
              f"{congruence:.1e} | {'pass' if ok else 'FAIL: ' + why} | "
              f"{j['deletions_refused']} | {wall:.2f} | {cpu:.2f} | {peak:.0f} |")
        sys.stdout.flush()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
