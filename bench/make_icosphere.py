#!/usr/bin/env python3
"""Writes a faceted closed shell for the benchmark: an icosphere, 20 x 4^LEVEL triangular
patches on a sphere of radius R (the icosahedron's faces split into four LEVEL times, the new
vertices pushed out to the sphere). The same shell as icosphere() in tests/support.

Usage: bench/make_icosphere.py LEVEL R OUT.json
"""
import json
import math
import sys


def icosphere(level):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
         (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
         (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
         (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = [(v[a][i] + v[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                middle[key] = len(v) - 1
            return middle[key]

        g = []
        for a, b, c in f:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            g += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = g
    return v, f


def main():
    if len(sys.argv) != 4 or sys.argv[1].startswith("-"):
        sys.exit(__doc__.strip())
    level, radius, out = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3]
    v, f = icosphere(level)
    part = {"laytracks": "brep/1", "units": "mm",
            "vertices": [[radius * c for c in p] for p in v],
            "patches": [{"name": "f%d" % i, "loops": [list(t)]} for i, t in enumerate(f)]}
    with open(out, "w") as fh:
        json.dump(part, fh)


if __name__ == "__main__":
    main()
