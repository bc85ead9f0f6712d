#!/usr/bin/python3
"""Fuzzed parts for laytracks (B-Rep JSON brep/1), six families other than gen.py's:

  blob     smooth random outlines (a few harmonics) with runs of dense vertices (down to 1/200
           of the mean spacing) and radial noise, 0-5 holes; sizes from 2% to 30% of the radius
  rect     outlines traced round random sets of grid cells (notches, pinches mended), holes
  split    a blob or a strip cut into 2-6 coplanar patches (sectors or strips) sharing edges
  bent     a blob or grid outline folded along 1-3 lines into as many patches, in 3D
  arcs     rounded rectangles, stadiums, bulged and D shapes, with arc holes and slots; fillet
           radii from 0.5% of the element size to half the part
  extreme  slivers (aspect 50-500), thin-tipped stars, holes close to the outline, element
           sizes far above or below the part's features

Every part is checked (simple loops, holes inside and apart) before it is written, and skipped
after 40 failed draws. The seeds are deterministic: the same SEED gives the same parts.

usage: fuzz.py gen OUTDIR N_PER_FAMILY SEED [FAMILY,...]
  writes OUTDIR/<family>_<i>.json and prints one line per part to stdout:
  path, family, seed, a short name, the estimated quad count (area / size^2), tab-separated.
scripts/stress/run-fuzz.py meshes them in three poses.
"""
import json, math, os, random, sys

TAU = 2 * math.pi


class Bad(Exception):
    pass


# ------------------------------------------------------------------ flat 2D part with ids
class Flat:
    def __init__(self):
        self.v = []          # 2D points
        self.key = {}
        self.patches = []    # list of list of loops (ids)
        self.arcs = {}       # frozenset(a,b) -> (a, b, via2d)

    def vid(self, p):
        k = (round(p[0], 10), round(p[1], 10))
        if k in self.key:
            return self.key[k]
        self.key[k] = len(self.v)
        self.v.append((float(p[0]), float(p[1])))
        return self.key[k]

    def new(self, p):
        return self.vid(p)

    def loop(self, pts):
        return [self.vid(p) for p in pts]

    def arc(self, a, b, via):
        self.arcs[frozenset((a, b))] = (a, b, (float(via[0]), float(via[1])))


# ------------------------------------------------------------------ arc helpers
def arc_via(A, B, sweep_deg, side=1):
    """via point of the arc from A to B of given sweep (deg, 0<sweep<360); side=+1 bulges to
    the left of A->B, -1 to the right."""
    th = math.radians(sweep_deg)
    c = math.dist(A, B)
    r = c / (2 * math.sin(th / 2))
    s = r * (1 - math.cos(th / 2))
    M = ((A[0] + B[0]) / 2, (A[1] + B[1]) / 2)
    nx, ny = -(B[1] - A[1]) / c, (B[0] - A[0]) / c
    return (M[0] + side * s * nx, M[1] + side * s * ny)


def circ3(A, V, B):
    ax, ay = A; bx, by = V; cx, cy = B
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    if abs(d) < 1e-300:
        raise Bad("collinear arc")
    ux = ((ax * ax + ay * ay) * (by - cy) + (bx * bx + by * by) * (cy - ay) + (cx * cx + cy * cy) * (ay - by)) / d
    uy = ((ax * ax + ay * ay) * (cx - bx) + (bx * bx + by * by) * (ax - cx) + (cx * cx + cy * cy) * (bx - ax)) / d
    return (ux, uy)


def arc_points(A, V, B, step_deg=4.0):
    """polyline A..B through V (excluding A, including B)."""
    C = circ3(A, V, B)
    r = math.dist(C, A)
    a0 = math.atan2(A[1] - C[1], A[0] - C[0])
    av = math.atan2(V[1] - C[1], V[0] - C[0])
    a1 = math.atan2(B[1] - C[1], B[0] - C[0])
    # ccw sweep from a0 to a1 and to av
    sw1 = (a1 - a0) % TAU
    swv = (av - a0) % TAU
    if swv < sw1:
        sweep = sw1
    else:
        sweep = -(TAU - sw1)
    n = max(8, int(abs(math.degrees(sweep)) / step_deg) + 1)
    return [(C[0] + r * math.cos(a0 + sweep * i / n), C[1] + r * math.sin(a0 + sweep * i / n)) for i in range(1, n + 1)]


def loop_poly(F, lp):
    """discretised polyline of a loop (arcs expanded)."""
    out = []
    n = len(lp)
    for i in range(n):
        a, b = lp[i], lp[(i + 1) % n]
        out.append(F.v[a])
        k = frozenset((a, b))
        if k in F.arcs:
            out += arc_points(F.v[a], F.arcs[k][2], F.v[b])[:-1]
    return out


# ------------------------------------------------------------------ validation
def area(poly):
    s = 0.0
    for i in range(len(poly)):
        x0, y0 = poly[i]; x1, y1 = poly[(i + 1) % len(poly)]
        s += x0 * y1 - x1 * y0
    return s / 2


def orient(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def seg_dist2(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    L = dx * dx + dy * dy
    t = 0.0 if L == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L))
    x, y = a[0] + t * dx - p[0], a[1] + t * dy - p[1]
    return x * x + y * y


def segs_close(a, b, c, d, tol2):
    """segments ab, cd intersect or come within sqrt(tol2)."""
    o1, o2, o3, o4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
    if ((o1 > 0) != (o2 > 0)) and ((o3 > 0) != (o4 > 0)) and o1 != 0 and o2 != 0 and o3 != 0 and o4 != 0:
        return True
    return min(seg_dist2(a, c, d), seg_dist2(b, c, d), seg_dist2(c, a, b), seg_dist2(d, a, b)) <= tol2


def inside(p, poly):
    x, y = p
    c = False
    n = len(poly)
    for i in range(n):
        x0, y0 = poly[i]; x1, y1 = poly[(i + 1) % n]
        if (y0 > y) != (y1 > y):
            xi = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
            if xi > x:
                c = not c
    return c


