#!/usr/bin/env python3
"""Random parts that mix the features gen.py's families have one at a time, as moulded and
sheet-metal parts do: filleted outlines (convex and concave corners) with round holes and
slots at any angle, some close to an edge or to each other; folded brackets whose flanges
carry such holes; drafted trays with holes in the floor and windows in the walls; and
rectangles with rounded corners of any radius (the fans of large fillets).

  composite.py DIR [N] [SEED]   N parts per family (default 12) into DIR, names to stdout

run-stress.sh meshes 20 of each family beside gen.py's parts, in the same five poses.
"""
import importlib.util
import json
import math
import os
import random
import sys

spec = importlib.util.spec_from_file_location(
    "gen", os.path.join(os.path.dirname(os.path.abspath(__file__)), "gen.py"))
gen = importlib.util.module_from_spec(spec)
spec.loader.exec_module(gen)
Part = gen.Part


def unit(x, y):
    n = math.hypot(x, y)
    return x / n, y / n


def filleted_outline(P, pts, radii, to3d):
    """pts: CCW 2D polygon; radii[i]: fillet radius at corner i (0: sharp). Registers the arcs
    (one per fillet, or two when it turns more than 120 degrees) and returns the 3D loop."""
    n = len(pts)
    out = []
    for i in range(n):
        p, a, b = pts[i], pts[i - 1], pts[(i + 1) % n]
        r = radii[i]
        if r <= 0:
            out.append(to3d(p))
            continue
        u = unit(p[0] - a[0], p[1] - a[1])  # incoming direction
        v = unit(b[0] - p[0], b[1] - p[1])  # outgoing direction
        phi = math.acos(max(-1.0, min(1.0, -u[0] * v[0] - u[1] * v[1])))  # angle between -u and v
        d = r / math.tan(phi / 2)
        bis = unit(-u[0] + v[0], -u[1] + v[1])
        c = (p[0] + bis[0] * r / math.sin(phi / 2), p[1] + bis[1] * r / math.sin(phi / 2))
        t0 = (p[0] - u[0] * d, p[1] - u[1] * d)
        t1 = (p[0] + v[0] * d, p[1] + v[1] * d)
        a0 = math.atan2(t0[1] - c[1], t0[0] - c[0])
        a1 = math.atan2(t1[1] - c[1], t1[0] - c[0])
        sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi  # the short way: |sweep| = pi - phi
        pieces = 2 if abs(sweep) > math.radians(120) else 1
        ends = [(c[0] + r * math.cos(a0 + sweep * k / pieces), c[1] + r * math.sin(a0 + sweep * k / pieces))
                for k in range(pieces + 1)]
        for k in range(pieces):
            am = a0 + sweep * (k + 0.5) / pieces
            P.arc(to3d(ends[k]), to3d(ends[k + 1]), to3d((c[0] + r * math.cos(am), c[1] + r * math.sin(am))))
        out += [to3d(e) for e in ends]
    return out


def fillet_radii(rnd, pts, frac, share=0.7):
    """A random fillet radius per corner, small enough that neighbouring fillets do not meet."""
    n = len(pts)
    radii = []
    for i in range(n):
        p, a, b = pts[i], pts[i - 1], pts[(i + 1) % n]
        u = unit(p[0] - a[0], p[1] - a[1])
        v = unit(b[0] - p[0], b[1] - p[1])
        phi = math.acos(max(-1.0, min(1.0, -u[0] * v[0] - u[1] * v[1])))
        if phi > math.radians(150) or phi < math.radians(20) or rnd.random() > share:
            radii.append(0.0)
            continue
        room = 0.45 * min(math.dist(p, a), math.dist(p, b)) * math.tan(phi / 2)
        radii.append(min(room, frac * rnd.uniform(0.3, 1.0)))
    return radii


