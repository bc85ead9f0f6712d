#!/usr/bin/python3
"""Writes STL-like faceted closed shells for the benchmark and for stress runs: cylinders with
triangulated sides and caps fanned from the centre, from a rim vertex or left as one n-gon,
cones, UV spheres, tori of quads or triangles, cubes of triangles, icospheres with jittered
radii (46 parts, each at its default size).

Usage: bench/make_faceted.py OUTDIR   (prints the part names)
"""
import json, math, os, random, sys
TAU = 2 * math.pi
if len(sys.argv) != 2 or sys.argv[1].startswith("-"):
    sys.exit(__doc__.strip())
out = sys.argv[1]
def write(name, v, faces, size=None):
    d = {"laytracks": "brep/1", "units": "mm", "vertices": [list(map(float, p)) for p in v],
         "patches": [{"loops": [list(f)]} for f in faces]}
    if size: d["mesh"] = {"size": size}
    with open(os.path.join(out, name + ".json"), "w") as fh: json.dump(d, fh)
    print(name)
def cyl(n, r, h, side_tri=True, cap="fan", name=None):
    v = []; f = []
    for k in range(n):
        a = TAU * k / n; v.append((r*math.cos(a), r*math.sin(a), 0))
    for k in range(n):
        a = TAU * k / n; v.append((r*math.cos(a), r*math.sin(a), h))
    for k in range(n):
        a, b = k, (k+1) % n
        if side_tri:
            f.append((a, b, n+b)); f.append((a, n+b, n+a))
        else:
            f.append((a, b, n+b, n+a))
    if cap == "fan":
        c0 = len(v); v.append((0, 0, 0)); c1 = len(v); v.append((0, 0, h))
        for k in range(n):
            a, b = k, (k+1) % n
            f.append((c0, b, a)); f.append((c1, n+a, n+b))
    elif cap == "rimfan":  # STL style: fan from vertex 0, thin triangles
        for k in range(1, n-1):
            f.append((0, k+1, k)); f.append((n, n+k, n+k+1))
    else:
        f.append(tuple(reversed(range(n)))); f.append(tuple(range(n, 2*n)))
    write(name or "cyl_%d_%s_%s" % (n, "tri" if side_tri else "quad", cap), v, f)
def cone(n, r, h, name=None):
    v = [(r*math.cos(TAU*k/n), r*math.sin(TAU*k/n), 0) for k in range(n)]
    ap = len(v); v.append((0, 0, h)); c = len(v); v.append((0, 0, 0))
    f = []
    for k in range(n):
        a, b = k, (k+1) % n
        f.append((a, b, ap)); f.append((c, b, a))
    write(name or "cone_%d_%g" % (n, h), v, f)
def uvsphere(nu, nv, r, name=None):
    v = [(0, 0, r)]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = TAU * i / nu
            v.append((r*math.sin(th)*math.cos(ph), r*math.sin(th)*math.sin(ph), r*math.cos(th)))
    v.append((0, 0, -r)); S = len(v) - 1
    idx = lambda j, i: 1 + (j-1)*nu + (i % nu)
    f = []
    for i in range(nu): f.append((0, idx(1, i), idx(1, i+1)))
    for j in range(1, nv-1):
        for i in range(nu): f.append((idx(j, i), idx(j+1, i), idx(j+1, i+1), idx(j, i+1)))
    for i in range(nu): f.append((S, idx(nv-1, i+1), idx(nv-1, i)))
    write(name or "uvsphere_%d_%d" % (nu, nv), v, f)
def torus(nu, nv, R, r, tri=False, name=None):
    v = []
    for i in range(nu):
        u = TAU * i / nu
        for j in range(nv):
            w = TAU * j / nv
            v.append(((R + r*math.cos(w))*math.cos(u), (R + r*math.cos(w))*math.sin(u), r*math.sin(w)))
    idx = lambda i, j: (i % nu)*nv + (j % nv)
    f = []
    for i in range(nu):
        for j in range(nv):
            q = (idx(i, j), idx(i+1, j), idx(i+1, j+1), idx(i, j+1))
            if tri: f += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
            else: f.append(q)
    write(name or "torus_%d_%d%s" % (nu, nv, "_tri" if tri else ""), v, f)
def tricube(s, k, name=None):
    # cube, each face a k x k grid of squares split into two triangles
    v = []; key = {}
    def vid(p):
        p = tuple(round(c, 9) for c in p)
        if p not in key: key[p] = len(v); v.append(p)
        return key[p]
    f = []
    for ax in range(3):
        for sgn in (0, 1):
            for a in range(k):
                for b in range(k):
                    def P(i, j):
                        p = [0, 0, 0]; p[ax] = sgn*s; p[(ax+1) % 3] = s*i/k; p[(ax+2) % 3] = s*j/k
                        return vid(p)
                    q = [P(a, b), P(a+1, b), P(a+1, b+1), P(a, b+1)]
                    if sgn == 0: q = q[::-1]
                    f += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
    write(name or "tricube_%d" % k, v, f)
def jitter_ico(level, r, amp, seed):
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from make_icosphere import icosphere
    v, f = icosphere(level); rnd = random.Random(seed)
    v = [tuple(c * r * (1 + amp*(rnd.random()-0.5)) for c in p) for p in v]
    write("jico_%d_%g_%d" % (level, amp, seed), v, f)
os.makedirs(out, exist_ok=True)
for n in (6, 12, 24, 48, 96):
    for cap in ("fan", "rimfan", "ngon"):
        cyl(n, 10, 30, True, cap)
    cyl(n, 10, 30, False, "fan")
cyl(64, 10, 1, True, "rimfan", "disk_thin_64")
cyl(8, 10, 200, True, "fan", "cyl_long_8")
for n, h in ((8, 20), (32, 20), (32, 2), (64, 60)):
    cone(n, 10, h)
for nu, nv in ((8, 4), (16, 8), (32, 16), (48, 24)):
    uvsphere(nu, nv, 20)
for nu, nv in ((12, 8), (24, 12), (48, 16)):
    torus(nu, nv, 30, 8); torus(nu, nv, 30, 8, True)
for k in (1, 2, 4, 7):
    tricube(10, k)
for lv in (1, 2):
    for s in (1, 2, 3): jitter_ico(lv, 30, 0.15, s)