def check_loops(polys, tol):
    """polys: list of discretised loops of one patch, first outer. Raises Bad."""
    segs = []
    for li, P in enumerate(polys):
        if len(P) < 3:
            raise Bad("loop too short")
        if abs(area(P)) <= tol * tol:
            raise Bad("zero area")
        n = len(P)
        for i in range(n):
            segs.append((li, i, n, P[i], P[(i + 1) % n]))
    xs = [p[0] for P in polys for p in P]; ys = [p[1] for P in polys for p in P]
    diag = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    cell = max(diag / max(1.0, math.sqrt(len(segs))) * 1.5, 1e-12)
    x0, y0 = min(xs), min(ys)
    grid = {}
    tol2 = tol * tol
    for si, (li, i, n, a, b) in enumerate(segs):
        gx0 = int((min(a[0], b[0]) - tol - x0) / cell); gx1 = int((max(a[0], b[0]) + tol - x0) / cell)
        gy0 = int((min(a[1], b[1]) - tol - y0) / cell); gy1 = int((max(a[1], b[1]) + tol - y0) / cell)
        if (gx1 - gx0 + 1) * (gy1 - gy0 + 1) > 200000:
            raise Bad("grid")
        cand = set()
        cells = [(gx, gy) for gx in range(gx0, gx1 + 1) for gy in range(gy0, gy1 + 1)]
        for c in cells:
            cand.update(grid.get(c, ()))
        for sj in cand:
            lj, j, m, c_, d_ = segs[sj]
            if lj == li and (j == (i + 1) % n or i == (j + 1) % n):
                # adjacent: check no fold-back (overlap)
                if lj == li and j == (i + 1) % n:
                    p, q, r = a, b, d_
                else:
                    p, q, r = c_, d_, b
                if seg_dist2(r, p, q) <= tol2 or seg_dist2(p, q, r) <= tol2:
                    raise Bad("fold back / duplicate")
                continue
            if segs_close(a, b, c_, d_, tol2):
                raise Bad("loops touch/intersect (loop %d seg %d, loop %d seg %d)" % (li, i, lj, j))
        for c in cells:
            grid.setdefault(c, []).append(si)
    outer = polys[0]
    for h in polys[1:]:
        if not inside(h[0], outer):
            raise Bad("hole outside")
    for i, h in enumerate(polys[1:]):
        for j, g in enumerate(polys[1:]):
            if i != j and inside(h[0], g):
                raise Bad("nested holes")


def min_dist_polys(P, Q):
    best = float("inf")
    for p in P:
        for i in range(len(Q)):
            best = min(best, seg_dist2(p, Q[i], Q[(i + 1) % len(Q)]))
    for q in Q:
        for i in range(len(P)):
            best = min(best, seg_dist2(q, P[i], P[(i + 1) % len(P)]))
    return math.sqrt(best)


def validate(F):
    allp = F.v
    xs = [p[0] for p in allp]; ys = [p[1] for p in allp]
    diag = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
    tol = 1e-9 * diag
    for pi, loops in enumerate(F.patches):
        for lp in loops:
            if len(set(lp)) != len(lp):
                raise Bad("repeated vertex in loop")
        check_loops([loop_poly(F, lp) for lp in loops], tol)
    # edge multiplicity: each edge in at most 2 patches (we don't make T-junctions)
    ecount = {}
    for loops in F.patches:
        for lp in loops:
            for i in range(len(lp)):
                e = frozenset((lp[i], lp[(i + 1) % len(lp)]))
                ecount[e] = ecount.get(e, 0) + 1
    for e, c in ecount.items():
        if c > 2:
            raise Bad("edge used >2")
    # vertex on other patch's unsplit edge
    if len(F.patches) > 1:
        pv = [set(i for lp in loops for i in lp) for loops in F.patches]
        for pi, loops in enumerate(F.patches):
            for lp in loops:
                for i in range(len(lp)):
                    a, b = lp[i], lp[(i + 1) % len(lp)]
                    A, B = F.v[a], F.v[b]
                    L2 = (A[0] - B[0]) ** 2 + (A[1] - B[1]) ** 2
                    for qi in range(len(F.patches)):
                        if qi == pi:
                            continue
                        for v in pv[qi]:
                            if v in (a, b):
                                continue
                            if seg_dist2(F.v[v], A, B) <= (1e-7 * diag) ** 2:
                                raise Bad("T vertex on unsplit edge")
    # arcs only on edges that exist
    used = set(ecount)
    for k in F.arcs:
        if k not in used:
            raise Bad("arc on missing edge")
    return diag


def flat_area(F):
    s = 0.0
    for loops in F.patches:
        s += abs(area(loop_poly(F, loops[0])))
        for h in loops[1:]:
            s -= abs(area(loop_poly(F, h)))
    return s


def to_json(F, size, lift=None, patch_lift=None):
    """lift: vertex id -> 3D; patch_lift(pi, p2) -> 3D for arc vias."""
    if lift is None:
        V = [[p[0], p[1], 0.0] for p in F.v]
    else:
        V = [list(lift(i)) for i in range(len(F.v))]
    arcs = []
    for k, (a, b, via) in F.arcs.items():
        arcs.append({"from": a, "to": b, "via": [via[0], via[1], 0.0] if lift is None else list(patch_lift(a, via))})
    d = {"laytracks": "brep/1", "units": "mm", "vertices": V,
         "patches": [{"name": "p%d" % i, "loops": loops} for i, loops in enumerate(F.patches)]}
    if arcs:
        d["arcs"] = arcs
    d["mesh"] = {"size": size}
    return d