def hole_loop(P, kind, c, r, ang, to3d, length=0.0):
    """A hole (CW in the plane): a circle of 2-4 arcs, a polygon, or a slot at angle ang."""
    cx, cy = c
    if kind == "circle":
        n = 3 + int(ang * 10) % 3
        pts = [(cx + r * math.cos(ang - 2 * math.pi * i / n), cy + r * math.sin(ang - 2 * math.pi * i / n))
               for i in range(n)]
        for i in range(n):
            am = ang - 2 * math.pi * (i + 0.5) / n
            P.arc(to3d(pts[i]), to3d(pts[(i + 1) % n]), to3d((cx + r * math.cos(am), cy + r * math.sin(am))))
        return [to3d(p) for p in pts]
    if kind == "poly":
        n = 5 + int(ang * 10) % 6
        return [to3d((cx + r * math.cos(ang - 2 * math.pi * i / n), cy + r * math.sin(ang - 2 * math.pi * i / n)))
                for i in range(n)]
    # slot: two half circles joined by straight sides, axis at angle ang
    ax, ay = math.cos(ang), math.sin(ang)
    nx, ny = -ay, ax
    e0 = (cx - ax * length / 2, cy - ay * length / 2)
    e1 = (cx + ax * length / 2, cy + ay * length / 2)
    p1 = (e1[0] - nx * r, e1[1] - ny * r)
    p2 = (e1[0] + nx * r, e1[1] + ny * r)
    p3 = (e0[0] + nx * r, e0[1] + ny * r)
    p4 = (e0[0] - nx * r, e0[1] - ny * r)
    # CW: p4 -> p3 -> p2 -> p1 (the hole's loop turns against the outer one)
    loop = [p1, p4, p3, p2]
    P.arc(to3d(p4), to3d(p3), to3d((e0[0] - ax * r, e0[1] - ay * r)))
    P.arc(to3d(p2), to3d(p1), to3d((e1[0] + ax * r, e1[1] + ay * r)))
    return [to3d(p) for p in loop]


def clearance_outline(pts, radii):
    """A polygon inside the filleted outline: each convex filleted corner cut by the chord of
    its fillet (a concave fillet only adds material)."""
    out = []
    n = len(pts)
    for i in range(n):
        p, a, b = pts[i], pts[i - 1], pts[(i + 1) % n]
        u = unit(p[0] - a[0], p[1] - a[1])
        v = unit(b[0] - p[0], b[1] - p[1])
        if radii[i] <= 0 or u[0] * v[1] - u[1] * v[0] <= 0:
            out.append(p)
            continue
        phi = math.acos(max(-1.0, min(1.0, -u[0] * v[0] - u[1] * v[1])))
        d = radii[i] / math.tan(phi / 2)
        out += [(p[0] - u[0] * d, p[1] - u[1] * d), (p[0] + v[0] * d, p[1] + v[1] * d)]
    return out


def inside(pts, q):
    x, y = q
    c = False
    n = len(pts)
    for i in range(n):
        (x1, y1), (x2, y2) = pts[i], pts[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            c = not c
    return c


def seg_dist(p, a, b):
    ax, ay = b[0] - a[0], b[1] - a[1]
    t = max(0.0, min(1.0, ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay) / (ax * ax + ay * ay)))
    return math.dist(p, (a[0] + t * ax, a[1] + t * ay))


def place_holes(rnd, outline, count, rmin, rmax, gap_min, gap_max):
    """Holes as (kind, centre, reach, radius, angle, length), clear of the outline (a polygon
    that contains the fillets' arcs) and of each other by a random gap in [gap_min, gap_max]."""
    xs = [p[0] for p in outline]
    ys = [p[1] for p in outline]
    holes = []
    for _ in range(count * 40):
        if len(holes) == count:
            break
        kind = rnd.choice(["circle", "circle", "slot", "poly"])
        r = rnd.uniform(rmin, rmax)
        length = rnd.uniform(1.0, 4.0) * r if kind == "slot" else 0.0
        reach = r + length / 2
        c = (rnd.uniform(min(xs), max(xs)), rnd.uniform(min(ys), max(ys)))
        gap = rnd.uniform(gap_min, gap_max)
        if not inside(outline, c):
            continue
        n = len(outline)
        if min(seg_dist(c, outline[i], outline[(i + 1) % n]) for i in range(n)) < reach + gap:
            continue
        if any(math.dist(c, h[1]) < reach + h[2] + gap for h in holes):
            continue
        holes.append((kind, c, reach, r, rnd.uniform(0, math.pi), length))
    return holes


