#!/usr/bin/env bash
# Meshes parts nobody drew: scripts/stress/gen.py writes about 200 valid parts in 28 families
# (closed prisms and polyhedra, boxes with tunnels, sheet-metal folds, ribs and T-junctions,
# plates with holes, slots and fillets, thin strips, tiny edges, sharp and near-flat corners,
# combs, spirals, many-vertex polygons, flat seams, several shells...), and composite.py's 80
# that mix them (filleted plates with holes and slots, folded brackets, drafted trays with
# holes and windows, rounded rectangles). Each is meshed at its
# default size and with --adaptive, and turned, mirrored and scaled by 1e-3 and 1e3 at its
# default size; a run that is refused (exit != 0), takes more than 60 s, or gives another quad
# count in another pose is listed. Not a test (it takes 10-20 minutes on 2 cores): the check
# before a change lands that the mesher has no refusal waiting for shapes it was not tuned on.
#
# Usage: scripts/stress/run-stress.sh [OUTDIR] [JOBS]   (defaults out/stress, 2)
# Environment: LAYTRACKS (the binary, default build/cli/laytracks), STRESS_LIMIT (mesh only the
# first N parts).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BIN="${LAYTRACKS:-$ROOT/build/cli/laytracks}"
OUT="${1:-$ROOT/out/stress}"
JOBS="${2:-2}"
GEN="$ROOT/scripts/stress/gen.py"
[ -x "$BIN" ] || { echo "run-stress: $BIN is missing (scripts/build.sh builds it)" >&2; exit 1; }
rm -rf "$OUT"
mkdir -p "$OUT/parts" "$OUT/poses" "$OUT/res"
python3 "$GEN" gen "$OUT/parts" > "$OUT/parts.all"
python3 "$ROOT/scripts/stress/composite.py" "$OUT/parts" 20 >> "$OUT/parts.all"
head -n "${STRESS_LIMIT:-100000}" "$OUT/parts.all" > "$OUT/parts.list"
jobs="$OUT/jobs.txt"
: > "$jobs"
while read -r name; do
  echo "$name.def $OUT/parts/$name.json" >> "$jobs"
  echo "$name.adapt $OUT/parts/$name.json --adaptive" >> "$jobs"
  for k in rot mirror s1e-3 s1e3; do
    python3 "$GEN" pose "$OUT/parts/$name.json" "$OUT/poses/$name.$k.json" "$k"
    echo "$name.$k $OUT/poses/$name.$k.json" >> "$jobs"
  done
done < "$OUT/parts.list"
export BIN OUT
one() {
  tag=$1; part=$2; shift 2
  rc=0
  timeout 60 "$BIN" mesh "$part" -o "$OUT/res/$tag.msh" --report "$OUT/res/$tag.json" --quiet "$@" \
    2> "$OUT/res/$tag.err" || rc=$?
  q=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['quads'])" "$OUT/res/$tag.json" 2>/dev/null || echo -)
  printf '%s\t%s\t%s\t%s\n' "$tag" "$rc" "$q" "$(head -c 300 "$OUT/res/$tag.err" | tr '\n\t' '  ')" > "$OUT/res/$tag.res"
  rm -f "$OUT/res/$tag.msh"
}
export -f one
total=$(wc -l < "$jobs")
echo "run-stress: $(wc -l < "$OUT/parts.list") parts, $total runs, $JOBS at a time" >&2
xargs -P "$JOBS" -L 1 bash -c 'one "$@"' _ < "$jobs"
cat "$OUT"/res/*.res > "$OUT/results.tsv"
python3 - "$OUT/results.tsv" <<'PY'
import sys, collections
rows = [l.rstrip('\n').split('\t') for l in open(sys.argv[1])]
bad = [r for r in rows if r[1] != '0']
by_part = collections.defaultdict(dict)
for r in rows:
    name, kind = r[0].rsplit('.', 1) if not r[0].endswith(('s1e-3', 's1e3')) else (r[0][:r[0].rindex('.s1e')], r[0][r[0].rindex('.s1e') + 1:])
    by_part[name][kind] = r[2]
pose = [(n, k) for n, k in by_part.items()
        if len({k.get(x) for x in ('def', 'rot', 'mirror', 's1e-3', 's1e3') if k.get(x) not in (None, '-')}) > 1]
print('%d runs: %d refused or failed, %d parts whose quad count differs between poses' % (len(rows), len(bad), len(pose)))
for r in bad:
    print('  FAIL %s (exit %s): %s' % (r[0], r[1], r[3][:200]))
for n, k in pose:
    print('  POSE %s: %s' % (n, ', '.join('%s %s' % (x, k.get(x)) for x in ('def', 'rot', 'mirror', 's1e-3', 's1e3'))))
PY
