#!/usr/bin/env bash
# CTest: a few parts of scripts/stress/composite.py (two of each family: filleted plates with
# holes and slots, folded brackets, drafted trays with holes and windows, rounded rectangles)
# mesh to valid all-quad meshes at their size, turned and scaled by 1e-3 as well, with one
# quad count in all three poses. The full run, five poses of 297 parts, is run-stress.sh.
# Usage: stress_smoke.sh LAYTRACKS
set -euo pipefail
BIN="$1"
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
python3 "$ROOT/scripts/stress/composite.py" "$TMP/parts" 2 > "$TMP/list"
[ "$(wc -l < "$TMP/list")" -eq 8 ] || { echo "composite.py wrote $(wc -l < "$TMP/list") parts, not 8"; exit 1; }
fail=0
while read -r name; do
  part="$TMP/parts/$name.json"
  python3 "$ROOT/scripts/stress/gen.py" pose "$part" "$TMP/$name.rot.json" rot
  python3 "$ROOT/scripts/stress/gen.py" pose "$part" "$TMP/$name.small.json" s1e-3
  counts=""
  for p in "$part" "$TMP/$name.rot.json" "$TMP/$name.small.json"; do
    if ! "$BIN" mesh "$p" -o "$TMP/m.msh" --report "$TMP/r.json" --quiet 2> "$TMP/err"; then
      echo "FAIL $(basename "$p"): $(head -c 300 "$TMP/err")"; fail=1; continue
    fi
    q=$(python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['valid']; print(d['quads'])" "$TMP/r.json") \
      || { echo "FAIL $(basename "$p"): the report says invalid"; fail=1; continue; }
    counts="$counts $q"
  done
  [ "$(echo $counts | tr ' ' '\n' | sort -u | wc -l)" -eq 1 ] || { echo "FAIL $name: quads by pose:$counts"; fail=1; }
  echo "$name:$counts"
done < "$TMP/list"
exit $fail
