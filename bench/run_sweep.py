#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Acceptance sweep of `subfab decompose` (issue 3, "Done when"): in one command,
every Table 4.1 model we ship with that row's height setting
(../shared/benchmarks/paper_table_4_1.csv, as bench/run_table_4_1.py) plus every
other closed model of ../shared/models (MANIFEST.md: closed, oriented, no
non-manifold vertex) at default settings. Each one is decomposed, then checked
with `subfab validate --json`. The bad inputs of the manifest (open,
non-manifold) are run too and must be refused with exit code 2.

Prints a markdown table (model, settings, exit code, blocks, per-stage times,
total, validate wall time and result per check, peak MB) and writes every row to
a JSON file (--json-out). Rows of models not run this time can be carried over
from an earlier JSON with --merge (so one model can be re-run alone).

Within a tolerance (issue 17: "the same table for every closed model" at 1e-3
and 5e-4), --tolerance F passes `--tolerance F` to every decompose; the table
then gains the tolerance, the blocks' deviation bound (decompose's) and the
number of blocks sticking out (filled), both from decomposition's --json, and
validate's check 10 verdict.

Usage: bench/run_sweep.py [--subfab build/subfab] [--out DIR] [--threads N]
                          [--only NAME ...] [--skip NAME ...] [--json-out FILE]
                          [--merge FILE] [--timeout S] [--no-validate]
                          [--tolerance F]
