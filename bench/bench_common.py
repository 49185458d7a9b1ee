# SPDX-License-Identifier: GPL-3.0-or-later
"""What the benchmark scripts (run_table_4_1.py, run_sweep.py, run_unfold.py)
share: their common command-line options, the Table 4.1 rows whose model
ships, and the peak memory /usr/bin/time -v reports."""
import csv
import os
import re

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
