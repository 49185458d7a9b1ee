#!/bin/sh
# Hexahedral meshing table of bench/RESULTS.md ("Hexahedral meshing"):
# one model at a time, default options. Usage: bench/run_hexmesh.sh [OUT] [MODEL...]
# Extra options in HEXMESH_FLAGS (e.g. HEXMESH_FLAGS=--scaling for resolution control, D.5).
set -e
out=${1:-/tmp/hexbench}
shift 2>/dev/null || true
mkdir -p "$out"
models=${*:-"cactus.off fertility.off humanoid.off bob.obj spot.obj rocker_arm.obj elephant.obj"}
for m in $models; do
  name=${m%.*}
  start=$(date +%s.%N)
  code=0
  ${SUBFAB:-build/subfab} hexmesh ../shared/models/$m -o $out/$name --json --quiet --no-view ${HEXMESH_FLAGS:-} > $out/$name.stdout 2> $out/$name.stderr || code=$?
  end=$(date +%s.%N)
  python3 - "$out/$name/hexmesh.json" "$name" "$code" "$start" "$end" <<'PY'
import json, sys
path, name, code, start, end = sys.argv[1:]
try:
    j = json.load(open(path))
except Exception as e:
    print(f"{name}: no json ({e}), exit {code}"); sys.exit()
sj = j["scaled_jacobian"]
print(f"{name}: exit {code}, wall {float(end) - float(start):.1f} s, tris {j['input_triangles']}, "
      f"skeleton nodes {j['skeleton_nodes']}, cubes/tubes {j['cubes']}/{j['tubes']}, hexahedra {j['hexahedra']}, "
      f"SJ avg/min {sj['avg']:.3f}/{sj['min']:.4f}, inverted {j['inverted']}, "
      f"mean/max dist {j['mean_distance_fraction']:.2e}/{j['max_distance_fraction']:.2e}, "
      f"vertices mean/max {j['mean_vertex_distance_fraction']:.2e}/{j['max_vertex_distance_fraction']:.2e}, "
      f"off {j.get('vertices_off_surface', '?')}/{j.get('boundary_vertices', '?')}, "
      f"total {j['seconds_total']:.1f} s, optimise {j['seconds']['subdivide + project + optimise']:.1f} s", end="")
rc = j.get("resolution_control")
if isinstance(rc, dict) and rc.get("enabled"):
    print(f", cones found/used {rc['cones_found']}/{rc['cones_used']}, levels {j['min_subdivisions']}-{j['subdivisions']}, "
          f"ILP {rc['ilp']['variables']} vars {rc['ilp']['seconds'] * 1000:.1f} ms")
else:
    print()
PY
done