# ------------------------------------------------------------------ shape primitives
def blob_outline(rnd, R, n, dense=True, noise=None):
    nh = rnd.randint(1, 6)
    harm = []
    tot = 0
    for k in range(2, 2 + nh):
        a = rnd.uniform(0, 0.35 / (k - 1) ** 0.7)
        harm.append((k, a, rnd.uniform(0, TAU)))
        tot += a
    sc = min(1.0, 0.6 / max(tot, 1e-9))
    harm = [(k, a * sc, p) for k, a, p in harm]
    noise = rnd.uniform(0.0, 0.03) if noise is None else noise
    w = [rnd.expovariate(1.0) + 0.05 for _ in range(n)]
    if dense:
        for _ in range(rnd.randint(0, 6)):
            s = rnd.randrange(n); L = rnd.randint(3, max(3, n // 5))
            f = rnd.uniform(0.005, 0.08)
            for j in range(L):
                w[(s + j) % n] *= f
    tw = sum(w)
    th0 = rnd.uniform(0, TAU)
    thetas = []
    acc = 0.0
    for x in w:
        thetas.append(th0 + TAU * acc / tw)
        acc += x
    pts = []
    for t in thetas:
        r = 1 + sum(a * math.cos(k * t + p) for k, a, p in harm) + rnd.uniform(-noise, noise)
        pts.append((R * r * math.cos(t), R * r * math.sin(t)))
    return pts, thetas


def rand_poly(rnd, cx, cy, r, n, irregular=0.3):
    a0 = rnd.uniform(0, TAU)
    angs = sorted(a0 + TAU * (i + rnd.uniform(-irregular, irregular) * 0.5) / n for i in range(n))
    return [(cx + r * rnd.uniform(1 - irregular, 1) * math.cos(a), cy + r * rnd.uniform(1 - irregular, 1) * math.sin(a)) for a in angs]


def place_holes(rnd, outer_poly, others, nholes, rmin, rmax, clearance, make=None, tries=300):
    """returns list of hole polys (2D point lists) placed inside outer_poly."""
    xs = [p[0] for p in outer_poly]; ys = [p[1] for p in outer_poly]
    holes = []
    for _ in range(nholes):
        for t in range(tries):
            r = rnd.uniform(rmin, rmax)
            c = (rnd.uniform(min(xs), max(xs)), rnd.uniform(min(ys), max(ys)))
            if not inside(c, outer_poly):
                continue
            h = make(c, r) if make else rand_poly(rnd, c[0], c[1], r, rnd.randint(3, 12))
            hp = h if make is None else h
            if not all(inside(p, outer_poly) for p in hp):
                continue
            if min_dist_polys(hp, outer_poly) < clearance:
                continue
            if any(min_dist_polys(hp, g) < clearance for g in holes + others):
                continue
            holes.append(h)
            break
    return holes


# ------------------------------------------------------------------ family 1: blobs
def fam_blob(rnd):
    R = rnd.uniform(3, 200)
    n = rnd.randint(40, 600)
    pts, _ = blob_outline(rnd, R, n)
    h = R * rnd.uniform(0.02, 0.3)
    F = Flat()
    outer = F.loop(pts)
    nh = rnd.randint(0, 5)
    holes = place_holes(rnd, pts, [], nh, 0.3 * h, max(0.5 * h, 0.12 * R), clearance=max(h, 0.05 * R))
    F.patches.append([outer] + [F.loop(hh[::rnd.choice([1, -1])]) for hh in holes])
    return F, h, "n%d_h%d" % (n, len(holes))


# ------------------------------------------------------------------ family 2: rectilinear
def fix_pinches(cells):
    changed = True
    while changed:
        changed = False
        xs = [c[0] for c in cells]; ys = [c[1] for c in cells]
        for i in range(min(xs) - 1, max(xs) + 1):
            for j in range(min(ys) - 1, max(ys) + 1):
                a, b, c, d = (i, j) in cells, (i + 1, j) in cells, (i, j + 1) in cells, (i + 1, j + 1) in cells
                if (a and d and not b and not c) or (b and c and not a and not d):
                    cells.add((i + 1, j) if not b else (i, j))
                    changed = True
    return cells


def largest_comp(cells):
    seen = set(); best = set()
    for c in cells:
        if c in seen:
            continue
        comp = set([c]); st = [c]; seen.add(c)
        while st:
            x, y = st.pop()
            for q in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)):
                if q in cells and q not in seen:
                    seen.add(q); comp.add(q); st.append(q)
        if len(comp) > len(best):
            best = comp
    return best


def trace_cells(cells, keep_collinear=False):
    nxt = {}
    for (i, j) in cells:
        if (i, j - 1) not in cells: nxt[(i, j)] = (i + 1, j)
        if (i + 1, j) not in cells: nxt[(i + 1, j)] = (i + 1, j + 1)
        if (i, j + 1) not in cells: nxt[(i + 1, j + 1)] = (i, j + 1)
        if (i - 1, j) not in cells: nxt[(i, j + 1)] = (i, j)
    loops = []
    used = set()
    for s in list(nxt):
        if s in used:
            continue
        lp = [s]; used.add(s); p = nxt[s]
        while p != s:
            if p in used:
                raise Bad("pinch in trace")
            lp.append(p); used.add(p); p = nxt[p]
        if not keep_collinear:
            out = []
            for k in range(len(lp)):
                a, b, c = lp[k - 1], lp[k], lp[(k + 1) % len(lp)]
                if orient(a, b, c) != 0:
                    out.append(b)
            lp = out
        loops.append(lp)
    loops.sort(key=lambda L: -area(L))
    return loops


