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

# poly_to_json.py: a CGAL .poly (CRLF ends, a hole) becomes a part laytracks meshes; a file
# whose counts do not add up is refused with where, and nothing is written.
printf '2\r\n4\r\n0 0\r\n4 0\r\n4 3\r\n0 3\r\n4 1 1 2 1 2 2 1 2\r\n' > "$TMP/sq.poly"
python3 "$HERE/poly_to_json.py" "$TMP/sq.poly" "$TMP/sq.json"
python3 - "$TMP/sq.json" << 'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
assert d["patches"] == [{"name": "sq", "loops": [[0, 1, 2, 3], [4, 5, 6, 7]]}], d["patches"]
assert d["vertices"][5] == [2.0, 1.0, 0.0], d["vertices"]
assert d["mesh"] == {"size": 0.0833333}, d["mesh"]
EOF
"$LAYTRACKS" mesh "$TMP/sq.json" -o "$TMP/sq.msh" --quiet
printf '1\n5\n0 0\n1 0\n1 1\n0 1\n' > "$TMP/short.poly"
if python3 "$HERE/poly_to_json.py" "$TMP/short.poly" "$TMP/short.json" 2> "$TMP/short.err"; then
  echo "poly_to_json accepted a loop of 5 vertices given 4" >&2
  exit 1
fi
grep -q "the file ends where x of vertex 4 of loop 0 was expected" "$TMP/short.err"
test ! -e "$TMP/short.json"

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
# gmsh_compare.py and generated_table.py (bench/run-generated.sh's summing up) on one part:
# every measure's counts (ours better, equal, Gmsh better) add up to the parts compared.
"$BENCH" "$CASES/rect_10x4.json" --json "$TMP/rect_10x4.json" > /dev/null
python3 "$HERE/gmsh_compare.py" "$TMP/rect_10x4.json" --laytracks "$LAYTRACKS" --work "$TMP/gw" \
  -o "$TMP/rect_10x4-gmsh.json" 2> /dev/null
python3 "$HERE/generated_table.py" "$TMP/rect_10x4-gmsh.json" > "$TMP/table.md"
python3 - "$TMP/table.md" << 'EOF'
import re, sys
t = open(sys.argv[1]).read()
assert t.startswith("1 parts; ours valid on 1; Gmsh valid on 1"), t
n = int(re.search(r"on the (\d+) parts at a similar count", t).group(1))
rows = [l for l in t.splitlines() if l.startswith("| ") and "measure" not in l]
assert len(rows) == 4, rows
for l in rows:
    c = [int(x) for x in l.split("|")[2:5]]
    assert sum(c) == n, l
assert "Whole commands (best of 3): ours faster on" in t, t
EOF
echo "bench tools: ok"
