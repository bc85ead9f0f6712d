#!/usr/bin/env python3
"""Writes a laytracks B-Rep JSON part (../shared/spec/brep-json.md) as a Gmsh .geo file.

    python3 bench/brep_to_geo.py PART.json -o PART.geo [--lc H]

What the .geo holds:
- a Point per vertex used by a loop, with the characteristic length `lc`;
- one curve per B-Rep edge (an unordered vertex pair), shared by every patch that uses the
  edge, so Gmsh meshes it once and the mesh is conformal across folds, seams and T-junctions.
  A loop that runs an edge against the curve's direction refers to it with a minus sign;
- a straight edge is a Line. An arc (`arcs`) is Gmsh Circle pieces {start, centre, end}: the
  centre is that of the circle through from, via and to (as brep/src/arcs.cpp finds it), and
  an arc of 180 degrees or more is split into equal pieces below 180 (Gmsh's Circle takes the
  arc of less than Pi between its ends), so Gmsh puts its nodes on the true circle, as our
  mesher does and as our checker asks (rule 6 holds arc nodes to the circle);
- a Curve Loop per loop and a Plane Surface per patch, tag = patch index + 1 (the first loop
  is the outer boundary, then the holes), so that `laytracks quality` maps surface t to patch
  t - 1; one Physical Surface per patch, named like the patch, tag = patch index + 1;
- the meshing options of the benchmark: Mesh.Algorithm = 6 (Frontal-Delaunay), RecombineAll,
  RecombinationAlgorithm = 1 (Blossom), MSH 4.1 ASCII. Two ONELAB constants can be set from
  the command line without rewriting the file: `-setnumber lc H` (the characteristic length,
  default --lc) and `-setnumber subdivide 1` (Mesh.SubdivisionAlgorithm = 1: every element
  split into quads, which halves the element size; default 0).

Only the standard library is used. Exit status 0, 1 for an unreadable part, 2 for a wrong
command line.
"""
import argparse
import json
import math
import sys


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def add(a, b):
    return [a[0] + b[0], a[1] + b[1], a[2] + b[2]]


def scale(k, a):
    return [k * a[0], k * a[1], k * a[2]]


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def norm(a):
    return math.sqrt(dot(a, a))


def normalized(a):
    n = norm(a)
    return [a[0] / n, a[1] / n, a[2] / n]


def part_size(vertices, used):
    """Twice the largest distance of a used vertex from their centroid (Part::size)."""
    pts = [vertices[i] for i in sorted(used)]
    c = [0.0, 0.0, 0.0]
    for p in pts:
        c = add(c, p)
    c = scale(1.0 / max(len(pts), 1), c)
    return 2.0 * max(norm(sub(p, c)) for p in pts)


def fit_circle(a, b, via):
    """Centre, radius, unit axis and span (0, 2 pi] of the arc from a through via to b, as
    brep/src/arcs.cpp computes them."""
    va = sub(a, via)
    vb = sub(b, via)
    n = cross(va, vb)
    w = sub(scale(dot(va, va), vb), scale(dot(vb, vb), va))
    offset = scale(1.0 / (2.0 * dot(n, n)), cross(w, n))
    centre = add(via, offset)
    radius = norm(sub(a, centre))
    axis = normalized(cross(sub(via, a), sub(b, via)))
    e1 = normalized(sub(a, centre))
    e2 = cross(axis, e1)
    span = math.atan2(dot(sub(b, centre), e2), dot(sub(b, centre), e1))
    if span <= 0.0:
        span += 2.0 * math.pi
    return centre, radius, e1, e2, span


def fmt(x):
    return repr(float(x))


