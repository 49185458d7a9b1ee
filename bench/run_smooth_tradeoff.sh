#!/usr/bin/env bash
# Blocks vs deviation (thesis Section 4.3.5): smooth each model with Taubin's
# filter at several deviation caps, decompose the smoothed mesh, validate it.
# Usage: bench/run_smooth_tradeoff.sh SUBFAB OUTDIR "model:height ..." "cap ..." [smooth options]
# e.g.   bench/run_smooth_tradeoff.sh build/subfab /tmp/st "max_planck: egea:0.1" "0.005 0.01" --passes 100 --mu -0.505
# Prints one line per run: model cap hausdorff/diag mean/diag smooth_s blocks decompose_s validate
set -u
SUBFAB=$1; OUT=$2; MODELS=$3; CAPS=$4; shift 4
MODELS_DIR=$(dirname "$0")/../../shared/models
mkdir -p "$OUT"
for cap in $CAPS; do
  for spec in $MODELS; do
    model=${spec%%:*}; height=${spec#*:}
    src=$MODELS_DIR/$model.obj
    tag=${model}_$cap
    hopt=""; [ -n "$height" ] && hopt="--max-height $height"
    "$SUBFAB" smooth "$src" -o "$OUT/$tag.obj" --max-deviation "$cap" --json --quiet "$@" > "$OUT/$tag.smooth.json" 2> "$OUT/$tag.smooth.err"
    t0=$(date +%s.%N)
    "$SUBFAB" decompose "$OUT/$tag.obj" -o "$OUT/$tag" $hopt --quiet > "$OUT/$tag.decompose.log" 2>&1
    rc=$?
    t1=$(date +%s.%N)
    if [ $rc -eq 0 ]; then
      "$SUBFAB" validate "$OUT/$tag.obj" "$OUT/$tag" --quiet > "$OUT/$tag.validate.log" 2>&1 && v=pass || v=FAIL
      blocks=$(python3 -c "import json;print(json.load(open('$OUT/$tag/decomposition.json'))['summary']['num_blocks'])")
    else
      v="decompose-exit-$rc"; blocks=-
    fi
    python3 - "$OUT/$tag.smooth.json" "$model" "$height" "$cap" "$blocks" "$t0" "$t1" "$v" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
m, h, cap, blocks, t0, t1, v = sys.argv[2:]
print(f"{m:12s} h={h or '-':5s} cap={cap:6s} hausdorff={j['hausdorff_fraction']:.5f} mean={j['mean_deviation_fraction']:.6f} "
      f"maxmove={j['max_displacement_fraction']:.5f} frozen={j['num_vertices_frozen']} smooth_s={j['seconds']:.1f} "
      f"blocks={blocks} decompose_s={float(t1)-float(t0):.1f} validate={v}", flush=True)
PY
  done
done
