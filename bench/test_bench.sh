#!/usr/bin/env bash
# CTest smoke test of the benchmark's tools (registered by bench/CMakeLists.txt):
# - bench_mesh meshes a part at a size and at a target quad count (within 10%) and writes JSON;
# - brep_to_geo.py gives Gmsh a conformal, correctly oriented geometry: Gmsh's meshes of a
#   T-junction, a closed cube, a plate with a hole of four arcs and the ribbed tray are valid
#   by `laytracks quality`.
# Usage: test_bench.sh BENCH_MESH LAYTRACKS CASES_DIR
set -euo pipefail
BENCH="$1"
LAYTRACKS="$2"
CASES="$3"
HERE="$(cd "$(dirname "$0")" && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT

"$BENCH" "$CASES/rect_10x4.json" --size 0.5 --target-quads 500 --json "$TMP/b.json" > /dev/null
python3 - "$TMP/b.json" << 'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
rows = d["rows"]
assert len(rows) == 2, rows
assert rows[0]["status"] == "ok" and rows[0]["quads"] == 160 and rows[0]["valid"], rows[0]
assert rows[1]["status"] == "ok" and abs(rows[1]["quads"] - 500) <= 50, rows[1]
for k in ("medial", "rails", "quads", "smooth", "check", "total", "cpu"):
    assert rows[0]["seconds"][k] >= 0.0
EOF

if ! command -v gmsh > /dev/null; then
  echo "gmsh is missing: the Gmsh half of the test is skipped"
  exit 0
fi
mesh() {  # mesh PART OUT.geo [brep_to_geo options]: gmsh's .msh beside the .geo
  local part="$1" geo="$2"
  shift 2
  python3 "$HERE/brep_to_geo.py" "$part" -o "$geo" "$@"
  gmsh "$geo" -2 -nt 1 -o "${geo%.geo}.msh" > "${geo%.geo}.log" 2>&1
}
for part in "$CASES/t_junction.json" "$CASES/closed_cube.json" "$CASES/plate_with_hole.json" \
  "$HERE/../samples/tray_ribs.json"; do
  name="$(basename "$part" .json)"
  mesh "$part" "$TMP/$name.geo"
  "$LAYTRACKS" quality "$part" "$TMP/$name.msh" --quiet
done
echo "bench tools: ok"
