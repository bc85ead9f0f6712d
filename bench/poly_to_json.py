#!/usr/bin/env python3
"""Turns a polygon file of CGAL's straight-skeleton test data (`<name>.poly`) into a one-patch
part in the B-Rep JSON format (../shared/spec/brep-json.md), the way ../shared/cases/external
was made: z = 0, the first loop the outer one, the others holes, `mesh.size` = the bounding
box's diagonal / 60.

    python3 bench/poly_to_json.py IN.poly OUT.json [--name NAME] [--per-diagonal N]

A .poly file is whitespace-separated numbers: the number of loops, then for each loop its
vertex count and that many x y pairs. Line breaks do not matter (some files have CR or CRLF
ends, or all numbers on one line). A file that does not read that way is refused with the
token where it went wrong, and nothing is written. The loops are kept as given (orientation
and all): whether they make a valid part is for `laytracks` to say.
"""
import argparse
import json
import math
import os
import sys


def read_poly(text):
    tokens = text.split()
    pos = 0

    def take(what):
        nonlocal pos
        if pos >= len(tokens):
            raise ValueError("the file ends where %s was expected (token %d)" % (what, pos + 1))
        tok = tokens[pos]
        pos += 1
        return tok

    def parse(what, convert, ok, problem):
        tok = take(what)
        try:
            x = convert(tok)
        except ValueError:
            raise ValueError("token %d: expected %s, got %r" % (pos, what, tok)) from None
        if not ok(x):
            raise ValueError("token %d: %s is %s" % (pos, what, problem))
        return x

    def count(what):
        return parse(what, int, lambda n: n >= 0, "negative")

    def number(what):
        return parse(what, float, math.isfinite, "not finite")

    loops = []
    for l in range(count("the number of loops")):
        n = count("the vertex count of loop %d" % l)
        loops.append([(number("x of vertex %d of loop %d" % (i, l)), number("y of vertex %d of loop %d" % (i, l)))
                      for i in range(n)])
    if pos != len(tokens):
        raise ValueError("%d numbers left after the last loop (token %d: %r)" % (len(tokens) - pos, pos + 1, tokens[pos]))
    if not loops:
        raise ValueError("no loops")
    return loops


def to_part(loops, name, per_diagonal):
    vertices, index_loops = [], []
    for loop in loops:
        index_loops.append(list(range(len(vertices), len(vertices) + len(loop))))
        vertices.extend([x, y, 0.0] for x, y in loop)
    xs = [v[0] for v in vertices]
    ys = [v[1] for v in vertices]
    diagonal = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    part = {"laytracks": "brep/1", "units": "mm", "vertices": vertices,
            "patches": [{"name": name, "loops": index_loops}]}
    if diagonal > 0.0:
        part["mesh"] = {"size": float("%.6g" % (diagonal / per_diagonal))}
    return part


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("poly")
    ap.add_argument("out")
    ap.add_argument("--name", help="the patch's name (default: the file's name without .poly)")
    ap.add_argument("--per-diagonal", type=float, default=60.0,
                    help="mesh.size = bounding-box diagonal / this (default 60)")
    args = ap.parse_args()
    name = args.name or os.path.splitext(os.path.basename(args.poly))[0]
    try:
        with open(args.poly, encoding="ascii", errors="replace") as f:
            loops = read_poly(f.read())
    except (OSError, ValueError) as e:
        sys.exit("poly_to_json: %s: %s" % (args.poly, e))
    part = to_part(loops, name, args.per_diagonal)
    tmp = args.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(part, f, indent=1)
        f.write("\n")
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
