#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The "Repair" table of bench/RESULTS.md: every model of ../shared/models that
# the solid-based commands refuse, repaired (subfab repair), then
# decompose --repair + validate, and unfold --repair. Usage (from the repo root,
# after building build/subfab): bash bench/run_repair.sh [OUTDIR]
set -u
OUT=${1:-out/bench_repair}
M=../shared/models
S=./build/subfab
mkdir -p "$OUT"
run() {  # name, decompose options
  local name=$1; shift
  local mesh=$M/$name.obj
  echo "== $name"
  /usr/bin/time -f "repair wall %e s, peak %M KB" $S repair "$mesh" -o "$OUT/$name.repaired.obj" --json --threads 1 \
    >"$OUT/$name.repair.json" 2>"$OUT/$name.repair.err"; echo "repair exit $?"; grep -E "error|wall" "$OUT/$name.repair.err"
  /usr/bin/time -f "decompose wall %e s" $S decompose "$mesh" -o "$OUT/$name.dec" --repair "$@" --json --threads 1 \
    >"$OUT/$name.dec.json" 2>"$OUT/$name.dec.err"; echo "decompose exit $?"; grep -E "^error|wall" "$OUT/$name.dec.err"
  $S validate "$mesh" "$OUT/$name.dec" --quiet --threads 1 >"$OUT/$name.val.txt" 2>&1; echo "validate exit $?"
  /usr/bin/time -f "unfold wall %e s" $S unfold "$mesh" -o "$OUT/$name.unf" --repair --json --threads 1 \
    >"$OUT/$name.unf.json" 2>"$OUT/$name.unf.err"; echo "unfold exit $?"; grep -E "^error|wall" "$OUT/$name.unf.err"
}
run gentildonna --max-height 0.125
run stanford_bunny_open
run teapot
run cow
