#!/usr/bin/python3
"""Random shells of planar patches, as STL-like and sheet-metal parts come: convex hulls of
random points on an ellipsoid (irregular triangles, slivers among them), prisms over random
star-shaped outlines (sides as quads or triangle pairs; caps as one n-gon, fanned from the
centre or ear-clipped into needles), prisms with a hole through them (caps of two loops),
plates with leaning ribs standing on them (seams of three patches) and open strips folded
along lines at random angles. Each part gets a mesh.size of its diagonal / 12..50.

  shells.py DIR N SEED > LIST.tsv    N parts (the five families in turn) into DIR

LIST.tsv is what run-fuzz.py reads (path, family, seed, name, 0), so
`run-fuzz.py LIST.tsv RESULTS.jsonl` meshes each in three poses and lists every refusal and
every quad count that differs between poses. Not a test.
"""
import importlib.util, json, math, os, random, sys

# fuzz.py's 2D helpers (orient, seg_dist2); its generator runs only as a script.
_spec = importlib.util.spec_from_file_location(
    "fuzz", os.path.join(os.path.dirname(os.path.abspath(__file__)), "fuzz.py"))
fuzz = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fuzz)

def hull(pts):
    # incremental 3D convex hull; faces as ccw-from-outside index triples
    def sub(a, b): return (a[0]-b[0], a[1]-b[1], a[2]-b[2])
    def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
    def dot(a, b): return a[0]*b[0]+a[1]*b[1]+a[2]*b[2]
    def vol(f, p):
        a, b, c = pts[f[0]], pts[f[1]], pts[f[2]]
        return dot(cross(sub(b, a), sub(c, a)), sub(p, a))
    n = len(pts)
    faces = []
    # initial tetra
    i0, i1 = 0, 1
    i2 = next(i for i in range(2, n) if any(abs(x) > 1e-9 for x in cross(sub(pts[i1], pts[i0]), sub(pts[i], pts[i0]))))
    i3 = next(i for i in range(2, n) if i != i2 and abs(vol((i0, i1, i2), pts[i])) > 1e-9)
    base = [(i0, i1, i2), (i0, i2, i3), (i0, i3, i1), (i1, i3, i2)]
    cen = [sum(pts[i][k] for i in (i0, i1, i2, i3)) / 4 for k in range(3)]
    for f in base:
        if vol(f, cen) > 0: f = (f[0], f[2], f[1])
        faces.append(f)
    for p in range(n):
        if p in (i0, i1, i2, i3): continue
        vis = [f for f in faces if vol(f, pts[p]) > 1e-12]
        if not vis: continue
        edges = {}
        for f in vis:
            for k in range(3):
                e = (f[k], f[(k+1) % 3])
                edges[e] = edges.get(e, 0) + 1
        horizon = [e for e in edges if (e[1], e[0]) not in edges]
        vs = set(vis)
        faces = [f for f in faces if f not in vs]
        for a, b in horizon: faces.append((a, b, p))
    used = sorted({i for f in faces for i in f})
    re = {v: k for k, v in enumerate(used)}
    return [pts[i] for i in used], [tuple(re[i] for i in f) for f in faces]

def star(rnd, n, r, noise):
    angs = sorted(rnd.uniform(0, 2*math.pi) for _ in range(n))
    # keep angle gaps from collapsing
    out = []
    for a in angs:
        if out and a - out[-1][0] < 0.5 * 2*math.pi/n / 2: continue
        out.append((a, r * (1 + rnd.uniform(-noise, noise))))
    return [(rr*math.cos(a), rr*math.sin(a)) for a, rr in out]

def earclip(poly):
    idx = list(range(len(poly))); tris = []
    cr = fuzz.orient
    def inside(p, a, b, c): return cr(a, b, p) > 0 and cr(b, c, p) > 0 and cr(c, a, p) > 0
    guard = 0
    while len(idx) > 3 and guard < 100000:
        guard += 1
        m = len(idx)
        for k in range(m):
            a, b, c = idx[k-1], idx[k], idx[(k+1) % m]
            if cr(poly[a], poly[b], poly[c]) <= 1e-12: continue
            if any(inside(poly[j], poly[a], poly[b], poly[c]) for j in idx if j not in (a, b, c)): continue
            tris.append((a, b, c)); idx.pop(k); break
        else:
            return None
    tris.append(tuple(idx))
    return tris