def convert(part, lc, source):
    vertices = part["vertices"]
    patches = part["patches"]
    used = set()
    for p in patches:
        for loop in p["loops"]:
            used.update(loop)
    size = part_size(vertices, used)

    arcs = {}
    for k, arc in enumerate(part.get("arcs", [])):
        arcs[(min(arc["from"], arc["to"]), max(arc["from"], arc["to"]))] = arc

    out = []
    w = out.append
    w("// Made by bench/brep_to_geo.py from %s." % source)
    w('DefineConstant[ lc = {%s, Name "lc"}, subdivide = {0, Name "subdivide"} ];' % fmt(lc))
    w("Mesh.Algorithm = 6;              // Frontal-Delaunay")
    w("Mesh.RecombineAll = 1;")
    w("Mesh.RecombinationAlgorithm = 1; // Blossom")
    w("Mesh.SubdivisionAlgorithm = subdivide;")
    w("Mesh.MshFileVersion = 4.1;")
    w("Mesh.Binary = 0;")
    w("Geometry.Tolerance = %s;" % fmt(1e-9 * size))
    w("Geometry.AutoCoherence = 0;      // every shared edge is already one curve")

    point_tag = {}  # file vertex index -> Gmsh point tag
    next_point = [1]

    def new_point(xyz):
        t = next_point[0]
        next_point[0] += 1
        w("Point(%d) = {%s, %s, %s, lc};" % (t, fmt(xyz[0]), fmt(xyz[1]), fmt(xyz[2])))
        return t

    for i in sorted(used):
        point_tag[i] = new_point(vertices[i])

    # curves[(a, b)] with a < b: the list of signed curve tags running from a to b.
    curves = {}
    next_curve = [1]

    def new_curve(kind, tags):
        t = next_curve[0]
        next_curve[0] += 1
        w("%s(%d) = {%s};" % (kind, t, ", ".join(str(x) for x in tags)))
        return t

    def edge_curves(a, b):
        key = (min(a, b), max(a, b))
        if key not in curves:
            lo, hi = key
            arc = arcs.get(key)
            if arc is None:
                chain = [new_curve("Line", [point_tag[lo], point_tag[hi]])]
            else:
                # Pieces run from the arc's "from" to its "to"; reversed below if that is hi->lo.
                src, dst = arc["from"], arc["to"]
                A, B = vertices[src], vertices[dst]
                centre, radius, e1, e2, span = fit_circle(A, B, arc["via"])
                n = max(1, int(math.ceil(span / (math.pi * (1.0 - 1e-6)))))
                pts = [point_tag[src]]
                for k in range(1, n):
                    t = span * k / n
                    u = add(scale(math.cos(t), e1), scale(math.sin(t), e2))
                    p = add(centre, scale(radius, u))
                    pts.append(new_point(p))
                pts.append(point_tag[dst])
                c = new_point(centre)
                chain = [new_curve("Circle", [pts[k], c, pts[k + 1]]) for k in range(n)]
                if src != lo:
                    chain = [-t for t in reversed(chain)]
            curves[key] = chain
        chain = curves[key]
        return chain if a < b else [-t for t in reversed(chain)]

    next_loop = 1
    for pi, p in enumerate(patches):
        loop_tags = []
        for loop in p["loops"]:
            signed = []
            for k, a in enumerate(loop):
                signed.extend(edge_curves(a, loop[(k + 1) % len(loop)]))
            w("Curve Loop(%d) = {%s};" % (next_loop, ", ".join(str(x) for x in signed)))
            loop_tags.append(next_loop)
            next_loop += 1
        w("Plane Surface(%d) = {%s};" % (pi + 1, ", ".join(str(x) for x in loop_tags)))
    for pi, p in enumerate(patches):
        name = p.get("name", "patch%d" % pi).replace('"', "'")
        w('Physical Surface("%s", %d) = {%d};' % (name, pi + 1, pi + 1))
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("part")
    ap.add_argument("-o", "--output", required=True)
    ap.add_argument("--lc", type=float, default=None,
                    help="characteristic length (default: the part's mesh.size, "
                    "else 1/40 of its size)")
    args = ap.parse_args()
    try:
        with open(args.part) as f:
            part = json.load(f)
    except (OSError, ValueError) as e:
        print("brep_to_geo: cannot read %s: %s" % (args.part, e), file=sys.stderr)
        return 1
    lc = args.lc
    if lc is None:
        lc = (part.get("mesh") or {}).get("size")
    if lc is None:
        used = {v for p in part["patches"] for loop in p["loops"] for v in loop}
        lc = part_size(part["vertices"], used) / 40.0
    text = convert(part, lc, args.part)
    with open(args.output, "w") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
