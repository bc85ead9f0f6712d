#!/usr/bin/env bash
# The meshing benchmark against Gmsh (bench/README.md, "Meshing vs Gmsh"):
# 1. builds laytracks and bench_mesh in Release (build-bench/, tests off);
# 2. meshes the ribbed tray (samples/tray_ribs.json) at about 10k, 100k and 1M quads
#    (bench_mesh --target-quads), and every part of ../shared/cases/*.json,
#    ../shared/cases/external/*.json and samples/*.json at its default size;
# 3. for each of our meshes, meshes the same part with `gmsh -2 -nt 1` (Frontal-Delaunay,
#    RecombineAll, Blossom; subdivision only where triangles remain) at a quad count within 10%
#    of ours, and rates both meshes with our checker (bench/gmsh_compare.py);
# 4. prints three markdown tables (bench/bench_table.py) and leaves them in $OUT/table.md:
#    seconds per stage on the tray, quality beside Gmsh, and the whole commands' times.
#
# Usage: bench/run-bench.sh [--quick]
#   --quick   the tray at 10k quads only and every part at its default size (half a minute)
# Environment: BUILD_DIR (default build-bench), SHARED_DIR (default ../shared), OUT_DIR
# (default out/bench), TIMEOUT (seconds allowed to each bench_mesh run, default 900),
# GMSH_TIMEOUT (seconds allowed to each gmsh run, default 3600: Gmsh takes from 7 minutes to
# more than half an hour for a million quads here), TRAY_TARGETS (default "10000 100000
# 1000000"), JOBS (build jobs, default 2).
# A bench_mesh run that exceeds TIMEOUT becomes a "timed out" row, and Gmsh meshes the part at
# the count asked for; a size our mesher refuses becomes a "refused: ..." row, and Gmsh meshes
# the part at that size.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${BUILD_DIR:-$ROOT/build-bench}"
SHARED="${SHARED_DIR:-$ROOT/../shared}"
OUT="${OUT_DIR:-$ROOT/out/bench}"
TIMEOUT="${TIMEOUT:-900}"
GMSH_TIMEOUT="${GMSH_TIMEOUT:-3600}"
TRAY_TARGETS="${TRAY_TARGETS:-10000 100000 1000000}"
JOBS="${JOBS:-2}"
if [[ "${1:-}" == "--quick" ]]; then TRAY_TARGETS="10000"; fi

if ! command -v gmsh > /dev/null; then
  echo "run-bench: gmsh is missing (scripts/setup.sh installs it)" >&2
  exit 1
fi
command -v python3 > /dev/null || { echo "run-bench: python3 is missing" >&2; exit 1; }

cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DLAYTRACKS_BUILD_TESTS=OFF > /dev/null
cmake --build "$BUILD" -j "$JOBS" --target laytracks bench_mesh > /dev/null
LAYTRACKS="$BUILD/cli/laytracks"
BENCH="$BUILD/bench/bench_mesh"
mkdir -p "$OUT/work"
COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2> /dev/null || echo '?')"
CPU="$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "# $(date -u +%Y-%m-%dT%H:%MZ), commit $COMMIT, Gmsh $(gmsh --version 2>&1)," \
  "$(nproc) cores: $CPU" > "$OUT/machine.txt"

# bench_mesh PART NAME ARGS...: our mesh (or a timeout stub), then Gmsh beside it.
compare() {
  local part="$1" name="$2"
  shift 2
  local ours="$OUT/$name.json" status=0
  echo "== $name: bench_mesh $*" >&2
  timeout "$TIMEOUT" "$BENCH" "$part" "$@" --json "$ours" >&2 || status=$?
  if [[ $status -eq 124 ]]; then
    local target="null"
    if [[ "$1" == "--target-quads" ]]; then target="$2"; fi
    python3 - "$part" "$ours" "$target" "$TIMEOUT" << 'EOF'
import json, sys
part, out, target, seconds = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
req = {"target_quads": float(target)} if target != "null" else "default"
json.dump({"part": part, "rows": [{"status": "timeout", "seconds": seconds, "request": req}]},
          open(out, "w"))
EOF
  elif [[ $status -ne 0 ]]; then
    echo "run-bench: bench_mesh failed on $part (exit $status)" >&2
    return 0
  fi
  python3 "$ROOT/bench/gmsh_compare.py" "$ours" --laytracks "$LAYTRACKS" --work "$OUT/work" \
    --timeout "$GMSH_TIMEOUT" -o "$OUT/$name-gmsh.json"
  RESULTS+=("$OUT/$name-gmsh.json")
}

RESULTS=()
for t in $TRAY_TARGETS; do
  compare "$ROOT/samples/tray_ribs.json" "tray_ribs-$t" --target-quads "$t"
done
TRAY_RESULTS=("${RESULTS[@]}")
RESULTS=()
for part in "$SHARED"/cases/*.json "$SHARED"/cases/external/*.json "$ROOT"/samples/*.json; do
  compare "$part" "$(basename "$part" .json)"
done

{
  cat "$OUT/machine.txt"
  echo
  echo "The tray at growing sizes: seconds per stage"
  echo
  python3 "$ROOT/bench/bench_table.py" --stages "${TRAY_RESULTS[@]}"
  echo
  echo "Quality beside Gmsh"
  echo
  python3 "$ROOT/bench/bench_table.py" "${TRAY_RESULTS[@]}" "${RESULTS[@]}"
  echo
  echo "Whole commands (what a user waits for), best of 3"
  echo
  python3 "$ROOT/bench/bench_table.py" --commands "${TRAY_RESULTS[@]}" "${RESULTS[@]}"
} > "$OUT/table.md"
cat "$OUT/table.md"
