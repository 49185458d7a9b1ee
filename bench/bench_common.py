# SPDX-License-Identifier: GPL-3.0-or-later
"""What the benchmark scripts (run_table_4_1.py, run_sweep.py, run_unfold.py,
run_smooth_tolerance.py, run_thesis_tolerances.py) share: their common
command-line options, the Table 4.1 rows whose model ships, commands timed
under /usr/bin/time -v and the peak memory it reports."""
import csv
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def add_common_arguments(ap, out, with_csv):
    """--subfab, --models, --csv (when with_csv), --out (default out/OUT) and --threads."""
    ap.add_argument("--subfab", default=os.path.join(ROOT, "build", "subfab"))
    ap.add_argument("--models", default=os.path.join(ROOT, "..", "shared", "models"))
    if with_csv:
        ap.add_argument("--csv", default=os.path.join(ROOT, "..", "shared", "benchmarks", "paper_table_4_1.csv"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", out))
    ap.add_argument("--threads", type=int, default=0)


def table_4_1_rows(csv_path, models_dir):
    """(rows, files): the rows of the Table 4.1 CSV whose model ships in
    models_dir, in order, without the "no pruning" rows (the same input and
    setting as "Cube Spike"; only the thesis's timing differs), and the set of
    shipped files of all rows."""
    rows, files = [], set()
    with open(csv_path) as f:
        for row in csv.DictReader(f):
            if not row["file"] or not os.path.exists(os.path.join(models_dir, row["file"])):
                continue
            files.add(row["file"])
            if "no pruning" in row["model"]:
                continue
            rows.append(row)
    return rows, files


def peak_rss_mb(stderr_text):
    """Peak resident memory in MB from /usr/bin/time -v's report, None when absent."""
    m = re.search(r"Maximum resident set size \(kbytes\): (\d+)", stderr_text)
    return int(m.group(1)) / 1024.0 if m else None


def timed_run(cmd, timeout):
    """(exit code or None on timeout, stdout, stderr with /usr/bin/time -v's report, wall seconds)."""
    start = time.time()
    try:
        p = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True, timeout=timeout)
        rc, out, err = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired:
        rc, out, err = None, "", f"timeout after {timeout} s"
    return rc, out, err, round(time.time() - start, 2)


def add_run_list_arguments(ap):
    """--only, --dry-run and --timeout of the scripts that run a fixed list of runs."""
    ap.add_argument("--only", nargs="*", help="run only these (model name or file stem; case-insensitive)")
    ap.add_argument("--dry-run", action="store_true", help="print the commands only")
    ap.add_argument("--timeout", type=float, default=3600.0, help="per command, seconds")


def selected(args, name, file):
    """True when --only is not given or names this run (its name or its file's stem)."""
    if not args.only:
        return True
    wanted = {n.lower() for n in args.only}
    return name.lower() in wanted or os.path.splitext(file)[0].lower() in wanted


def logged_run(args, cmd):
    """Prints the command to stderr, then timed_run() it (None with --dry-run)."""
    print("$ " + " ".join(cmd), file=sys.stderr, flush=True)
    return None if args.dry_run else timed_run(cmd, args.timeout)
