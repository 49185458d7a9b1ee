#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Unfoldable-simplification benchmark (thesis Chapter 3, issue 4): runs
`subfab unfold` at default settings on the acceptance models and prints one
Markdown table row per model: facets after marching cubes / masks / deletion,
nets, Hausdorff distance (absolute and in grid spacings), refold error,
refused deletions, wall time and peak memory (from /usr/bin/time -v).

Usage: bench/run_unfold.py [--subfab build/subfab] [--models DIR] [--out DIR]
                           [--threads N] [--granularity G] [--only NAME ...]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MODELS = ["bunny_lowres.off", "spot.obj", "moai.obj", "max_planck.obj", "fandisk.obj"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--subfab", default=os.path.join(ROOT, "build", "subfab"))
    ap.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench_unfold"))
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--granularity", type=float, default=None)
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--no-masks", action="store_true")
    args = ap.parse_args()
    names = [m for m in MODELS if not args.only or any(m.startswith(o) for o in args.only)]
    print("| model | facets MC | after masks | final | nets | Hausdorff | / spacing | after masks / spacing | refold error | refused | wall (s) | CPU (s) | peak MB |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
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
        m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", r.stderr)
        peak = int(m.group(1)) / 1024.0 if m else float("nan")
        u = re.search(r"User time \(seconds\): ([0-9.]+)", r.stderr)
        sy = re.search(r"System time \(seconds\): ([0-9.]+)", r.stderr)
        cpu = float(u.group(1)) + float(sy.group(1)) if u and sy else float("nan")
        if r.returncode != 0:
            failed = True
            last = [l for l in r.stderr.splitlines() if l.startswith("error") or l.startswith("internal")]
            print(f"| {name} | exit {r.returncode}: {last[-1] if last else ''} |")
            continue
        j = json.loads(r.stdout)
        print(f"| {name} | {j['facets_mc']} | {j['facets_after_masks']} | {j['facets_final']} | {j['nets']} | "
              f"{j['hausdorff']:.4g} | {j['hausdorff_over_spacing']:.3f} | "
              f"{j['hausdorff_after_masks'] / j['spacing']:.3f} | {j['refold_error']:.2e} | "
              f"{j['deletions_refused']} | {wall:.2f} | {cpu:.2f} | {peak:.0f} |")
        sys.stdout.flush()
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
