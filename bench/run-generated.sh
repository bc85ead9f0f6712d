#!/usr/bin/env bash
# Quality and speed beside Gmsh on parts nobody tuned for (bench/README.md, "Generated parts
# beside Gmsh"): the ~217 parts of scripts/stress/gen.py and the 80 of composite.py (the
# stress run's parts), each meshed by bench_mesh at its default size, then by `gmsh -2 -nt 1`
# at a count within 5% of ours where Gmsh can reach it (bench/gmsh_compare.py: the same
# search, the same options as run-bench.sh), both rated by our checker; then
# bench/generated_table.py sums up where each mesher is ahead.
#
# Usage: bench/run-generated.sh [OUTDIR] [JOBS]   (defaults out/generated, 2; 10 minutes
#        on 2 cores)
# Environment: BUILD_DIR (default build-bench), GEN_LIMIT (only the first N parts).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${BUILD_DIR:-$ROOT/build-bench}"
OUT="${1:-$ROOT/out/generated}"
JOBS="${2:-2}"
command -v gmsh > /dev/null || { echo "run-generated: gmsh is missing (scripts/setup.sh installs it)" >&2; exit 1; }
cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release -DLAYTRACKS_BUILD_TESTS=OFF > /dev/null
cmake --build "$BUILD" -j "$JOBS" --target laytracks bench_mesh > /dev/null
rm -rf "$OUT"
mkdir -p "$OUT/parts" "$OUT/work"
python3 "$ROOT/scripts/stress/gen.py" gen "$OUT/parts" > "$OUT/parts.all"
python3 "$ROOT/scripts/stress/composite.py" "$OUT/parts" 20 >> "$OUT/parts.all"
head -n "${GEN_LIMIT:-100000}" "$OUT/parts.all" > "$OUT/parts.list"
export LAYTRACKS="$BUILD/cli/laytracks" BENCH="$BUILD/bench/bench_mesh" OUT ROOT
one() {
  local name=$1
  if ! timeout 300 "$BENCH" "$OUT/parts/$name.json" --json "$OUT/$name.json" > /dev/null 2>&1; then
    echo "run-generated: bench_mesh failed on $name" >&2
    return 0
  fi
  mkdir -p "$OUT/work/$name"
  python3 "$ROOT/bench/gmsh_compare.py" "$OUT/$name.json" --laytracks "$LAYTRACKS" \
    --work "$OUT/work/$name" --timeout 120 -o "$OUT/$name-gmsh.json" 2> /dev/null ||
    echo "run-generated: gmsh_compare failed on $name" >&2
  rm -f "$OUT/work/$name"/*.msh
}
export -f one
echo "run-generated: $(wc -l < "$OUT/parts.list") parts, $JOBS at a time" >&2
xargs -P "$JOBS" -n 1 bash -c 'one "$@"' _ < "$OUT/parts.list"
python3 "$ROOT/bench/generated_table.py" "$OUT"/*-gmsh.json | tee "$OUT/table.md"