Long (tens of minutes): never run from the test suite. Models run one at a time.
"""
import argparse
import datetime
import json
import os
import re
import subprocess
import sys

import bench_common
from bench_common import ROOT, add_common_arguments, table_4_1_rows, timed_run

# The steepest face of the thesis's own published blocks per run, degrees past
# vertical (../shared/notes/reference-implementation.md, "What its published
# results show under a strict check"); runs it does not list are not measured.
THESIS_OVERHANG_DEG = {"Airplane": 23.0, "Cube Spike": 0.0, "Cube Spike (no height limit)": 14.0, "hu": 43.0,
                       "Moai": 3.5, "Max Planck": 42.0, "Kitten": 27.0}

# Short names of the checks of `subfab validate`, in order (the tenth only within a tolerance).
CHECK_NAMES = ["solid", "hfield", "overlap", "inside", "cover", "limits", "machine", "float32", "sliver", "tolerance"]


def peak_rss_mb(stderr_text):
    mb = bench_common.peak_rss_mb(stderr_text)
    return None if mb is None else round(mb)


def last_error_line(stderr_text):
    lines = [l for l in stderr_text.strip().splitlines() if l and not l.startswith("\t")
             and not l.startswith("Command exited") and not l.startswith("Command terminated")]
    errs = [l for l in lines if l.startswith("error")]
    return (errs[-1] if errs else (lines[-1] if lines else "")).strip()


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_")


def manifest_models(models_dir):
    """(file, good) for every model of MANIFEST.md; good = closed, oriented, no non-manifold vertex."""
    out = []
    with open(os.path.join(models_dir, "MANIFEST.md")) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) < 11 or not re.match(r"^[\w.-]+\.(obj|off|ply|stl)$", cells[0]):
                continue
            closed, oriented, nmv = cells[6].lower(), cells[7].lower(), cells[10]
            good = closed == "yes" and oriented == "yes" and nmv in ("0", "")
            out.append((cells[0], good))
    return out


def collect_runs(args):
    """The runs of the sweep: dicts with name, file, options, expect ("valid" or "refused")."""
    runs = []
    rows, table_files = table_4_1_rows(args.csv, args.models)
    for row in rows:
        h = row["max_height_frac"]
        opts = [] if h in ("inf", "") else ["--max-height", h]
        runs.append({"name": row["model"], "file": row["file"], "options": opts, "expect": "valid",
                     "settings": " ".join(opts) or "default",
                     "thesis_blocks": int(row["blocks"]), "thesis_total_s": float(row["total_s"])})
    for file, good in manifest_models(args.models):
        if file in table_files:
            continue
        runs.append({"name": os.path.splitext(file)[0], "file": file, "options": [], "settings": "default",
                     "expect": "valid" if good else "refused"})
    sel = [o.lower() for o in (args.only or [])]
    skip = [o.lower() for o in (args.skip or [])]
    def matches(run, names):
        return run["name"].lower() in names or run["file"].lower() in names or \
            os.path.splitext(run["file"])[0].lower() in names
    return [r for r in runs if (not sel or matches(r, sel)) and not matches(r, skip)]


def stage_times(stderr_text):
    """'[stage] done in X s' lines of ConsoleProgress -> {stage: seconds}."""
    return {m.group(1): float(m.group(2)) for m in re.finditer(r"^\[([^\]]+)\] done in ([0-9.]+) s", stderr_text, re.M)}


def overhang_of(args, run):
    """The --max-overhang of this run (None: not run under --max-overhang thesis)."""
    if args.max_overhang is None:
        return 0.0
    if args.max_overhang == "thesis":
        return THESIS_OVERHANG_DEG.get(run["name"])
    return float(args.max_overhang)


def run_one(args, run):
    mesh = os.path.join(args.models, run["file"])
    outdir = os.path.join(args.out, slug(run["name"] + ("_" + "_".join(run["options"]) if run["options"] else "")))
    overhang = overhang_of(args, run)
    extra = ["--max-overhang", f"{overhang:g}"] if overhang else []
    if args.tolerance is not None:
        extra += ["--tolerance", f"{args.tolerance:g}"]
        outdir += f"_t{args.tolerance:g}"
    cmd = [args.subfab, "decompose", mesh, "-o", outdir, "--json", "--quiet", "--threads", str(args.threads)] + \
        run["options"] + extra
    res = dict(run)
    if extra:
        res["settings"] = " ".join(([] if run["settings"] == "default" else [run["settings"]]) + extra)
    res["command"] = " ".join(cmd)
    rc, out, err, res["wall_s"] = timed_run(cmd, args.timeout)
    res["exit"] = rc
    res["peak_mb"] = peak_rss_mb(err)
    if rc != 0:
        res["error"] = last_error_line(err)
        res["status"] = "refused (ok)" if (run["expect"] == "refused" and rc == 2) else "FAIL decompose"
        return res
    if run["expect"] == "refused":
        res["status"] = "FAIL (bad input accepted)"
        return res
    summary = json.loads(out)
    res["blocks"] = summary.get("num_blocks")
    res["timings_s"] = summary.get("timings_s", {})
    for key in ("num_grown_boxes", "num_selected_boxes", "num_ordered_boxes", "num_cycle_splits", "num_merges",
                "cover_optimal", "max_overhang_deg", "tolerance", "deviation_bound", "num_sticking_out",
                "num_slivers"):
        if key in summary:
            res[key] = summary[key]
    if args.no_validate:
        res["status"] = "not validated"
        return res
    vcmd = [args.subfab, "validate", mesh, outdir, "--json", "--threads", str(args.threads)]
    res["validate_command"] = " ".join(vcmd)
    vrc, vout, verr, res["validate_wall_s"] = timed_run(vcmd, args.timeout)
    res["validate_exit"] = vrc
    res["validate_peak_mb"] = peak_rss_mb(verr)
    res["validate_times_s"] = stage_times(verr)
    try:
        vj = json.loads(vout)
        res["checks"] = [{"name": c["name"], "passed": c["passed"], "summary": c["summary"],
                          "num_failures": c["num_failures"], "failures": c["failures"][:5]} for c in vj["checks"]]
        if "thickness" in vj:
            res["min_thickness_fraction"] = vj["thickness"]["min_thickness_fraction"]
            res["num_slivers"] = vj["thickness"]["num_slivers"]
    except (ValueError, KeyError):
        res["checks"] = None
        res["error"] = last_error_line(verr)
    res["status"] = "valid" if vrc == 0 else "FAIL validate"
    return res


def fmt_t(x):
    return "" if x is None else f"{x:.2f}"


def table(results):
    stages = ["orient", "field", "grow", "cover", "resolve", "carve"]
    within = any(r.get("tolerance") for r in results)
    if within:
        stages.append("tolerance")
    header = ["model", "settings", "exit", "blocks", "thesis"] + \
        (["deviation bound (x diag)", "filled blocks"] if within else []) + stages + \
        ["total", "validate (s)", "v.overlap (s)", "v.inside (s)"] + CHECK_NAMES + ["peak MB", "status"]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in results:
        t = r.get("timings_s", {})
        checks = r.get("checks")
        if checks:
            marks = ["ok" if c["passed"] else f"FAIL({c['num_failures']})" for c in checks]
            marks += ["-"] * (len(CHECK_NAMES) - len(marks))  # no tolerance check without a tolerance
        else:
            marks = ["-"] * len(CHECK_NAMES)
        peak = max([x for x in (r.get("peak_mb"), r.get("validate_peak_mb")) if x is not None], default=None)
        status = r["status"]
        if r.get("error") and status.startswith("FAIL"):
            status += ": " + r["error"][:160].replace("|", "/")
        tol = r.get("tolerance")
        extra_cells = []
        if within:
            frac = None
            m = re.search(r"--tolerance (\S+)", r["settings"])
            if tol and m and "deviation_bound" in r:
                frac = r["deviation_bound"] / tol * float(m.group(1))  # tolerance = F x diagonal
            extra_cells = ["" if frac is None else f"{frac:.2e}", str(r.get("num_sticking_out", ""))]
        cells = [r["name"], r["settings"], str(r["exit"]), str(r.get("blocks", "")),
                 str(r.get("thesis_blocks", ""))] + extra_cells + [fmt_t(t.get(s)) for s in stages] + \
            [fmt_t(t.get("total", r.get("wall_s") if r["exit"] != 0 else None)), fmt_t(r.get("validate_wall_s")),
             fmt_t(r.get("validate_times_s", {}).get("check: overlaps")),
             fmt_t(r.get("validate_times_s", {}).get("check: inside the input"))] + \
            marks + ["" if peak is None else str(peak), status]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_common_arguments(ap, "sweep", with_csv=True)
    ap.add_argument("--only", nargs="*", help="run only these (model name, file or file stem; case-insensitive)")
    ap.add_argument("--skip", nargs="*", help="do not run these (same matching as --only)")
    ap.add_argument("--json-out", default=None, help="write the rows here (default OUT/sweep.json)")
    ap.add_argument("--merge", default=None, help="carry over rows of runs not made now from this JSON")
    ap.add_argument("--timeout", type=float, default=1800.0, help="per command, seconds")
    ap.add_argument("--no-validate", action="store_true")
    ap.add_argument("--max-overhang", default=None,
                    help="pass --max-overhang DEG to every decompose; 'thesis': each run's thesis blocks' own "
                         "steepest overhang (THESIS_OVERHANG_DEG; runs without one are skipped). validate "
                         "checks against the recorded allowance")
    ap.add_argument("--tolerance", type=float, default=None,
                    help="pass --tolerance F (fraction of the diagonal) to every decompose; validate then checks "
                         "the recorded tolerance (check 10)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    json_out = args.json_out or os.path.join(args.out, "sweep.json")

    runs = collect_runs(args)
    if args.max_overhang == "thesis":
        runs = [r for r in runs if overhang_of(args, r) is not None]
    previous = {}
    if args.merge and os.path.exists(args.merge):
        with open(args.merge) as f:
            for r in json.load(f).get("results", []):
                previous[(r["name"], r["settings"])] = r
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    started = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    fresh = []
    for run in runs:
        r = run_one(args, run)
        r["commit"] = commit
        r["run_at"] = datetime.datetime.now(datetime.timezone.utc).strftime("%H:%M UTC")
        fresh.append(r)
        t = r.get("timings_s", {}).get("total")
        print(f"{r['name']} [{r['settings']}]: exit {r['exit']}, {r.get('blocks', '-')} blocks, "
              f"total {fmt_t(t) or r['wall_s']} s, validate {fmt_t(r.get('validate_wall_s')) or '-'} s: {r['status']}"
              + (f" ({r['error']})" if r.get("error") else ""), file=sys.stderr, flush=True)
        done = {(x["name"], x["settings"]) for x in fresh}
        merged = fresh + [p for k, p in previous.items() if k not in done]
        with open(json_out, "w") as f:
            json.dump({"command": " ".join(sys.argv), "started": started, "load_at_end": os.getloadavg(),
                       "results": merged}, f, indent=1)
    done = {(x["name"], x["settings"]) for x in fresh}
    merged = fresh + [p for k, p in previous.items() if k not in done]
    order = {(r["name"], r["settings"]): i for i, r in enumerate(collect_runs(argparse.Namespace(**{**vars(args), "only": None, "skip": None})))}
    merged.sort(key=lambda r: order.get((r["name"], r["settings"]), 1 << 30))
    print(table(merged))
    bad = [r for r in merged if r["status"].startswith("FAIL")]
    print(f"\n{len(merged)} runs ({len(fresh)} now, commit {commit}), {len(bad)} failures; "
          f"load average {os.getloadavg()[0]:.1f}; rows in {json_out}")
    print(f"command: {' '.join(sys.argv)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
