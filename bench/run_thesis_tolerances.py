#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Issue 17's first acceptance point in one command: every Table 4.1 model we
ship, at its Table 4.1 height, decomposed with `--tolerance` set to the
deviation of the thesis's own published blocks (the milled shape's distance
from the block, bench/thesis_blocks_deviation.py; cube spike at height 0.4:
1e-4, its thesis blocks are exact; fertility: 1e-3, its thesis mesh is not
shipped), then checked with `subfab validate`. hu is not a Table 4.1 row (the
thesis publishes 7 blocks of it) and is run last.

Prints the markdown table of bench/RESULTS.md ("Where we stand against Table
4.1"): blocks ours / thesis, the deviation validate measures (check 10) and
decompose's recorded bound, the blocks' volume over the input's (above 1:
material filled under undercuts; below: the model's interior left empty or
thin features not covered), decompose's and validate's wall
time and peak memory, the thesis's total time and the speed-up.

Usage: bench/run_thesis_tolerances.py [--subfab build/subfab] [--out DIR]
                                      [--threads N] [--only NAME ...]
                                      [--timeout S] [--dry-run]
Long (tens of minutes in all): never run from the test suite.
"""
import argparse
import json
import os

from bench_common import add_common_arguments, add_run_list_arguments, logged_run, peak_rss_mb, selected

# name, file, Table 4.1 height (None: no limit), tolerance (x diagonal), thesis blocks, thesis total s
RUNS = [
    ("Airplane", "airplane.obj", None, 1.8e-3, 11, 112.0),
    ("Cube Spike (no height limit)", "cube_spike.obj", None, 9.8e-4, 2, 175.1),
    ("Cube Spike", "cube_spike.obj", 0.4, 1e-4, 6, 92.1),
    ("Moai", "moai.obj", 0.225, 3.8e-4, 12, 780.2),
    ("Max Planck", "max_planck.obj", None, 3.3e-3, 8, 983.3),
    ("Kitten", "kitten.obj", 0.05, 1.6e-3, 25, 1352.0),
    ("Bimba", "bimba.obj", None, 7.5e-3, 16, 1565.2),
    ("Egea", "egea.obj", 0.1, 8.3e-2, 6, 969.1),
    ("Fertility", "fertility.off", None, 1e-3, 63, 1595.0),
    ("hu", "hu.obj", None, 1.4e-3, 7, None),
]


def error_line(err, rc):
    errors = [line for line in err.splitlines() if line.startswith("error:")]
    return errors[-1] if errors else "timeout" if rc is None else "exit %d" % rc


def one(args, name, file, height, tolerance):
    model = os.path.join(args.models, file)
    stem = os.path.splitext(file)[0]
    outdir = os.path.join(args.out, "%s_h%s_t%g" % (stem, "none" if height is None else "%g" % height, tolerance))
    cmd = [args.subfab, "decompose", model, "-o", outdir, "--tolerance", "%g" % tolerance,
           "--threads", str(args.threads), "--no-view", "--quiet"]
    if height is not None:
        cmd += ["--max-height", "%g" % height]
    row = {"model": name, "height": height, "tolerance": tolerance}
    done = logged_run(args, cmd)
    if done is None:
        return row
    rc, _, err, seconds = done
    row.update(decompose_s=seconds, decompose_mb=peak_rss_mb(err))
    if rc != 0 or not os.path.exists(os.path.join(outdir, "decomposition.json")):
        row["error"] = error_line(err, rc)
        return row
    with open(os.path.join(outdir, "decomposition.json")) as f:
        doc = json.load(f)
    row["blocks"] = len(doc["blocks"])
    row["bound"] = doc["summary"].get("deviation_bound_fraction")
    row["volume_ratio"] = doc["summary"].get("material_volume_fraction")
    done = logged_run(args, [args.subfab, "validate", model, outdir, "--json", "--quiet", "--threads", str(args.threads)])
    if done is None:
        return row
    rc, out, err, seconds = done
    row.update(validate_s=seconds, validate_mb=peak_rss_mb(err))
    try:
        v = json.loads(out)
    except json.JSONDecodeError:
        row["validate"] = error_line(err, rc)
        return row
    row["validate"] = "%d/%d" % (sum(1 for c in v["checks"] if c["passed"]), len(v["checks"]))
    row["deviation"] = v.get("deviation", {}).get("max_fraction")
    return row


def fmt(x, spec="%.3g"):
    return "-" if x is None else spec % x


def table(rows):
    out = ["| model | height | T | blocks ours / thesis | deviation: validate (decompose's bound) | blocks' volume / input's | "
           "validate | decompose s (peak MB) | thesis total s | speed-up | validate s (peak MB) |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        name, height, tol = r["model"], fmt(r["height"], "%g"), "%g" % r["tolerance"]
        thesis_blocks, thesis_s = r["thesis_blocks"], r["thesis_s"]
        if "error" in r or "blocks" not in r:
            out.append("| %s | %s | %s | %s / %d | | | | %s | %s | | |" % (
                name, height, tol, r.get("error", "-"), thesis_blocks, fmt(r.get("decompose_s"), "%.1f"),
                fmt(thesis_s, "%.0f")))
            continue
        speed = thesis_s / r["decompose_s"] if thesis_s and r.get("decompose_s") else None
        out.append("| %s | %s | %s | %s%d%s / %d | %s (%s) | %s | %s | %s (%s) | %s | %s | %s (%s) |" % (
            name, height, tol, "**" if r["blocks"] <= thesis_blocks else "", r["blocks"],
            "**" if r["blocks"] <= thesis_blocks else "", thesis_blocks, fmt(r.get("deviation")), fmt(r.get("bound")),
            fmt(r.get("volume_ratio"), "%.5f"), r.get("validate", "-"), fmt(r.get("decompose_s"), "%.1f"),
            fmt(r.get("decompose_mb"), "%.0f"), fmt(thesis_s, "%.0f"), fmt(speed, "%.1fx"),
            fmt(r.get("validate_s"), "%.1f"), fmt(r.get("validate_mb"), "%.0f")))
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "thesis_tolerances", with_csv=False)
    add_run_list_arguments(ap)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for name, file, height, tolerance, thesis_blocks, thesis_s in RUNS:
        if not selected(args, name, file):
            continue
        row = one(args, name, file, height, tolerance)
        row.update(thesis_blocks=thesis_blocks, thesis_s=thesis_s)
        rows.append(row)
        with open(os.path.join(args.out, "thesis_tolerances.json"), "w") as f:
            json.dump(rows, f, indent=1)
    print(table(rows))


if __name__ == "__main__":
    main()
