#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Blocks against tolerance (issue 17, second acceptance point): for max planck,
bimba, kitten and egea at their Table 4.1 height settings, `subfab decompose
--tolerance T` for T in 0, 2.5e-4, 5e-4, 1e-3, 2e-3, 5e-3 (fractions of the
bounding-box diagonal), each output checked with `subfab validate`, and the
thesis's own point (its published blocks' deviation, its block count) beside the
curve. Each run is one row of bench/run_sweep.py (same command lines, same JSON
rows), so a row here and a row of a sweep at the same tolerance are the same.

Prints a markdown table: one row per model, one column per tolerance, each cell
"blocks / measured deviation (validate's check 10, x diagonal)", a cell marked
when validate fails or the run times out, and "dominates" when some point of the
curve has no more blocks than the thesis at no more deviation than the thesis's.

Usage: bench/run_tolerance_curve.py [--subfab build/subfab] [--out DIR] [--threads N]
                                    [--only NAME ...] [--tolerances T ...]
                                    [--timeout S] [--json-out FILE] [--merge FILE ...]
                                    [--table-only]
Long (one to two hours on one thread): never run from the test suite.
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys

import run_sweep
from bench_common import ROOT, add_common_arguments

# The deviation of the thesis's published blocks (their milled shapes), fraction of the diagonal
# (../shared/notes/reference-implementation.md, last section; issue 17).
THESIS_DEVIATION = {"Max Planck": 3.3e-3, "Bimba": 7.5e-3, "Kitten": 1.6e-3, "Egea": 8.3e-2}
CURVE_TOLERANCES = [0.0, 2.5e-4, 5e-4, 1e-3, 2e-3, 5e-3]


def measured_deviation(row):
    """validate's check 10 deviation (x diagonal); 0 for an exact run that validates; None if unknown."""
    for c in row.get("checks") or []:
        m = re.search(r"deviation ([0-9.eE+-]+) x diagonal", c["summary"])
        if m:
            return float(m.group(1))
    if row.get("status") == "valid" and not row.get("tolerance"):
        return 0.0
    return None


def cell(row):
    if row is None:
        return ""
    if row.get("exit") is None:
        return f"timeout ({row['wall_s']:.0f} s)"
    if row["exit"] != 0:
        return f"exit {row['exit']}"
    dev = measured_deviation(row)
    text = f"{row.get('blocks')} / " + ("?" if dev is None else ("0" if dev == 0 else f"{dev:.2e}"))
    text += f" ({row['wall_s']:.0f} s)"
    if row["status"] != "valid":
        failed = [run_sweep.CHECK_NAMES[i] if i < len(run_sweep.CHECK_NAMES) else c["name"]
                  for i, c in enumerate(row.get("checks") or []) if not c["passed"]]
        text += " **validate fails" + (": " + ", ".join(failed) if failed else "") + "**"
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "tolerance_curve", with_csv=True)
    ap.add_argument("--only", nargs="*", default=list(THESIS_DEVIATION), help="models (Table 4.1 names)")
    ap.add_argument("--tolerances", nargs="*", type=float, default=CURVE_TOLERANCES)
    ap.add_argument("--timeout", type=float, default=1800.0, help="per command, seconds")
    ap.add_argument("--json-out", default=None, help="default OUT/curve.json")
    ap.add_argument("--merge", nargs="*", default=[], help="carry over rows not run now from these JSON files "
                    "(a later file's row wins)")
    ap.add_argument("--table-only", action="store_true", help="run nothing: the table of the --merge rows")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    json_out = args.json_out or os.path.join(args.out, "curve.json")
    sweep_args = argparse.Namespace(**vars(args), skip=None, no_validate=False, max_overhang=None, tolerance=None)
    runs = run_sweep.collect_runs(sweep_args)
    rows = {}
    for path in args.merge:
        with open(path) as f:
            for r in json.load(f)["results"]:
                rows[(r["name"], r["curve_tolerance"])] = r
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    # Tolerance by tolerance, so that an interrupted run still has whole columns.
    for tol in ([] if args.table_only else args.tolerances):
        for run in runs:
            sweep_args.tolerance = tol
            r = run_sweep.run_one(sweep_args, run)
            r.update(commit=commit, curve_tolerance=tol,
                     run_at=datetime.datetime.now(datetime.timezone.utc).strftime("%H:%M UTC"))
            rows[(r["name"], tol)] = r
            print(f"{r['name']} T={tol:g}: {cell(r)}", file=sys.stderr, flush=True)
            with open(json_out, "w") as f:
                json.dump({"command": " ".join(sys.argv), "started": started, "load_at_end": os.getloadavg(),
                           "results": list(rows.values())}, f, indent=1)
    tols = sorted({t for (_, t) in rows})
    names = [r["name"] for r in runs]
    names = [n for n in names if any(k[0] == n for k in rows)]
    header = ["model", "settings", "thesis (T / blocks)"] + [f"T = {t:g}" for t in tols] + ["dominates the thesis"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for name in names:
        run = next(r for r in runs if r["name"] == name)
        t_dev, t_blocks = THESIS_DEVIATION.get(name), run.get("thesis_blocks")
        dom = [t for t in tols if (r := rows.get((name, t))) and r["status"] == "valid"
               and (d := measured_deviation(r)) is not None and t_dev is not None
               and d <= t_dev and r["blocks"] <= t_blocks]
        lines.append("| " + " | ".join([name, run["settings"], ("-" if t_dev is None else f"{t_dev:g}") + f" / {t_blocks}"] +
                                       [cell(rows.get((name, t))) for t in tols] +
                                       [", ".join(f"T = {t:g}" for t in dom) or "no"]) + " |")
    print("\n".join(lines))
    commits = sorted({r.get("commit", "?") for r in rows.values()})
    print(f"\nrows of commit(s) {', '.join(commits)}; load average {os.getloadavg()[0]:.1f}; rows in {json_out}")
    print(f"command: {' '.join(sys.argv)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
