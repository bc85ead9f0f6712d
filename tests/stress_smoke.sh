#!/usr/bin/env bash
# CTest: a few generated parts mesh to valid all-quad meshes at their size, turned and scaled
# by 1e-3 as well, with one quad count in all three poses. `composite` (the default): two of
# each family of scripts/stress/composite.py (filleted plates with holes and slots, folded
# brackets, drafted trays with holes and windows, rounded rectangles); `shells`: two of each
# family of scripts/stress/shells.py (convex hulls of random points, prisms with needle caps,
# prisms with a hole, ribbed plates, folded strips). The full runs are run-stress.sh (five
# poses of 297 parts) and run-fuzz.py.
# Usage: stress_smoke.sh LAYTRACKS [composite|shells]
set -euo pipefail
BIN="$1"
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
KIND="${2:-composite}"
if [ "$KIND" = shells ]; then
  # shells.py lists paths (first column); the names are the files'.
  python3 "$ROOT/scripts/stress/shells.py" "$TMP/parts" 10 47051 | cut -f1 | xargs -n 1 basename -s .json > "$TMP/list"
  want=10
else
  python3 "$ROOT/scripts/stress/composite.py" "$TMP/parts" 2 > "$TMP/list"
  want=8
fi
[ "$(wc -l < "$TMP/list")" -eq "$want" ] || { echo "$KIND wrote $(wc -l < "$TMP/list") parts, not $want"; exit 1; }
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