def random_outline(rnd, size):
    """A CCW polygon: a rectangle with notches cut into some sides, or a random star-shaped
    polygon of 5-9 corners."""
    if rnd.random() < 0.5:
        W, H = size, size * rnd.uniform(0.4, 1.0)
        pts = [(0, 0)]
        if rnd.random() < 0.6:  # a notch in the bottom side
            a = rnd.uniform(0.2, 0.5) * W
            b = a + rnd.uniform(0.15, 0.3) * W
            d = rnd.uniform(0.15, 0.35) * H
            pts += [(a, 0), (a, d), (b, d), (b, 0)]
        pts += [(W, 0), (W, H)]
        if rnd.random() < 0.6:  # a step in the top side
            a = rnd.uniform(0.3, 0.7) * W
            d = rnd.uniform(0.15, 0.35) * H
            pts += [(a, H), (a, H - d)]
            pts += [(0, H - d)]
        else:
            pts += [(0, H)]
        return pts
    n = rnd.randint(5, 9)
    angs = sorted(rnd.uniform(0, 2 * math.pi) for _ in range(n))
    # keep corners apart
    angs = [2 * math.pi * i / n + rnd.uniform(-0.25, 0.25) * 2 * math.pi / n for i in range(n)]
    return [(size / 2 * rnd.uniform(0.6, 1.0) * math.cos(a), size / 2 * rnd.uniform(0.6, 1.0) * math.sin(a))
            for a in angs]


def flat_part(rnd, seed):
    P = Part()
    size = rnd.choice([40.0, 100.0, 7.0])
    outline = random_outline(rnd, size)
    radii = fillet_radii(rnd, outline, size * rnd.uniform(0.03, 0.15))
    to3d = lambda p: (p[0], p[1], 0.0)
    holes = place_holes(rnd, clearance_outline(outline, radii), rnd.randint(0, 5), size * 0.03, size * 0.12,
                        size * rnd.choice([0.005, 0.02, 0.05]), size * 0.1)
    loops = [hole_loop(P, k, c, r, a, to3d, l) for k, c, _, r, a, l in holes]
    P.patch(filleted_outline(P, outline, radii, to3d), loops, name="plate")
    P.size = size / rnd.choice([20, 30, 45])
    return P


def bracket_part(rnd, seed):
    """A folded strip: flanges of random lengths at random bend angles, extruded by a depth;
    holes in some flanges; the free corners of the end flanges filleted."""
    P = Part()
    depth = rnd.uniform(10, 40)
    nfl = rnd.randint(2, 4)
    lengths = [rnd.uniform(10, 40) for _ in range(nfl)]
    turns = [rnd.choice([-1, 1]) * rnd.uniform(30, 135) for _ in range(nfl - 1)]
    # profile points in the xz plane
    pts = [(0.0, 0.0)]
    ang = 0.0
    for i, L in enumerate(lengths):
        pts.append((pts[-1][0] + L * math.cos(ang), pts[-1][1] + L * math.sin(ang)))
        if i < nfl - 1:
            ang += math.radians(turns[i])
    for i in range(nfl):
        a, b = pts[i], pts[i + 1]
        L = math.dist(a, b)
        ux, uz = (b[0] - a[0]) / L, (b[1] - a[1]) / L
        to3d = lambda p, a=a, ux=ux, uz=uz: (a[0] + ux * p[0], p[1], a[1] + uz * p[0])
        outline = [(0, 0), (L, 0), (L, depth), (0, depth)]
        radii = [0.0] * 4
        if i == 0 and rnd.random() < 0.7:
            radii[0] = radii[3] = min(L, depth) * rnd.uniform(0.1, 0.4)
        if i == nfl - 1 and rnd.random() < 0.7:
            radii[1] = radii[2] = min(L, depth) * rnd.uniform(0.1, 0.4)
        holes = place_holes(rnd, clearance_outline(outline, radii), rnd.randint(0, 3), 1.0, min(L, depth) * 0.2,
                            rnd.choice([0.3, 1.0, 2.0]), 4.0)
        loops = [hole_loop(P, k, c, r, an, to3d, l) for k, c, _, r, an, l in holes]
        P.patch(filleted_outline(P, outline, radii, to3d), loops, name="flange%d" % i)
    P.size = depth / rnd.choice([8, 12, 20])
    return P


