#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Thesis Table 4.1 benchmark: decomposes every model of
../shared/benchmarks/paper_table_4_1.csv that ships in ../shared/models with
that row's height setting, validates each result with `subfab validate`, and
prints: model, blocks (ours / thesis), time per stage, total, thesis total,
speed ratio, peak memory (from /usr/bin/time -v).

Usage: bench/run_table_4_1.py [--subfab build/subfab] [--models DIR] [--csv FILE]
                              [--out DIR] [--threads N] [--only NAME ...]
Long (minutes): never run from the test suite.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

from bench_common import add_common_arguments, peak_rss_mb, table_4_1_rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "bench", with_csv=True)
    ap.add_argument("--only", nargs="*", help="run only these model names (as in the CSV, case-insensitive)")
    args = ap.parse_args()

    rows, _ = table_4_1_rows(args.csv, args.models)
    if args.only:
        rows = [row for row in rows if row["model"].lower() in [o.lower() for o in args.only]]

    header = ("model", "blocks", "thesis", "orient", "field", "grow", "cover", "resolve", "carve", "total",
              "thesis_total", "speedup", "peak_MB", "valid")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    failures = 0
    for row in rows:
        name = row["model"]
        height = row["max_height_frac"]
        slug = re.sub(r"[^a-z0-9]+", "_", name.lower()).strip("_")
        outdir = os.path.join(args.out, slug)
        cmd = ["/usr/bin/time", "-v", args.subfab, "decompose", os.path.join(args.models, row["file"]),
               "-o", outdir, "--json", "--quiet", "--threads", str(args.threads)]
        if height not in ("inf", ""):
            cmd += ["--max-height", height]
        start = time.time()
        p = subprocess.run(cmd, capture_output=True, text=True)
        wall = time.time() - start
        peak = peak_rss_mb(p.stderr)
        peak = float("nan") if peak is None else peak
        if p.returncode != 0:
            failures += 1
            err = p.stderr.strip().splitlines()
            err = [l for l in err if not l.startswith("\t")]
            print(f"| {name} | FAILED (exit {p.returncode}: {err[-1] if err else ''}) |", flush=True)
            continue
        summary = json.loads(p.stdout)
        t = summary["timings_s"]
        v = subprocess.run([args.subfab, "validate", os.path.join(args.models, row["file"]), outdir, "--quiet",
                            "--threads", str(args.threads)], capture_output=True, text=True)
        valid = "yes" if v.returncode == 0 else f"NO (exit {v.returncode})"
        if v.returncode != 0:
            failures += 1
            sys.stderr.write(v.stdout + v.stderr)
        thesis_total = float(row["total_s"])
        speedup = thesis_total / t["total"] if t["total"] > 0 else math.inf
        cells = [name, str(summary["num_blocks"]), row["blocks"]] + \
                [f"{t[k]:.2f}" for k in ("orient", "field", "grow", "cover", "resolve", "carve", "total")] + \
                [f"{thesis_total:.1f}", f"{speedup:.0f}x", f"{peak:.0f}", valid]
        print("| " + " | ".join(cells) + " |", flush=True)
    print(f"\n{len(rows)} models, {failures} failures; command: {' '.join(sys.argv)}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