def prism(rnd, hole=False):
    n = rnd.randint(5, 40)
    outer = star(rnd, n, 10.0, rnd.uniform(0.0, 0.5))
    n = len(outer)
    # the centre inside (every angular gap below 180 degrees): the fan cap and the hole need it
    if n < 3 or any(outer[k][0] * outer[(k + 1) % n][1] - outer[(k + 1) % n][0] * outer[k][1] <= 0
                    for k in range(n)):
        return None
    h = rnd.uniform(1.0, 25.0)
    v = [(x, y, 0.0) for x, y in outer] + [(x, y, h) for x, y in outer]
    f = []
    sidetri = rnd.random() < 0.5
    for k in range(n):
        a, b = k, (k+1) % n
        if sidetri: f += [[a, b, n+b], [a, n+b, n+a]]
        else: f.append([a, b, n+b, n+a])
    holes = None
    if hole:
        # the outline's nearest approach to the centre bounds the hole
        reach = min(abs(outer[k][0] * outer[(k + 1) % n][1] - outer[(k + 1) % n][0] * outer[k][1]) /
                    math.dist(outer[k], outer[(k + 1) % n]) for k in range(n))
        m = rnd.randint(3, 24)
        rin = reach / 1.2 * rnd.uniform(0.3, 0.8)
        inner = star(rnd, m, rin, 0.2)
        m = len(inner)
        if m < 3:
            return None
        base = len(v)
        v += [(x, y, 0.0) for x, y in inner] + [(x, y, h) for x, y in inner]
        for k in range(m):
            a, b = base+k, base+(k+1) % m
            f.append([b, a, a+m, b+m])  # facing the hole's axis
        # caps with a hole: n-gon loops; bottom faces down
        f.append({"loops": [list(reversed(range(n))), [base+k for k in range(m)]]})
        f.append({"loops": [list(range(n, 2*n)), [base+m+k for k in reversed(range(m))]]})
        return v, f, "hole_n%d_m%d_%s" % (n, m, "tri" if sidetri else "quad")
    cap = rnd.choice(["ngon", "fan", "ear"])
    if cap == "ngon":
        f.append(list(reversed(range(n)))); f.append(list(range(n, 2*n)))
    elif cap == "fan":
        c0 = len(v); v.append((0.0, 0.0, 0.0)); c1 = len(v); v.append((0.0, 0.0, h))
        for k in range(n):
            a, b = k, (k+1) % n
            f.append([c0, b, a]); f.append([c1, n+a, n+b])
    else:
        tris = earclip(outer)
        if tris is None: return None
        for a, b, c in tris:
            f.append([c, b, a]); f.append([n+a, n+b, n+c])
    return v, f, "prism_n%d_%s_%s" % (n, "tri" if sidetri else "quad", cap)

def ribs(rnd):
    # plate [0,W]x[0,D] split at x-lines; a rib stands on each line, leaning
    W, D = rnd.uniform(20, 60), rnd.uniform(10, 40)
    k = rnd.randint(1, 4)
    xs = sorted(rnd.uniform(0.15, 0.85) * W for _ in range(k))
    xs = [x for i, x in enumerate(xs) if i == 0 or x - xs[i-1] > 0.1 * W]
    cuts = [0.0] + xs + [W]
    v = []; f = []
    def vid(p):
        v.append(p); return len(v) - 1
    front = [vid((x, 0.0, 0.0)) for x in cuts]
    back = [vid((x, D, 0.0)) for x in cuts]
    for i in range(len(cuts) - 1):
        f.append([front[i], front[i+1], back[i+1], back[i]])
    for i, x in enumerate(xs):
        hgt = rnd.uniform(2, 15); lean = math.radians(rnd.uniform(-35, 35))
        dx, dz = hgt * math.sin(lean), hgt * math.cos(lean)
        a, b = front[i+1], back[i+1]
        c = vid((x + dx, D, dz)); d = vid((x + dx, 0.0, dz))
        f.append([a, b, c, d][::-1] if rnd.random() < 0.5 else [a, d, c, b])
    return v, f, "ribs_%d" % len(xs)

def folded(rnd):
    # an open strip folded along lines: a polyline profile in xz extruded along y
    m = rnd.randint(2, 7)
    D = rnd.uniform(5, 40)
    pts = [(0.0, 0.0)]; ang = 0.0
    for _ in range(m):
        ang += math.radians(rnd.choice([-1, 1]) * rnd.uniform(10, 120))
        L = rnd.uniform(3, 20)
        pts.append((pts[-1][0] + L*math.cos(ang), pts[-1][1] + L*math.sin(ang)))
    # reject self-approaching profiles (crude): segments not adjacent keep 2 apart
    for i in range(len(pts)):
        for j in range(len(pts) - 1):
            if abs(i - j) > 1 and i != j + 1 and fuzz.seg_dist2(pts[i], pts[j], pts[j+1]) < 4.0:
                return None
    v = [(x, 0.0, z) for x, z in pts] + [(x, D, z) for x, z in pts]
    n = len(pts)
    f = [[i, i+1, n+i+1, n+i] for i in range(n - 1)]
    return v, f, "folded_%d" % m

def hullpart(rnd):
    N = rnd.randint(8, 120)
    ax = [rnd.uniform(1, 6) for _ in range(3)]
    pts = []
    for _ in range(N):
        g = [rnd.gauss(0, 1) for _ in range(3)]; s = math.sqrt(sum(x*x for x in g))
        r = rnd.uniform(0.9, 1.0) if rnd.random() < 0.8 else rnd.uniform(0.0, 1.0)
        pts.append(tuple(5 * ax[k] * g[k] / s * r for k in range(3)))
    v, f = hull(pts)
    return v, [list(t) for t in f], "hull_%d" % len(v)

def main():
    if len(sys.argv) != 4 or sys.argv[1].startswith("-"):
        sys.exit(__doc__.strip())
    out, N, seed = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    os.makedirs(out, exist_ok=True)
    fams = [("hull", hullpart), ("prism", lambda r: prism(r)), ("hole", lambda r: prism(r, True)),
            ("ribs", ribs), ("folded", folded)]
    for i in range(N):
        fam, fn = fams[i % len(fams)]
        s = seed * 1000 + i
        rnd = random.Random(s)
        res = None
        while res is None:
            res = fn(rnd)
        v, f, name = res
        lo = [min(p[k] for p in v) for k in range(3)]; hi = [max(p[k] for p in v) for k in range(3)]
        diag = math.sqrt(sum((hi[k]-lo[k])**2 for k in range(3)))
        size = round(diag / rnd.uniform(12, 50), 6)
        d = {"laytracks": "brep/1", "units": "mm", "vertices": [list(map(float, p)) for p in v],
             "patches": [x if isinstance(x, dict) else {"loops": [x]} for x in f], "mesh": {"size": size}}
        path = os.path.join(out, "%s_%03d.json" % (fam, i))
        with open(path, "w") as fh: json.dump(d, fh)
        print("\t".join([path, fam, str(s), name, "0"]))

main()
