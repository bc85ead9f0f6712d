#!/usr/bin/env python3
"""Sums up bench/gmsh_compare.py's JSON files of many parts (bench/run-generated.sh): of the
parts where Gmsh's valid mesh came within 10% of our quad count, on how many each mesher has
the better worst corner (scaled Jacobian, ties within 0.01), fewer quads beyond each threshold
of quality.md (ties within 0.5 point), and the faster whole command; the means; and the parts
where we are behind, worst first.

    python3 bench/generated_table.py COMPARE.json ...
"""
import json
import os
import sys

from bench_table import measures  # (worst scaled Jacobian, skew %, aspect %, taper %)

KEYS = ("sj", "skew", "aspect", "taper")


def load(path):
    d = json.load(open(path))
    row = d["rows"][0]
    ours, gmsh = row["ours"], row["gmsh"]
    name = os.path.basename(path)[: -len("-gmsh.json")]
    if ours.get("status") != "ok":
        return name, None
    r = dict(zip(KEYS, measures(ours["quality"])), quads=ours["quads"], gmsh=None)
    if gmsh.get("status") == "ok" and gmsh.get("valid"):
        c = gmsh.get("commands", {})
        r["gmsh"] = dict(zip(KEYS, measures(gmsh["quality"])), quads=gmsh["quads"],
                         ours_s=c.get("ours"), gmsh_s=c.get("gmsh"))
    elif gmsh.get("status") == "ok":
        r["gmsh_invalid"] = gmsh.get("failed_rules")
    return name, r


def main():
    rows = [load(p) for p in sys.argv[1:]]
    ours_ok = [(n, r) for n, r in rows if r]
    invalid = [(n, r) for n, r in ours_ok if r.get("gmsh_invalid")]
    valid = [(n, r) for n, r in ours_ok if r["gmsh"]]
    near = [(n, r) for n, r in valid if abs(r["gmsh"]["quads"] - r["quads"]) <= 0.1 * r["quads"]]
    print("%d parts; ours valid on %d; Gmsh valid on %d (invalid by quality.md on %d: %s); "
          "within 10%% of our count on %d (the rest: Gmsh cannot come down to our count, or "
          "its counts jump past it)" % (len(rows), len(ours_ok), len(valid), len(invalid),
                                        ", ".join(n for n, _ in invalid) or "none", len(near)))
    print()
    print("| measure (on the %d parts at a similar count) | ours better | equal | Gmsh better "
          "| our mean | Gmsh's mean |" % len(near))
    print("|---|---:|---:|---:|---:|---:|")
    behind = {}
    for key, label, tie, higher_better in (("sj", "worst scaled Jacobian", 0.01, True),
                                           ("skew", "% skew >= 30", 0.5, False),
                                           ("aspect", "% aspect >= 5", 0.5, False),
                                           ("taper", "% taper <= 0.8", 0.5, False)):
        b = e = w = 0
        for n, r in near:
            d = r[key] - r["gmsh"][key]
            if not higher_better:
                d = -d
            if d > tie:
                b += 1
            elif d < -tie:
                w += 1
                behind.setdefault(key, []).append((abs(d), n, r))
            else:
                e += 1
        mo = sum(r[key] for _, r in near) / max(len(near), 1)
        mg = sum(r["gmsh"][key] for _, r in near) / max(len(near), 1)
        print("| %s | %d | %d | %d | %.3f | %.3f |" % (label, b, e, w, mo, mg))
    timed = [(n, r) for n, r in near if r["gmsh"]["ours_s"] and r["gmsh"]["gmsh_s"]]
    faster = [(n, r) for n, r in timed if r["gmsh"]["ours_s"] < r["gmsh"]["gmsh_s"]]
    slower = sorted([(r["gmsh"]["ours_s"] / r["gmsh"]["gmsh_s"], n, r) for n, r in timed
                     if r["gmsh"]["ours_s"] >= r["gmsh"]["gmsh_s"]], reverse=True)
    print()
    print("Whole commands (best of 3): ours faster on %d of %d; slower on %s" %
          (len(faster), len(timed), ", ".join("%s (%.3f s against %.3f s)" %
                                              (n, r["gmsh"]["ours_s"], r["gmsh"]["gmsh_s"])
                                              for _, n, r in slower) or "none"))
    print()
    print("Where Gmsh is ahead, by the most first (ours / Gmsh's):")
    for key in KEYS:
        for d, n, r in sorted(behind.get(key, []), key=lambda t: -t[0])[:8]:
            print("- %s %s: %.3f / %.3f (%d / %d quads)" %
                  (n, key, r[key], r["gmsh"][key], r["quads"], r["gmsh"]["quads"]))


if __name__ == "__main__":
    main()
