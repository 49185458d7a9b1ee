#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Smoothing and a tolerance together (issue 17): `subfab decompose --smooth=F
--smooth-passes P --smooth-lambda 0.89 --smooth-mu -0.9 --tolerance T` on the
thesis's statues at their Table 4.1 height, each output checked with `subfab
validate` (against the smoothed model, within T) and, with --against-input,
`subfab validate --against-input` (against the input itself, within the recorded
F + T). The thesis's point beside each row: its block count and how far its
published blocks lie from the input at least (bench/thesis_blocks_deviation.py;
bench/RESULTS.md, "What the thesis's statue counts are").

Prints a markdown table (the one of bench/RESULTS.md, "Smoothing and a tolerance
together"): blocks, the recorded bound of the blocks' deviation from the input,
validate's verdict and check 10, the measured deviation from the input, and
the decomposition's wall time.

Usage: bench/run_smooth_tolerance.py [--subfab build/subfab] [--out DIR]
                                     [--threads N] [--only NAME ...]
                                     [--against-input] [--dry-run]
Long (minutes per run, the --against-input measure as long again): never run
from the test suite.
"""
import argparse
import json
import os

from bench_common import add_common_arguments, add_run_list_arguments, logged_run, peak_rss_mb, selected

# The authors' own Taubin factors (their tool's defaults)
FACTORS = ["--smooth-lambda", "0.89", "--smooth-mu", "-0.9"]
# name, file, Table 4.1 height (None: no limit), smoothing cap F, passes, tolerance T
RUNS = [
    ("Max Planck", "max_planck.obj", None, 8e-3, 1000, 2.5e-3),
    ("Max Planck", "max_planck.obj", None, 6e-3, 1000, 4e-3),
    ("Max Planck", "max_planck.obj", None, 5e-3, 1000, 3e-3),
    ("Bimba", "bimba.obj", None, 7e-3, 1000, 3e-3),
    ("Bimba", "bimba.obj", None, 8e-3, 400, 2e-3),
    ("Kitten", "kitten.obj", 0.05, 1e-2, 1500, 3e-3),
    ("Kitten", "kitten.obj", 0.05, 1.1e-2, 2500, 2.5e-3),
]
# Table 4.1's count, and the least distance of the thesis's blocks from the input (x diagonal)
THESIS = {"Max Planck": (8, 1.08e-2), "Bimba": (16, 1.01e-2), "Kitten": (25, 1.36e-2)}


def validate_json(args, model, outdir, against):
    cmd = [args.subfab, "validate", model, outdir, "--json", "--quiet", "--threads", str(args.threads)]
    if against:
        cmd.append("--against-input")
    done = logged_run(args, cmd)
    if done is None:
        return None
    _, out, err, seconds = done
    try:
        j = json.loads(out)
    except json.JSONDecodeError:
        return {"passed": False, "error": [line for line in err.splitlines() if line.startswith("error:")][-1:]
                or ["no output"]}
    j["seconds"] = seconds
    return j


def one(args, name, file, height, cap, passes, tolerance):
    model = os.path.join(args.models, file)
    outdir = os.path.join(args.out, "%s_c%g_p%d_t%g" % (os.path.splitext(file)[0], cap, passes, tolerance))
    cmd = [args.subfab, "decompose", model, "-o", outdir, "--smooth=%g" % cap, "--smooth-passes", str(passes),
           *FACTORS, "--tolerance", "%g" % tolerance, "--threads", str(args.threads), "--no-view", "--quiet"]
    if height is not None:
        cmd += ["--max-height", "%g" % height]
    done = logged_run(args, cmd)
    row = {"model": name, "height": height, "cap": cap, "passes": passes, "tolerance": tolerance,
           "decompose_s": done[3] if done else 0.0}
    if done is None:
        return row
    rc, _, err, _ = done
    row["peak_rss_mb"] = peak_rss_mb(err)
    if rc not in (0, 3) or not os.path.exists(os.path.join(outdir, "decomposition.json")):
        errors = [line for line in err.splitlines() if line.startswith("error:")]
        row["error"] = errors[-1] if errors else "timeout" if rc is None else "exit %d" % rc
        return row
    with open(os.path.join(outdir, "decomposition.json")) as f:
        doc = json.load(f)
    row["blocks"] = len(doc["blocks"])
    row["bound"] = doc["input"]["smoothing"]["total_deviation_bound_fraction"]
    row["validate"] = validate_json(args, model, outdir, False)
    if args.against_input:
        row["against_input"] = validate_json(args, model, outdir, True)
    return row


def verdict(v):
    if not v:
        return "-"
    if "error" in v:
        return "error: " + " ".join(v["error"])
    passed = sum(1 for c in v["checks"] if c["passed"])
    dev = v.get("deviation", {}).get("max_fraction")
    return "%d/%d%s" % (passed, len(v["checks"]), " (%.3g)" % dev if dev is not None else "")


def table(rows):
    out = ["| model (height) | F (passes) | T | blocks | bound from the input | validate (vs smoothed) | "
           "measured from the input | decompose s | thesis: blocks / from the input (at least) |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        thesis = THESIS.get(r["model"])
        height = " (%g)" % r["height"] if r["height"] is not None else ""
        if "error" in r:
            out.append("| %s%s | %g (%d) | %g | %s | | | | %.0f | |" % (r["model"], height, r["cap"], r["passes"],
                                                                       r["tolerance"], r["error"], r["decompose_s"]))
            continue
        out.append("| %s%s | %g (%d) | %g | %s | %s | %s | %s | %.0f | %s |" % (
            r["model"], height, r["cap"], r["passes"], r["tolerance"], r.get("blocks", "-"),
            "%.3g" % r["bound"] if "bound" in r else "-", verdict(r.get("validate")),
            verdict(r.get("against_input")), r["decompose_s"],
            "%d / %.3g" % thesis if thesis else "-"))
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "smooth_tolerance", with_csv=False)
    ap.add_argument("--against-input", action="store_true", help="also validate against the input itself")
    add_run_list_arguments(ap)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for name, file, height, cap, passes, tolerance in RUNS:
        if not selected(args, name, file):
            continue
        rows.append(one(args, name, file, height, cap, passes, tolerance))
    with open(os.path.join(args.out, "smooth_tolerance.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print(table(rows))


if __name__ == "__main__":
    main()