def tray_part(rnd, seed):
    """An open tray with drafted walls, holes in the floor and a window in some walls."""
    P = Part()
    L, W, H = rnd.uniform(40, 120), rnd.uniform(30, 80), rnd.uniform(8, 30)
    draft = math.tan(math.radians(rnd.choice([0.0, 1.0, 3.0, 8.0])))
    e = H * draft
    b = [(0, 0, 0), (L, 0, 0), (L, W, 0), (0, W, 0)]
    t = [(-e, -e, H), (L + e, -e, H), (L + e, W + e, H), (-e, W + e, H)]
    floor2 = [(0, 0), (L, 0), (L, W), (0, W)]
    to3d = lambda p: (p[0], p[1], 0.0)
    holes = place_holes(rnd, floor2, rnd.randint(0, 6), 1.5, min(L, W) * 0.12,
                        rnd.choice([0.5, 2.0]), 6.0)
    loops = [hole_loop(P, k, c, r, a, to3d, l) for k, c, _, r, a, l in holes]
    # floor normal down (outer side), walls outward: loops as in gen.box
    P.patch([to3d(p) for p in floor2][::-1], [h[::-1] for h in loops], name="floor")
    for i in range(4):
        j = (i + 1) % 4
        quad = [b[i], b[j], t[j], t[i]]
        windows = []
        if rnd.random() < 0.4:
            # a rectangular window in the wall's own (s along the bottom, w up the wall) frame
            base = math.dist(b[i], b[j])
            s0, s1 = sorted(rnd.uniform(0.15, 0.85) * base for _ in range(2))
            w0, w1 = sorted(rnd.uniform(0.2, 0.8) for _ in range(2))
            if s1 - s0 > 0.1 * base and w1 - w0 > 0.15:
                def at(s, w):
                    lo = [b[i][k] + (b[j][k] - b[i][k]) * s / base for k in range(3)]
                    hi = [t[i][k] + (t[j][k] - t[i][k]) * (s + e) / (base + 2 * e) for k in range(3)]
                    return tuple(lo[k] + (hi[k] - lo[k]) * w for k in range(3))
                windows.append([at(s0, w0), at(s0, w1), at(s1, w1), at(s1, w0)])
        P.patch(quad, windows, name="wall%d" % i)
    P.size = min(L, W) / rnd.choice([10, 16, 25])
    return P


def rounded_rect_part(rnd, seed):
    """A W x H plate (h = 1) whose four corners are rounded with one radius r, from a twentieth
    to nearly half its width: the arcs' fans and the faces round their centres."""
    P = Part()
    W = rnd.uniform(10, 30)
    H = rnd.uniform(6, W)
    r = rnd.uniform(0.05, 0.49) * min(W, H)
    to3d = lambda p: (p[0], p[1], 0.0)
    outline = [(0, 0), (W, 0), (W, H), (0, H)]
    P.patch(filleted_outline(P, outline, [r] * 4, to3d), name="plate")
    P.size = 1.0
    return P


FAMILIES = {"cflat": flat_part, "cbracket": bracket_part, "ctray": tray_part, "rrect": rounded_rect_part}


def main():
    out = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 12
    seed0 = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    os.makedirs(out, exist_ok=True)
    for fam, make in FAMILIES.items():
        for k in range(n):
            seed = seed0 * 1000 + k
            P = make(random.Random(seed), seed)
            name = "%s__s%d" % (fam, seed)
            with open(os.path.join(out, name + ".json"), "w") as f:
                json.dump(P.json(), f, indent=1)
            print(name)


if __name__ == "__main__":
    main()