def rect_cells(rnd):
    kind = rnd.choice(["grow", "perc", "maze", "comb", "LTU", "steps", "ring"])
    cells = set()
    if kind == "grow":
        cells.add((0, 0)); fr = [(0, 0)]
        N = rnd.randint(5, 200)
        while len(cells) < N:
            x, y = rnd.choice(list(cells)) if rnd.random() < 0.5 else fr[-1]
            q = rnd.choice(((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)))
            cells.add(q); fr.append(q)
    elif kind == "perc":
        W, H = rnd.randint(4, 25), rnd.randint(4, 25); p = rnd.uniform(0.55, 0.8)
        cells = set((i, j) for i in range(W) for j in range(H) if rnd.random() < p)
    elif kind == "maze":
        a, b = rnd.randint(2, 12), rnd.randint(2, 12)
        seen = {(0, 0)}; st = [(0, 0)]; cells.add((0, 0))
        while st:
            x, y = st[-1]
            nb = [(x + dx, y + dy) for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)) if 0 <= x + dx < a and 0 <= y + dy < b and (x + dx, y + dy) not in seen]
            if not nb:
                st.pop(); continue
            q = rnd.choice(nb); seen.add(q); st.append(q)
            cells.add((2 * q[0], 2 * q[1])); cells.add((x + q[0], y + q[1]))
        for _ in range(rnd.randint(0, 4)):  # extra openings -> holes
            x, y = rnd.randrange(a), rnd.randrange(b)
            if x + 1 < a: cells.add((2 * x + 1, 2 * y))
        cells = set((2 * x, 2 * y) for x, y in cells) if False else cells
    elif kind == "comb":
        nt = rnd.randint(2, 15); base = rnd.randint(1, 3); x = 0
        for t in range(nt):
            w = rnd.randint(1, 2); g = rnd.randint(1, 3); L = rnd.randint(1, 12)
            for i in range(x, x + w):
                for j in range(base, base + L): cells.add((i, j))
            x += w + (g if t < nt - 1 else 0)
        for i in range(x):
            for j in range(base): cells.add((i, j))
        if rnd.random() < 0.3:  # double comb
            for (i, j) in list(cells):
                if j >= base: cells.add((i, -1 - (j - base) - 0))
    elif kind == "LTU":
        s = rnd.choice("LTU"); a = rnd.randint(1, 4); L1 = rnd.randint(3, 25); L2 = rnd.randint(3, 25)
        if s == "L":
            cells = set((i, j) for i in range(L1) for j in range(a)) | set((i, j) for i in range(a) for j in range(L2))
        elif s == "T":
            cells = set((i, j) for i in range(L1) for j in range(L2 - a, L2)) | set((i, j) for i in range(L1 // 2, L1 // 2 + a) for j in range(L2))
        else:
            cells = set((i, j) for i in range(L1) for j in range(a)) | set((i, j) for i in range(a) for j in range(L2)) | set((i, j) for i in range(L1 - a, L1) for j in range(L2))
    elif kind == "steps":
        n = rnd.randint(2, 15); x = 0; y = 0
        for k in range(n):
            w = rnd.randint(1, 4); h = rnd.randint(1, 4)
            for i in range(x, x + w):
                for j in range(0, y + h): cells.add((i, j))
            x += w; y += h * rnd.choice([1, 1, -1]) if y > 4 else h
    else:  # ring / frame with bars -> holes
        W, H = rnd.randint(5, 30), rnd.randint(5, 30)
        cells = set((i, j) for i in range(W) for j in range(H) if i in (0, W - 1) or j in (0, H - 1))
        for _ in range(rnd.randint(0, 4)):
            if rnd.random() < 0.5:
                i = rnd.randrange(W); cells |= set((i, j) for j in range(H))
            else:
                j = rnd.randrange(H); cells |= set((i, j) for i in range(W))
    cells = fix_pinches(set(cells))
    cells = largest_comp(cells)
    return cells, kind


def rect_flat(rnd, with_holes=True):
    cells, kind = rect_cells(rnd)
    loops = trace_cells(cells, keep_collinear=rnd.random() < 0.2)
    c = rnd.uniform(0.2, 5)
    loops = [[(x * c, y * c) for x, y in lp] for lp in loops]
    if not with_holes:
        loops = loops[:1]
    return loops, c, kind


def fam_rect(rnd):
    loops, c, kind = rect_flat(rnd)
    h = c * rnd.uniform(0.3, 2.0)
    F = Flat()
    F.patches.append([F.loop(lp) for lp in loops])
    return F, h, "%s_n%d_h%d" % (kind, sum(len(l) for l in loops), len(loops) - 1)


# ------------------------------------------------------------------ family 3: coplanar split
def fam_split(rnd):
    F = Flat()
    k = rnd.randint(2, 6)
    variant = rnd.choice(["sectors", "strips"])
    if variant == "sectors":
        R = rnd.uniform(5, 100)
        n = rnd.randint(40, 300)
        pts, thetas = blob_outline(rnd, R, n, noise=0.005)
        ids = F.loop(pts)
        base = rnd.uniform(0, TAU)
        want = [(base + TAU * (i + rnd.uniform(-0.25, 0.25)) / k) for i in range(k)]
        idx = sorted(set(min(range(n), key=lambda j: abs(((thetas[j] - w + math.pi) % TAU) - math.pi)) for w in want))
        if len(idx) != k:
            raise Bad("dup idx")
        if any((idx[(i + 1) % k] - idx[i]) % n < 3 for i in range(k)):
            raise Bad("sectors too close")
        gaps = [((thetas[idx[(i + 1) % k]] - thetas[idx[i]]) % TAU) for i in range(k)]
        if max(gaps) > math.pi * 0.95:
            raise Bad("sector > 180")  # center must see everything
        center = F.new((0.0, 0.0))
        rays = []
        for i, j in enumerate(idx):
            m = rnd.randint(0, 8)
            th = thetas[j]
            wig = 0.3 * min(gaps[i], gaps[i - 1])
            ts = sorted(rnd.uniform(0.05, 0.95) for _ in range(m))
            ray = [center]
            for t in ts:
                phi = th + rnd.uniform(-wig, wig) * (1 - t)
                rr = math.hypot(*pts[j])
                # radius along phi: interpolate r(theta) ~ rr (approx); keep safely inside
                ray.append(F.new((t * 0.9 * rr * math.cos(phi), t * 0.9 * rr * math.sin(phi))))
            ray.append(ids[j])
            rays.append(ray)
        for i in range(k):
            a, b = idx[i], idx[(i + 1) % k]
            bnd = [ids[(a + s) % n] for s in range(1, (b - a) % n)]
            lp = rays[i] + bnd + rays[(i + 1) % k][::-1][:-1]
            F.patches.append([lp])
        diag = 2 * R
    else:
        W, H = rnd.uniform(5, 200), rnd.uniform(5, 200)
        xs = [0.0] + sorted(rnd.uniform(0.1, 0.9) * W for _ in range(k - 1)) + [W]
        if min(xs[i + 1] - xs[i] for i in range(k)) < 0.05 * W:
            raise Bad("strips too close")
        lines = []
        for i in range(k + 1):
            if i in (0, k):
                ys = [0.0, H]
                lines.append([F.new((xs[i], y)) for y in ys])
                continue
            m = rnd.randint(0, 12)
            ys = [0.0] + sorted(rnd.uniform(0, H) for _ in range(m)) + [H]
            wig = 0.4 * min(xs[i] - xs[i - 1], xs[i + 1] - xs[i])
            lines.append([F.new((xs[i] + (rnd.uniform(-wig, wig) if 0 < q < len(ys) - 1 else 0), y)) for q, y in enumerate(ys)])
        for i in range(k):
            L, Rl = lines[i], lines[i + 1]
            lp = [L[0]] + Rl + L[::-1][:-1]
            lp = [L[0], Rl[0]] + Rl[1:] + L[::-1][:-1]
            # simplify: bottom L0->R0, up R, top R_end->L_end, down L
            lp = [L[0]] + Rl + L[:0:-1]
            if rnd.random() < 0.4 and len(L) > 2 and len(Rl) > 2:
                # split this strip by a cross polyline between an interior vertex of L and of R
                a = rnd.randrange(1, len(L) - 1); b = rnd.randrange(1, len(Rl) - 1)
                pa, pb = F.v[L[a]], F.v[Rl[b]]
                mid = [F.new((pa[0] + (pb[0] - pa[0]) * t, pa[1] + (pb[1] - pa[1]) * t + rnd.uniform(-0.05, 0.05) * H))
                       for t in sorted(rnd.uniform(0.1, 0.9) for _ in range(rnd.randint(0, 4)))]
                low = [L[0]] + Rl[:b + 1] + mid[::-1] + L[a:0:-1]
                high = [L[a]] + mid + Rl[b:] + L[:a:-1]
                F.patches.append([low]); F.patches.append([high])
            else:
                F.patches.append([lp])
        diag = math.hypot(W, H)
    h = diag * rnd.uniform(0.01, 0.12)
    # holes in some patches
    for loops in F.patches:
        if rnd.random() < 0.3:
            op = loop_poly(F, loops[0])
            hs = place_holes(rnd, op, [], rnd.randint(1, 2), 0.3 * h, 1.0 * h, clearance=h, tries=60)
            for hh in hs:
                loops.append(F.loop(hh))
    if rnd.random() < 0.5:  # reverse all loops (consistent orientation either way)
        F.patches = [[lp[::-1] for lp in loops] for loops in F.patches]
    return F, h, "%s_k%d_np%d" % (variant, k, len(F.patches))


# ------------------------------------------------------------------ family 4: bent sheets
def fam_bent(rnd):
    if rnd.random() < 0.5:
        R = rnd.uniform(5, 100)
        pts, _ = blob_outline(rnd, R, rnd.randint(40, 300))
        h = R * rnd.uniform(0.03, 0.2)
        holes = place_holes(rnd, pts, [], rnd.randint(0, 4), 0.3 * h, max(0.5 * h, 0.1 * R), clearance=h)
        src = "blob"
    else:
        loops, c, kind = rect_flat(rnd)
        pts, holes = loops[0], loops[1:]
        h = c * rnd.uniform(0.3, 2.0)
        src = "rect-" + kind
    # random 2D rotation
    a = rnd.uniform(0, TAU); ca, sa = math.cos(a), math.sin(a)
    rot = lambda P: [(x * ca - y * sa, x * sa + y * ca) for x, y in P]
    pts = rot(pts); holes = [rot(hh) for hh in holes]
    xs = [p[0] for p in pts]; ys = [p[1] for p in pts]
    xmin, xmax, ymin, ymax = min(xs), max(xs), min(ys), max(ys)
    yc = (ymin + ymax) / 2; Hh = ymax - ymin
    nf = rnd.randint(1, 3)
    for attempt in range(60):
        cs = sorted(rnd.uniform(xmin + 0.1 * (xmax - xmin), xmax - 0.1 * (xmax - xmin)) for _ in range(nf))
        ss = [rnd.uniform(-0.3, 0.3) if rnd.random() < 0.5 else 0.0 for _ in range(nf)]
        ok = True
        for i in range(nf - 1):
            if cs[i + 1] - cs[i] < 0.05 * (xmax - xmin):
                ok = False
            if ss[i] != ss[i + 1] and abs((cs[i + 1] - cs[i]) / (ss[i] - ss[i + 1])) < Hh:
                ok = False
        if not ok:
            continue
        fs = [lambda p, c=c, s=s: p[0] - c - s * (p[1] - yc) for c, s in zip(cs, ss)]
        for f in fs:
            vals = [f(p) for p in pts]
            if min(abs(v) for v in vals) < 1e-6 * (xmax - xmin):
                ok = False; break
            ncross = sum(1 for i in range(len(pts)) if (vals[i] > 0) != (vals[i - 1] > 0))
            if ncross != 2:
                ok = False; break
            for hh in holes:
                hv = [f(p) for p in hh]
                if min(hv) < 0.3 * h and max(hv) > -0.3 * h:
                    ok = False; break
            if not ok:
                break
        if ok:
            break
    else:
        raise Bad("no fold lines")
    F = Flat()
    cur = F.loop(pts)
    pieces = []
    for f in fs:
        vals = [f(F.v[i]) for i in cur]
        n = len(cur)
        # find sign changes
        ch = [i for i in range(n) if (vals[i] > 0) != (vals[i - 1] > 0)]
        assert len(ch) == 2
        ins = {}
        for i in ch:
            a_, b_ = cur[i - 1], cur[i]
            A, B = F.v[a_], F.v[b_]; fa, fb = vals[i - 1], vals[i]
            t = fa / (fa - fb)
            ins[i] = F.new((A[0] + t * (B[0] - A[0]), A[1] + t * (B[1] - A[1])))
        # rebuild loop with inserted points, then split
        L = []
        for i in range(n):
            if i in ins:
                L.append(ins[i])
            L.append(cur[i])
        m = len(L)
        iA, iB = L.index(ins[ch[0]]), L.index(ins[ch[1]])
        seg1 = [L[(iA + s) % m] for s in range(((iB - iA) % m) + 1)]
        seg2 = [L[(iB + s) % m] for s in range(((iA - iB) % m) + 1)]
        f1 = f(F.v[seg1[1]])
        left, right = (seg1, seg2) if f1 < 0 else (seg2, seg1)
        pieces.append(left)
        cur = right
    pieces.append(cur)
    for p in pieces:
        F.patches.append([p])
    for hh in holes:
        hp = hh
        for pi, p in enumerate(pieces):
            if inside(hp[0], [F.v[i] for i in p]):
                F.patches[pi].append(F.loop(hp[::rnd.choice([1, -1])]))
                break
    # fold
    for _ in range(100):
        angs = [math.radians(rnd.uniform(10, 170)) * rnd.choice([1, -1]) for _ in fs]
        ps = [abs(sum(angs[:i + 1])) for i in range(len(angs))]
        if max(ps) < math.radians(170):
            break
    else:
        raise Bad("fold angles")
    sc = math.hypot(xmax - xmin, Hh)

    def rotate_about(p, c, s, ang):
        # axis through (c, yc, 0) direction (s,1,0)
        o = (c, yc, 0.0); d = (s, 1.0, 0.0); dn = math.sqrt(s * s + 1); d = (s / dn, 1 / dn, 0.0)
        v = (p[0] - o[0], p[1] - o[1], p[2] - o[2])
        ct, st = math.cos(ang), math.sin(ang)
        dot = sum(v[i] * d[i] for i in range(3))
        cr = (d[1] * v[2] - d[2] * v[1], d[2] * v[0] - d[0] * v[2], d[0] * v[1] - d[1] * v[0])
        return tuple(o[i] + v[i] * ct + cr[i] * st + d[i] * dot * (1 - ct) for i in range(3))

    def lift_pt(p2, strip):
        p = (p2[0], p2[1], 0.0)
        for k in range(strip - 1, -1, -1):
            p = rotate_about(p, cs[k], ss[k], angs[k])
        return p

    def strip_of(p2):
        return sum(1 for f in fs if f(p2) > 1e-9 * sc)

    F._lift = lambda i: lift_pt(F.v[i], strip_of(F.v[i]))
    F._plift = lambda a, via: lift_pt(via, strip_of(via))
    return F, h, "%s_f%d_a%s" % (src, nf, "-".join("%d" % round(math.degrees(x)) for x in angs))


# ------------------------------------------------------------------ family 5: arcs
def rounded_rect_loop(F, rnd, x0, y0, W, H, radii, nsub=1, ccw=True):
    corners = [(x0 + W, y0, -90), (x0 + W, y0 + H, 0), (x0, y0 + H, 90), (x0, y0, 180)]
    ctr = [(x0 + W - radii[0], y0 + radii[0]), (x0 + W - radii[1], y0 + H - radii[1]), (x0 + radii[2], y0 + H - radii[2]), (x0 + radii[3], y0 + radii[3])]
    a0s = [-90, 0, 90, 180]
    ids = []
    for k in range(4):
        r = radii[k]; cx, cy = ctr[k]; a0 = a0s[k]
        if r <= 0:
            ids.append(F.new((corners[k][0], corners[k][1]))); continue
        P = [(cx + r * math.cos(math.radians(a0 + 90 * t / nsub)), cy + r * math.sin(math.radians(a0 + 90 * t / nsub))) for t in range(nsub + 1)]
        pid = [F.new(p) for p in P]
        for t in range(nsub):
            am = math.radians(a0 + 90 * (t + 0.5) / nsub)
            F.arc(pid[t], pid[t + 1], (cx + r * math.cos(am), cy + r * math.sin(am)))
        ids += pid
    return ids if ccw else ids[::-1]


def arc_circle(F, cx, cy, r, sweeps):
    """circle from arcs with the given sweeps (deg, sum 360)."""
    a = 0.0
    a0 = random.random() * TAU
    angs = []
    for s in sweeps:
        angs.append(a0 + a); a += math.radians(s)
    ids = [F.new((cx + r * math.cos(t), cy + r * math.sin(t))) for t in angs]
    for i in range(len(ids)):
        t0 = angs[i]; t1 = angs[i] + math.radians(sweeps[i]); tm = (t0 + t1) / 2
        F.arc(ids[i], ids[(i + 1) % len(ids)], (cx + r * math.cos(tm), cy + r * math.sin(tm)))
    return ids


def slot_loop(F, cx, cy, r, L, ang):
    ca, sa = math.cos(ang), math.sin(ang)
    T = lambda u, v: (cx + u * ca - v * sa, cy + u * sa + v * ca)
    p1, p2, p3, p4 = T(L / 2, -r), T(L / 2, r), T(-L / 2, r), T(-L / 2, -r)
    i1, i2, i3, i4 = F.new(p1), F.new(p2), F.new(p3), F.new(p4)
    F.arc(i1, i2, T(L / 2 + r, 0)); F.arc(i3, i4, T(-L / 2 - r, 0))
    return [i1, i2, i3, i4]


def random_sweeps(rnd):
    k = rnd.choice([3, 3, 3, 4, 5, 6, 8])
    if rnd.random() < 0.4:  # nearly-180 arcs
        big = rnd.uniform(170, 179.9)
        rest = 360 - 2 * big
        return [big, big] + [rest / (k - 2)] * (k - 2) if k > 2 else [big, big, rest]
    w = [rnd.uniform(0.2, 1) for _ in range(k)]
    return [360 * x / sum(w) for x in w]


def fam_arcs(rnd):
    F = Flat()
    kind = rnd.choice(["rrect", "rrect", "stadium", "bulged", "dshape"])
    S = rnd.uniform(5, 200)
    h = S * rnd.uniform(0.01, 0.1)
    if kind == "rrect":
        W, H = S, S * rnd.uniform(0.2, 1.0)
        rads = []
        for _ in range(4):
            t = rnd.random()
            rads.append(0.0 if t < 0.1 else rnd.uniform(0.005, 0.3) * h if t < 0.45 else rnd.uniform(0.1, 0.5) * min(W, H))
        rads[1] = min(rads[1], 0.98 * H - rads[0], 0.98 * W - rads[2]) if rads[1] > 0 else 0
        rads[3] = min(rads[3], 0.98 * H - rads[2], 0.98 * W - rads[0]) if rads[3] > 0 else 0
        rads = [max(r, 0) for r in rads]
        outer = rounded_rect_loop(F, rnd, 0, 0, W, H, rads, nsub=rnd.choice([1, 1, 2, 3]))
    elif kind == "stadium":
        r = S * rnd.uniform(0.1, 0.5)
        outer = slot_loop(F, 0, 0, r, S, rnd.uniform(0, TAU))
    elif kind == "bulged":
        n = rnd.randint(3, 12)
        pts = rand_poly(rnd, 0, 0, S / 2, n, 0.2)
        outer = F.loop(pts)
        for i in range(n):
            a, b = outer[i], outer[(i + 1) % n]
            t = rnd.random()
            sw = rnd.uniform(0.001, 0.5) if t < 0.4 else rnd.uniform(0.5, 30) if t < 0.8 else rnd.uniform(30, 120)
            side = rnd.choice([1, -1]) if sw < 40 else -1   # CCW polygon: -1 bulges outward (right of A->B)
            F.arc(a, b, arc_via(F.v[a], F.v[b], sw, side))
    else:  # D shape: chord + arc of sweep 170-350
        r = S / 2
        sw = rnd.choice([rnd.uniform(170, 179.9), rnd.uniform(180.1, 190), rnd.uniform(190, 340)])
        t0 = rnd.uniform(0, TAU)
        A = (r * math.cos(t0), r * math.sin(t0)); B = (r * math.cos(t0 + math.radians(sw)), r * math.sin(t0 + math.radians(sw)))
        tm = t0 + math.radians(sw) / 2
        ia, ib = F.new(A), F.new(B)
        # optional extra vertex on the chord
        outer = [ia, ib]
        if rnd.random() < 0.5:
            outer = [ia, ib, F.new(((A[0] + B[0]) / 2, (A[1] + B[1]) / 2))]
        F.arc(ia, ib, (r * math.cos(tm), r * math.sin(tm)))
        kind += "%d" % sw
    op = loop_poly(F, outer)
    holes = []
    hpolys = []
    for _ in range(rnd.randint(0, 4)):
        hk = rnd.choice(["circle", "slot", "rrect"])
        for t in range(100):
            xs = [p[0] for p in op]; ys = [p[1] for p in op]
            c = (rnd.uniform(min(xs), max(xs)), rnd.uniform(min(ys), max(ys)))
            rr = rnd.uniform(0.05, 0.2) * S
            G = Flat(); G.v = list(F.v); G.key = dict(F.key); G.arcs = dict(F.arcs)
            if hk == "circle":
                lp = arc_circle(G, c[0], c[1], rr, random_sweeps(rnd))
            elif hk == "slot":
                lp = slot_loop(G, c[0], c[1], rr * 0.4, rr * rnd.uniform(0.5, 2), rnd.uniform(0, TAU))
            else:
                w, hh = rr * 1.5, rr * rnd.uniform(0.4, 1.5)
                rs = [rnd.uniform(0, 0.5) * min(w, hh) for _ in range(4)]
                lp = rounded_rect_loop(G, rnd, c[0] - w / 2, c[1] - hh / 2, w, hh, rs, ccw=rnd.random() < 0.5)
            hp = loop_poly(G, lp)
            if not all(inside(p, op) for p in hp):
                continue
            if min_dist_polys(hp, op) < 0.5 * h or any(min_dist_polys(hp, g) < 0.5 * h for g in hpolys):
                continue
            F.v, F.key, F.arcs = G.v, G.key, G.arcs
            holes.append(lp); hpolys.append(hp)
            break
    F.patches.append([outer] + holes)
    return F, h, "%s_h%d" % (kind, len(holes))


# ------------------------------------------------------------------ family 6: extremes
def fam_extreme(rnd):
    F = Flat()
    kind = rnd.choice(["sliver", "star", "closehole", "hugesize", "tinysize"])
    if kind == "sliver":
        asp = math.exp(rnd.uniform(math.log(50), math.log(500)))
        L = rnd.uniform(10, 500); t = L / asp
        sub = rnd.choice(["rect", "ellipse", "parallelogram", "bentbar", "blob"])
        if sub == "rect":
            pts = [(0, 0), (L, 0), (L, t), (0, t)]
        elif sub == "ellipse":
            n = rnd.randint(8, 200)
            pts = [(L / 2 * math.cos(TAU * i / n), t / 2 * math.sin(TAU * i / n)) for i in range(n)]
        elif sub == "parallelogram":
            sk = rnd.uniform(-2, 2) * L
            pts = [(0, 0), (L, 0), (L + sk, t), (sk, t)]
        elif sub == "bentbar":  # zigzag thin bar
            m = rnd.randint(2, 8)
            xs = [L * i / m for i in range(m + 1)]
            yo = [rnd.uniform(-0.2, 0.2) * L for _ in xs]
            pts = [(x, y) for x, y in zip(xs, yo)] + [(x, y + t) for x, y in zip(xs[::-1], yo[::-1])]
        else:
            n = rnd.randint(40, 300)
            p, _ = blob_outline(rnd, 1.0, n, noise=0.01)
            pts = [(x * L / 2, y * t / 2) for x, y in p]
        h = t * math.exp(rnd.uniform(math.log(0.3), math.log(3)))
        F.patches.append([F.loop(pts)])
        name = "sliver_%s_asp%d" % (sub, asp)
    elif kind == "star":
        n = rnd.randint(3, 20); R = rnd.uniform(5, 100)
        alpha = math.radians(rnd.uniform(1, 5)) / 2
        pts = []
        var = rnd.random() < 0.5
        for i in range(n):
            Ri = R * (rnd.uniform(0.5, 1.0) if var else 1.0)
            r_in = Ri * math.tan(alpha) / (math.sin(math.pi / n) + math.tan(alpha) * math.cos(math.pi / n))
            r_in = max(r_in, 0.02 * R)
            th = TAU * i / n
            pts.append((Ri * math.cos(th), Ri * math.sin(th)))
            pts.append((r_in * math.cos(th + math.pi / n), r_in * math.sin(th + math.pi / n)))
        # core: inner radius defined by tip angle; if too small for n spikes use blob core
        h = R * rnd.uniform(0.01, 0.1)
        F.patches.append([F.loop(pts)])
        name = "star_n%d_tip%.1f" % (n, math.degrees(2 * alpha))
    elif kind == "closehole":
        S = rnd.uniform(5, 200); h = S * rnd.uniform(0.02, 0.1)
        g = h * rnd.uniform(0.05, 0.5)
        sub = rnd.choice(["rect", "blob", "twoholes"])
        if sub == "blob":
            op, _ = blob_outline(rnd, S / 2, rnd.randint(40, 200), dense=False, noise=0.0)
        else:
            op = [(0, 0), (S, 0), (S, S * 0.6), (0, S * 0.6)]
        outer = F.loop(op)
        # hole: polygon near a boundary edge with gap g (shift until min distance == g)
        holes = []
        for _ in range(50):
            i = rnd.randrange(len(op))
            A, B = op[i], op[(i + 1) % len(op)]
            L = math.dist(A, B)
            nx, ny = -(B[1] - A[1]) / L, (B[0] - A[0]) / L
            if area(op) < 0:
                nx, ny = -nx, -ny
            M = ((A[0] + B[0]) / 2, (A[1] + B[1]) / 2)
            rr = rnd.uniform(0.5, 3) * h
            hp = rand_poly(rnd, 0, 0, rr, rnd.randint(3, 10))
            # move hole so its nearest point to the line is at distance g
            dmin = min((p[0] * nx + p[1] * ny) for p in hp)
            off = g - dmin
            hp = [(M[0] + p[0] + nx * off, M[1] + p[1] + ny * off) for p in hp]
            if not all(inside(p, op) for p in hp):
                continue
            if min_dist_polys(hp, op) < 0.99 * g:
                continue
            holes.append(hp)
            if sub != "twoholes":
                break
            # second hole at gap g from the first
            q = rand_poly(rnd, 0, 0, rr, rnd.randint(3, 10))
            dd = min((p[0] * nx + p[1] * ny) for p in q)
            top = max(p[0] * nx + p[1] * ny for p in hp) - (M[0] * nx + M[1] * ny)
            off2 = top + g - dd
            q = [(M[0] + p[0] + nx * off2, M[1] + p[1] + ny * off2) for p in q]
            if all(inside(p, op) for p in q) and min_dist_polys(q, op) > 0.99 * g and min_dist_polys(q, hp) > 0.99 * g:
                holes.append(q)
                break
            holes = []
        if not holes:
            raise Bad("no close hole")
        F.patches.append([outer] + [F.loop(hh) for hh in holes])
        name = "closehole_%s_g%.2f" % (sub, g / h)
    else:
        sub = rnd.choice([fam_blob, fam_rect, fam_arcs])
        F, h0, nm = sub(rnd)
        xs = [p[0] for p in F.v]; ys = [p[1] for p in F.v]
        diag = math.hypot(max(xs) - min(xs), max(ys) - min(ys))
        if kind == "hugesize":
            h = diag * rnd.uniform(1.5, 20)
        else:
            h = diag / rnd.uniform(150, 250)
        name = "%s_%s" % (kind, nm)
    return F, h, name


FAMS = {"blob": fam_blob, "rect": fam_rect, "split": fam_split, "bent": fam_bent, "arcs": fam_arcs, "extreme": fam_extreme}


def make(fam, seed):
    rnd = random.Random(seed)
    random.seed(seed)
    for attempt in range(40):
        try:
            F, h, name = FAMS[fam](rnd)
            validate(F)
            A = flat_area(F)
            if A / (h * h) > 300000:
                raise Bad("too many quads")
            lift = getattr(F, "_lift", None)
            d = to_json(F, h, lift, getattr(F, "_plift", None))
            return d, name, A / (h * h)
        except Bad as e:
            continue
    return None, None, None


if __name__ == "__main__":
    if sys.argv[1] == "gen":
        out = sys.argv[2]; N = int(sys.argv[3]); seed0 = int(sys.argv[4])
        fams = sys.argv[5].split(",") if len(sys.argv) > 5 else list(FAMS)
        os.makedirs(out, exist_ok=True)
        for fam in fams:
            for i in range(N):
                seed = seed0 * 1000003 + sum(map(ord, fam)) * 1009 + i
                d, name, est = make(fam, seed)
                if d is None:
                    print("FAILGEN", fam, i, file=sys.stderr); continue
                fn = os.path.join(out, "%s_%03d.json" % (fam, i))
                json.dump(d, open(fn, "w"))
                print("%s\t%s\t%d\t%s\t%.0f" % (fn, fam, seed, name, est), flush=True)
