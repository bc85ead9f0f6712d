#!/usr/bin/env python3
"""Markdown tables from the JSON files of bench/gmsh_compare.py (one per bench_mesh run).

    python3 bench/bench_table.py [--stages] COMPARE.json ...

Prints one table row per bench_mesh row: our quads, seconds, quads/s, smallest scaled
Jacobian, % of quads with skew >= 30 degrees, aspect ratio >= 5, taper <= 0.8, and validity by
quality.md, then the same for Gmsh's mesh at a similar count (with whether it is all-quad).
With --stages, prints instead the seconds of each of our stages and Gmsh's times.
"""
import argparse
import json
import os
import sys


def name_of(path):
    stem = os.path.splitext(os.path.basename(path))[0]
    return stem


def pct(x):
    return "-" if x is None else "%.2f" % x


def num(x, f="%.3f"):
    return "-" if x is None else f % x


def measures(q):
    m = q["measures"]
    return (m["scaled_jacobian"]["worst"], m["skew_deg"]["bad_percent"],
            m["aspect_ratio"]["bad_percent"], m["taper"]["bad_percent"])


def ours_cells(r):
    st = r.get("status")
    if st == "refused":
        msg = r.get("message", "").replace("|", "/")
        if len(msg) > 90:
            msg = msg[:87] + "..."
        return ["refused: " + msg] + [""] * 7
    if st == "timeout":
        return ["timed out after %d s" % r.get("seconds", 0)] + [""] * 7
    sj, skew, asp, tap = measures(r["quality"])
    t = r["seconds"]["total"]
    return ["{:,}".format(r["quads"]), num(t, "%.2f"), "{:,.0f}".format(r["quads"] / t if t else 0),
            num(sj), pct(skew), pct(asp), pct(tap), "yes" if r["valid"] else "NO"]


def gmsh_valid(g):
    if "valid" not in g:
        return "?"
    text = "yes" if g["valid"] else "no (rules %s)" % ",".join(g.get("failed_rules", []))
    return text


def gmsh_cells(g):
    st = g.get("status")
    if st != "ok":
        return ["gmsh %s%s" % (st, (": " + g["message"]) if g.get("message") else "")] + [""] * 8
    sj, skew, asp, tap = measures(g["quality"])
    t = g["mesh_wall"]
    allquad = "yes" if g["triangles"] == 0 else "no (%d triangles)" % g["triangles"]
    count = "{:,}".format(g["quads"])
    notes = []
    if g.get("nearest"):
        notes.append("nearest")
    w = g.get("without_subdivision")
    if w:
        notes.append("subdivided; before: {:,} quads + {:,} triangles".format(w["quads"],
                                                                             w["triangles"]))
    if notes:
        count += " (" + "; ".join(notes) + ")"
    if g.get("target_quads") is None:
        count += " (at our h)"
    return [count, num(t, "%.2f"), "{:,.0f}".format(g["quads"] / t if t else 0),
            num(sj), pct(skew), pct(asp), pct(tap), allquad, gmsh_valid(g)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("files", nargs="+")
    ap.add_argument("--stages", action="store_true")
    ap.add_argument("--commands", action="store_true")
    args = ap.parse_args()
    if args.commands:
        print("| part | quads | `laytracks mesh` [s] | Gmsh quads | `gmsh -2` [s] | Gmsh / ours |")
        print("|---|---:|---:|---:|---:|---:|")
        for path in args.files:
            with open(path) as f:
                doc = json.load(f)
            for row in doc["rows"]:
                c = row["gmsh"].get("commands")
                if not c:
                    continue
                print("| %s | {:,} | %.3f | {:,} | %.3f | %.1f |".format(
                    row["ours"]["quads"], row["gmsh"]["quads"]) %
                      (name_of(doc["part"]), c["ours"], c["gmsh"], c["gmsh"] / c["ours"]))
        return 0
    if args.stages:
        print("| part | h | quads | medial | rails | quads | refill | smooth | check | total [s] | cpu [s] "
              "| quads/s | Gmsh quads | Gmsh lc | Gmsh 1D+2D [s] | Gmsh cpu [s] | Gmsh command [s] "
              "| Gmsh quads/s |")
        print("|---|" + "---:|" * 17)
    else:
        print("| part | quads | s | quads/s | min SJ | skew>=30 % | aspect>=5 % | taper<=0.8 % "
              "| valid | Gmsh quads | s | quads/s | min SJ | skew>=30 % | aspect>=5 % "
              "| taper<=0.8 % | all-quad | valid |")
        print("|---|" + "---:|" * 7 + "---|" + "---:|" * 7 + "---|---|")
    for path in args.files:
        with open(path) as f:
            doc = json.load(f)
        for row in doc["rows"]:
            o, g = row["ours"], row["gmsh"]
            name = name_of(doc["part"])
            if args.stages:
                if o.get("status") == "ok":
                    s = o["seconds"]
                    cells = [num(o["size"], "%.4g"), "{:,}".format(o["quads"]), num(s["medial"]),
                             num(s["rails"]), num(s["quads"]), num(s.get("refill")),
                             num(s["smooth"]), num(s["check"]),
                             num(s["total"]), num(s.get("cpu")),
                             "{:,.0f}".format(o["quads"] / s["total"])]
                else:
                    cells = [num(o.get("size"), "%.4g"), ours_cells(o)[0]] + [""] * 9
                if g.get("status") == "ok":
                    cells += ["{:,}".format(g["quads"]), num(g["lc"], "%.4g"), num(g["mesh_wall"]),
                              num(g["mesh_cpu"]), num(g["wall"]),
                              "{:,.0f}".format(g["quads"] / g["mesh_wall"])]
                else:
                    cells += [gmsh_cells(g)[0], "", "", "", "", ""]
            else:
                cells = ours_cells(o) + gmsh_cells(g)
            print("| " + " | ".join([name] + cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
