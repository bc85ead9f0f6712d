#!/usr/bin/python3
"""Generator of stress-test parts for laytracks (B-Rep JSON brep/1).

usage:
  gen.py gen OUTDIR            write parts OUTDIR/<family>__<name>.json, one per line to stdout
  gen.py pose IN OUT KIND      write IN transformed: rot (random 3D rotation), mirror,
                               s1e-3, s1e3 (scale; mesh.size is scaled too)
  gen.py malformed OUTDIR      write malformed parts + OUTDIR/expected.tsv
"""
import json, math, os, random, sys

TAU = 2 * math.pi


class Part:
    def __init__(self, size=None):
        self.v = []
        self.key = {}
        self.patches = []
        self.arcs = []
        self.size = size

    def vid(self, p):
        p = [float(c) for c in p]
        k = tuple(round(c, 9) for c in p)
        if k in self.key:
            return self.key[k]
        self.key[k] = len(self.v)
        self.v.append(p)
        return self.key[k]

    def loop(self, pts):
        return [self.vid(p) for p in pts]

    def patch(self, outer, holes=(), name=None):
        loops = [self.loop(outer)] + [self.loop(h) for h in holes]
        d = {"loops": loops}
        if name:
            d["name"] = name
        self.patches.append(d)
        return loops

    def arc(self, a, b, via):
        self.arcs.append({"from": self.vid(a), "to": self.vid(b), "via": [float(c) for c in via]})

    def json(self):
        d = {"laytracks": "brep/1", "units": "mm", "vertices": self.v, "patches": self.patches}
        if self.arcs:
            d["arcs"] = self.arcs
        if self.size:
            d["mesh"] = {"size": self.size}
        return d


def default_size(pts):
    n = len(pts)
    c = [sum(p[i] for p in pts) / n for i in range(3)]
    r = max(math.dist(p, c) for p in pts)
    return 2 * r / 40


# ---------- 2D helpers ---------------------------------------------------------------
def xy(pts, z=0.0):
    return [(p[0], p[1], z) for p in pts]


def circle_pts(cx, cy, r, n, a0=0.0, cw=False):
    s = -1 if cw else 1
    return [(cx + r * math.cos(a0 + s * TAU * i / n), cy + r * math.sin(a0 + s * TAU * i / n)) for i in range(n)]


def arc_circle(P, cx, cy, r, n, z=0.0, a0=0.0):
    """circle made of n arcs, returns 3D loop points; registers arcs."""
    pts = [(cx + r * math.cos(a0 + TAU * i / n), cy + r * math.sin(a0 + TAU * i / n), z) for i in range(n)]
    for i in range(n):
        am = a0 + TAU * (i + 0.5) / n
        P.arc(pts[i], pts[(i + 1) % n], (cx + r * math.cos(am), cy + r * math.sin(am), z))
    return pts


def rect(x0, y0, x1, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]


# ---------- families -----------------------------------------------------------------
def prism(n, r, h, caps=True, twist=0.0):
    P = Part()
    bot = [(r * math.cos(TAU * i / n), r * math.sin(TAU * i / n), 0) for i in range(n)]
    top = [(r * math.cos(TAU * i / n + twist), r * math.sin(TAU * i / n + twist), h) for i in range(n)]
    if caps:
        P.patch(bot, name="bottom")
        P.patch(top[::-1], name="top")
    for i in range(n):
        j = (i + 1) % n
        P.patch([bot[i], bot[j], top[j], top[i]], name="side%d" % i)
    return P


def tetra():
    P = Part()
    V = [(0, 0, 0), (10, 0, 0), (5, 8.660254037844386, 0), (5, 2.886751345948129, 8.16496580927726)]
    for f in [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]:
        P.patch([V[i] for i in f])
    return P


def octa(s=10.0):
    P = Part()
    V = [(s, 0, 0), (-s, 0, 0), (0, s, 0), (0, -s, 0), (0, 0, s), (0, 0, -s)]
    F = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    for f in F:
        P.patch([V[i] for i in f])
    return P


def icosa(s=10.0):
    P = Part()
    t = (1 + 5 ** 0.5) / 2
    V = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    V = [(a * s, b * s, c * s) for a, b, c in V]
    F = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for f in F:
        P.patch([V[i] for i in f])
    return P


def box(a, b, c, top_hole=None, open_top=False, size=None):
    """closed box; top_hole: None, ('poly', n, r), ('arc', n, r)"""
    P = Part(size)
    V = lambda x, y, z: (x * a, y * b, z * c)
    P.patch([V(0, 0, 0), V(0, 1, 0), V(1, 1, 0), V(1, 0, 0)], name="bottom")
    P.patch([V(0, 0, 0), V(1, 0, 0), V(1, 0, 1), V(0, 0, 1)], name="south")
    P.patch([V(1, 0, 0), V(1, 1, 0), V(1, 1, 1), V(1, 0, 1)], name="east")
    P.patch([V(1, 1, 0), V(0, 1, 0), V(0, 1, 1), V(1, 1, 1)], name="north")
    P.patch([V(0, 1, 0), V(0, 0, 0), V(0, 0, 1), V(0, 1, 1)], name="west")
    if not open_top:
        holes = []
        if top_hole:
            kind, n, r = top_hole
            if kind == "poly":
                holes.append([(a / 2 + x, b / 2 + y, c) for x, y in circle_pts(0, 0, r, n, 0.3)])
            else:
                holes.append(arc_circle(P, a / 2, b / 2, r, n, z=c))
        P.patch([V(0, 0, 1), V(1, 0, 1), V(1, 1, 1), V(0, 1, 1)], holes, name="top")
    return P


def box_tunnel(a, b, c, w):
    """closed box with a square tunnel from bottom to top (genus 1 shell)."""
    P = Part()
    x0, x1, y0, y1 = a / 2 - w / 2, a / 2 + w / 2, b / 2 - w / 2, b / 2 + w / 2
    P.patch([(0, 0, 0), (0, b, 0), (a, b, 0), (a, 0, 0)], [[(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)]], "bottom")
    P.patch([(0, 0, c), (a, 0, c), (a, b, c), (0, b, c)], [[(x0, y0, c), (x0, y1, c), (x1, y1, c), (x1, y0, c)]], "top")
    for (p, q) in [((0, 0), (a, 0)), ((a, 0), (a, b)), ((a, b), (0, b)), ((0, b), (0, 0))]:
        P.patch([(p[0], p[1], 0), (q[0], q[1], 0), (q[0], q[1], c), (p[0], p[1], c)])
    T = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]
    for i in range(4):
        p, q = T[i], T[(i + 1) % 4]
        P.patch([(p[0], p[1], 0), (p[0], p[1], c), (q[0], q[1], c), (q[0], q[1], 0)], name="tunnel%d" % i)
    return P


def profile_sheet(profile, depth, holes_in=(), nseg_y=1, size=None):
    """extrude a 2D polyline profile (x,z) along y; each segment a rectangle patch.
    holes_in: indices of segments with a round hole; nseg_y>1 splits along y (flat seams)."""
    P = Part(size)
    ys = [depth * k / nseg_y for k in range(nseg_y + 1)]
    for i in range(len(profile) - 1):
        (xa, za), (xb, zb) = profile[i], profile[i + 1]
        L = math.hypot(xb - xa, zb - za)
        for k in range(nseg_y):
            y0, y1 = ys[k], ys[k + 1]
            holes = []
            if i in holes_in and k == 0:
                r = min(L, y1 - y0) * 0.2
                cx, cy = 0.5, (y0 + y1) / 2
                # hole in local coords: u along segment (0..1), y
                pts = []
                for j in range(16):
                    ang = TAU * j / 16
                    u = cx + r * math.cos(ang) / L
                    pts.append((xa + (xb - xa) * u, cy + r * math.sin(ang), za + (zb - za) * u))
                holes.append(pts)
            P.patch([(xa, y0, za), (xb, y0, zb), (xb, y1, zb), (xa, y1, za)], holes, name="s%d_%d" % (i, k))
    return P


def polyline_from_turns(lengths, turns_deg):
    """2D polyline: start at origin along +x; turn by turns_deg[i] after segment i."""
    pts = [(0.0, 0.0)]
    ang = 0.0
    for i, L in enumerate(lengths):
        x, y = pts[-1]
        pts.append((x + L * math.cos(ang), y + L * math.sin(ang)))
        if i < len(turns_deg):
            ang += math.radians(turns_deg[i])
    return pts


def box_flanges(a, b, c, f):
    """open box (no top) with outward flanges at the top rim; flanges meet at corners by
    square corner patches."""
    P = Part()
    P.patch([(0, 0, 0), (0, b, 0), (a, b, 0), (a, 0, 0)], name="floor")
    W = [((0, 0), (a, 0)), ((a, 0), (a, b)), ((a, b), (0, b)), ((0, b), (0, 0))]
    for (p, q) in W:
        P.patch([(p[0], p[1], 0), (q[0], q[1], 0), (q[0], q[1], c), (p[0], p[1], c)])
    # flanges: rectangles outward
    P.patch([(0, 0, c), (a, 0, c), (a, -f, c), (0, -f, c)], name="fl_s")
    P.patch([(a, 0, c), (a, b, c), (a + f, b, c), (a + f, 0, c)], name="fl_e")
    P.patch([(a, b, c), (0, b, c), (0, b + f, c), (a, b + f, c)], name="fl_n")
    P.patch([(0, b, c), (0, 0, c), (-f, 0, c), (-f, b, c)], name="fl_w")
    # corner squares (flat seams with two flanges)
    P.patch([(0, 0, c), (0, -f, c), (-f, -f, c), (-f, 0, c)], name="c_sw")
    P.patch([(a, 0, c), (a + f, 0, c), (a + f, -f, c), (a, -f, c)], name="c_se")
    P.patch([(a, b, c), (a, b + f, c), (a + f, b + f, c), (a + f, b, c)], name="c_ne")
    P.patch([(0, b, c), (-f, b, c), (-f, b + f, c), (0, b + f, c)], name="c_nw")
    return P


def rib_plate(L, W, h, nribs, crossing=False, below=False):
    """plate LxW split at rib lines x=k*L/(n+1); ribs standing on the split lines (3 patches at
    an edge); below=True adds ribs under the plate too (4 patches per edge)."""
    P = Part()
    xs = [L * k / (nribs + 1) for k in range(nribs + 2)]
    if not crossing:
        for k in range(nribs + 1):
            P.patch([(xs[k], 0, 0), (xs[k + 1], 0, 0), (xs[k + 1], W, 0), (xs[k], W, 0)], name="plate%d" % k)
        for k in range(1, nribs + 1):
            P.patch([(xs[k], 0, 0), (xs[k], W, 0), (xs[k], W, h), (xs[k], 0, h)], name="rib%d" % k)
            if below:
                P.patch([(xs[k], 0, 0), (xs[k], 0, -h), (xs[k], W, -h), (xs[k], W, 0)], name="ribb%d" % k)
    else:
        ym = W / 2
        ys = [0, ym, W]
        for k in range(nribs + 1):
            for j in range(2):
                P.patch([(xs[k], ys[j], 0), (xs[k + 1], ys[j], 0), (xs[k + 1], ys[j + 1], 0), (xs[k], ys[j + 1], 0)])
        for k in range(1, nribs + 1):
            for j in range(2):
                P.patch([(xs[k], ys[j], 0), (xs[k], ys[j + 1], 0), (xs[k], ys[j + 1], h), (xs[k], ys[j], h)])
        # the long rib along y=ym split at crossings
        for k in range(nribs + 1):
            P.patch([(xs[k], ym, 0), (xs[k + 1], ym, 0), (xs[k + 1], ym, h), (xs[k], ym, h)])
    return P


def tray_ribs(L, W, H, nribs, size=None):
    """open tray; ribs across the floor (x=const) meeting both long walls; walls split at ribs."""
    P = Part(size)
    xs = [L * k / (nribs + 1) for k in range(nribs + 2)]
    for k in range(nribs + 1):
        P.patch([(xs[k], 0, 0), (xs[k + 1], 0, 0), (xs[k + 1], W, 0), (xs[k], W, 0)], name="floor%d" % k)
        P.patch([(xs[k], 0, 0), (xs[k], 0, H), (xs[k + 1], 0, H), (xs[k + 1], 0, 0)], name="ws%d" % k)
        P.patch([(xs[k], W, 0), (xs[k + 1], W, 0), (xs[k + 1], W, H), (xs[k], W, H)], name="wn%d" % k)
    P.patch([(0, 0, 0), (0, W, 0), (0, W, H), (0, 0, H)], name="ww")
    P.patch([(L, 0, 0), (L, 0, H), (L, W, H), (L, W, 0)], name="we")
    rh = H * 0.6
    for k in range(1, nribs + 1):
        # rib as a pentagon so its top edge is below wall top: vertices on the wall edges
        # must be wall vertices -> use full height ribs
        P.patch([(xs[k], 0, 0), (xs[k], W, 0), (xs[k], W, H), (xs[k], 0, H)], name="rib%d" % k)
    return P


def plate_holes(W, Hh, holes, size=None, fillet=0.0, nfil=1):
    """plate W x H with holes [(kind, cx, cy, r, n)] kind poly|arc|slot (slot: r, len)"""
    P = Part(size)
    if fillet > 0:
        outer = []
        corners = [(W - fillet, fillet, -90), (W - fillet, Hh - fillet, 0), (fillet, Hh - fillet, 90), (fillet, fillet, 180)]
        for (cx, cy, a0) in corners:
            pts = [(cx + fillet * math.cos(math.radians(a0 + 90 * t / nfil)), cy + fillet * math.sin(math.radians(a0 + 90 * t / nfil)), 0)
                   for t in range(nfil + 1)]
            for t in range(nfil):
                am = math.radians(a0 + 90 * (t + 0.5) / nfil)
                P.arc(pts[t], pts[t + 1], (cx + fillet * math.cos(am), cy + fillet * math.sin(am), 0))
            outer += pts
    else:
        outer = xy(rect(0, 0, W, Hh))
    hl = []
    for h in holes:
        kind = h[0]
        if kind == "poly":
            _, cx, cy, r, n = h
            hl.append(xy(circle_pts(cx, cy, r, n, 0.1)))
        elif kind == "arc":
            _, cx, cy, r, n = h
            hl.append(arc_circle(P, cx, cy, r, n))
        elif kind == "slot":
            _, cx, cy, r, l = h
            a, b = (cx - l / 2, cy), (cx + l / 2, cy)
            p1, p2, p3, p4 = (b[0], cy - r, 0), (b[0], cy + r, 0), (a[0], cy + r, 0), (a[0], cy - r, 0)
            P.arc(p1, p2, (b[0] + r, cy, 0))
            P.arc(p3, p4, (a[0] - r, cy, 0))
            hl.append([p1, p2, p3, p4])
        elif kind == "rect":
            _, x0, y0, x1, y1 = h
            hl.append(xy(rect(x0, y0, x1, y1)))
    P.patch(outer, hl, name="plate")
    return P


def polygon_part(pts2, size=None, holes=()):
    P = Part(size)
    P.patch(xy(pts2), [xy(h) for h in holes], name="poly")
    return P


def comb(nteeth, tw, tl, gap, base):
    pts = [(0, 0)]
    x = 0
    W = nteeth * tw + (nteeth - 1) * gap
    pts = [(0, 0), (W, 0)]
    top = []
    for k in range(nteeth):
        x0 = k * (tw + gap)
        top += [(x0, base + tl), (x0 + tw, base + tl)]
        if k < nteeth - 1:
            top += [(x0 + tw, base), (x0 + tw + gap, base)]
    # traverse top from right to left
    pts += top[::-1][0:1]
    pts = [(0, 0), (W, 0)] + top[::-1]
    return pts


def spiral(turns, w, pitch, npt_per_turn):
    """strip along an archimedean spiral r = r0 + pitch*theta/2pi, width w."""
    r0 = pitch * 1.5
    n = int(turns * npt_per_turn)
    inner, outer = [], []
    for i in range(n + 1):
        th = TAU * turns * i / n
        r = r0 + pitch * th / TAU
        inner.append(((r - w / 2) * math.cos(th), (r - w / 2) * math.sin(th)))
        outer.append(((r + w / 2) * math.cos(th), (r + w / 2) * math.sin(th)))
    return outer + inner[::-1]


def wavy_polygon(n, r, amp, k):
    return [((r + amp * math.sin(k * TAU * i / n)) * math.cos(TAU * i / n),
             (r + amp * math.sin(k * TAU * i / n)) * math.sin(TAU * i / n)) for i in range(n)]


def flat_seam_grid(nx, ny, W, Hh, jitter=0.0, rnd=random.Random(1)):
    P = Part()
    X = [[(W * i / nx + (jitter * (rnd.random() - .5) if 0 < i < nx else 0), Hh * j / ny + (jitter * (rnd.random() - .5) if 0 < j < ny else 0)) for j in range(ny + 1)] for i in range(nx + 1)]
    for i in range(nx):
        for j in range(ny):
            P.patch(xy([X[i][j], X[i + 1][j], X[i + 1][j + 1], X[i][j + 1]]))
    return P


def flat_seam_poly(n, r, nsplit):
    """a polygon disc cut into nsplit pie patches meeting at the centre (flat fan)."""
    P = Part()
    pts = circle_pts(0, 0, r, n)
    step = n // nsplit
    for s in range(nsplit):
        a = s * step
        b = (s + 1) * step if s < nsplit - 1 else n
        seq = [pts[i % n] for i in range(a, b + 1)]
        P.patch(xy([(0, 0)] + seq))
    return P


def umbrella(n, r, apex_h, rim_h=0.0, arcs=False):
    """n triangular patches around one apex; optional rim skirt patches."""
    P = Part()
    rim = [(r * math.cos(TAU * i / n), r * math.sin(TAU * i / n), 0) for i in range(n)]
    ap = (0, 0, apex_h)
    for i in range(n):
        P.patch([ap, rim[i], rim[(i + 1) % n]])
    if rim_h:
        for i in range(n):
            j = (i + 1) % n
            P.patch([rim[i], (rim[i][0], rim[i][1], -rim_h), (rim[j][0], rim[j][1], -rim_h), rim[j]])
    return P


def two_plates_vertex_fan(n):
    """n rectangular fins sharing one vertical edge (n patches at one edge, book shape)."""
    P = Part()
    for i in range(n):
        a = TAU * i / n
        P.patch([(0, 0, 0), (10 * math.cos(a), 10 * math.sin(a), 0), (10 * math.cos(a), 10 * math.sin(a), 10), (0, 0, 10)])
    return P



def arc_outline(P, segs, z=0.0):
    """segs: list of (x, y, bulge) ; bulge = sagitta of the arc to the next point (0: line,
    >0 to the left of the direction of travel). returns 3D loop points."""
    pts = [(x, y, z) for x, y, _ in segs]
    n = len(segs)
    for i in range(n):
        x0, y0, b = segs[i]
        x1, y1, _ = segs[(i + 1) % n]
        if b:
            mx, my = (x0 + x1) / 2, (y0 + y1) / 2
            L = math.hypot(x1 - x0, y1 - y0)
            nx, ny = -(y1 - y0) / L, (x1 - x0) / L
            P.arc(pts[i], pts[(i + 1) % n], (mx + b * nx, my + b * ny, z))
    return pts


def gen2(add):
    rnd = random.Random(999)
    # several shells in one file
    P = box(10, 10, 10)
    for p in box(6, 6, 6).json()["patches"]:
        pass
    Q = Part()
    for pp in [box(10, 10, 10), prism(7, 4, 6)]:
        pass
    P = Part()
    for (ox, B) in [(0, box(10, 10, 10)), (30, prism(7, 4, 6)), (60, None)]:
        if B is None:
            P.patch(xy([(60, 0), (80, 0), (80, 10), (60, 10)]), name="loose_plate")
            continue
        for pt in B.patches:
            P.patch([[B.v[i][0] + ox, B.v[i][1], B.v[i][2]] for i in pt["loops"][0]])
    add("multi", "box_prism_plate", P)
    P = Part()
    for k in range(5):
        P.patch(xy([(k * 12, 0), (k * 12 + 10, 0), (k * 12 + 10, 10 + k), (k * 12, 10 + k)]))
    add("multi", "five_plates", P)
    P = Part()  # two plates touching at one vertex only
    P.patch(xy([(0, 0), (10, 0), (10, 10), (0, 10)]))
    P.patch(xy([(10, 10), (20, 10), (20, 20), (10, 20)]))
    add("multi", "touch_vertex", P)
    P = Part()  # two plates sharing a vertex in 3D (different planes)
    P.patch([(0, 0, 0), (10, 0, 0), (10, 10, 0), (0, 10, 0)])
    P.patch([(10, 10, 0), (10, 20, 5), (10, 20, 15), (10, 10, 10)])
    add("multi", "touch_vertex_3d", P)
    # hems and near-flat folds
    for ang in [178, 179, 179.9, 2, 1, 0.5]:
        pl = polyline_from_turns([20, 20], [ang])
        add("fold2", "a%g" % ang, profile_sheet(pl, 15))
    add("fold2", "hem_short", profile_sheet(polyline_from_turns([30, 1.5], [170]), 20))
    add("fold2", "tiny_flange", profile_sheet([(0, 0), (30, 0), (30, 0.3)], 20, size=1.0))
    add("fold2", "flange_0.6h", profile_sheet([(0, 0), (30, 0), (30, 0.6)], 20, size=1.0))
    # arcs: outlines with concave arcs, big arcs, keyholes
    P = Part()
    P.patch(arc_outline(P, [(0, 0, 2), (20, 0, 0), (20, 10, 2), (0, 10, 0)]))
    add("arcs", "concave_sides", P)
    P = Part()
    P.patch(arc_outline(P, [(0, 0, -8), (20, 0, 0), (20, 10, -8), (0, 10, 0)]))
    add("arcs", "convex_big", P)
    P = Part()  # D shape: arc > 180 degrees (via beyond the diameter)
    P.patch(arc_outline(P, [(0, -5, 14), (0, 5, 0)]) if False else arc_outline(P, [(0, -5, 0), (0, 5, 0), (-1, 5, 0)])[:0] or arc_outline(P, [(0, -5, 0), (2, 5, 0), (0, 5, 10)]))
    add("arcs", "D_shape", P)
    P = Part()  # 270-degree arc: points on circle r=5 at -135 and 135 deg, via at 0
    a, b = (5 * math.cos(math.radians(135)), 5 * math.sin(math.radians(135))), (5 * math.cos(math.radians(-135)), 5 * math.sin(math.radians(-135)))
    P.patch([(a[0], a[1], 0), (b[0], b[1], 0), (5, 0, 0)]) if False else None
    pts = [(b[0], b[1], 0), (5, 0, 0), (a[0], a[1], 0), (-8, 0, 0)]
    P.patch(pts)
    P.arc(pts[0], pts[1], (5 * math.cos(math.radians(-67.5)), 5 * math.sin(math.radians(-67.5)), 0))
    P.arc(pts[1], pts[2], (5 * math.cos(math.radians(67.5)), 5 * math.sin(math.radians(67.5)), 0))
    add("arcs", "keyhole_tip", P)
    P = Part()
    pts = [(0, 0, 0), (10, 0, 0), (10, 10, 0)]
    P.patch(pts)
    P.arc(pts[0], pts[1], (5, -4.9, 0))
    add("arcs", "tri_arc_base", P)
    P = Part()  # scalloped disc: 12 concave arcs
    n = 12
    pts = [(10 * math.cos(TAU * i / n), 10 * math.sin(TAU * i / n), 0) for i in range(n)]
    P.patch(pts)
    for i in range(n):
        am = TAU * (i + .5) / n
        P.arc(pts[i], pts[(i + 1) % n], (8.8 * math.cos(am), 8.8 * math.sin(am), 0))
    add("arcs", "scallop12", P)
    P = Part()  # gear-ish: arcs alternating convex / concave
    n = 16
    pts = [(10 * math.cos(TAU * i / n), 10 * math.sin(TAU * i / n), 0) for i in range(n)]
    P.patch(pts, [arc_circle(P, 0, 0, 3, 3)])
    for i in range(n):
        am = TAU * (i + .5) / n
        r = 11 if i % 2 else 9.3
        P.arc(pts[i], pts[(i + 1) % n], (r * math.cos(am), r * math.sin(am), 0))
    add("arcs", "gear16_hole", P)
    # hex hole grid
    hs = []
    for i in range(6):
        for j in range(4):
            hs.append(("poly", 5 + 8 * i + (4 if j % 2 else 0), 5 + 7 * j, 2.5, 6))
    add("holes2", "hexgrid", plate_holes(57, 30, hs))
    add("holes2", "hexgrid_fine", plate_holes(57, 30, hs, size=0.5))
    # holes everywhere in a folded part
    P = profile_sheet([(0, 10), (0, 0), (20, 0), (20, 10)], 30, holes_in=(0, 1, 2))
    add("holes2", "U_holes", P)
    # box with holes on all faces (closed with holes)
    P = Part()
    a = 20
    faces = [[(0, 0, 0), (0, a, 0), (a, a, 0), (a, 0, 0)], [(0, 0, a), (a, 0, a), (a, a, a), (0, a, a)],
             [(0, 0, 0), (a, 0, 0), (a, 0, a), (0, 0, a)], [(a, 0, 0), (a, a, 0), (a, a, a), (a, 0, a)],
             [(a, a, 0), (0, a, 0), (0, a, a), (a, a, a)], [(0, a, 0), (0, 0, 0), (0, 0, a), (0, a, a)]]
    for k, f in enumerate(faces):
        c = [sum(p[i] for p in f) / 4 for i in range(3)]
        u = [(f[1][i] - f[0][i]) / a for i in range(3)]
        v = [(f[3][i] - f[0][i]) / a for i in range(3)]
        hole = [tuple(c[i] + (3 + k) * (math.cos(TAU * j / 8) * u[i] + math.sin(TAU * j / 8) * v[i]) for i in range(3)) for j in range(8)]
        P.patch(f, [hole])
    add("holes2", "cube_holes", P)
    # random simple polygons (star-shaped, many vertices) and random rectilinear
    for k in range(6):
        n = rnd.choice([30, 80, 200, 320])
        rs = [10 + rnd.uniform(-4, 4) for _ in range(n)]
        add("rndpoly", "star%d_n%d" % (k, n), polygon_part([(r * math.cos(TAU * i / n), r * math.sin(TAU * i / n)) for i, r in enumerate(rs)]))
    for k in range(6):
        # rectilinear staircase polygon
        m = rnd.randint(3, 15)
        pts = [(0, 0)]
        x, y = 0, 0
        for i in range(m):
            x += rnd.uniform(0.5, 5); pts.append((x, y))
            y += rnd.uniform(0.5, 5); pts.append((x, y))
        pts.append((0, y))
        add("rndpoly", "stairs%d" % k, polygon_part(pts))
    # umbrellas with very flat or very steep cones, and half-umbrella
    add("fan2", "steep24", umbrella(24, 3, 40))
    add("fan2", "flat24_h0.1", umbrella(24, 10, 0.1))
    P = Part()  # half-fan on a plate: 5 coplanar wedges around a boundary vertex
    for i in range(5):
        a0, a1 = math.pi * i / 5, math.pi * (i + 1) / 5
        P.patch(xy([(0, 0), (10 * math.cos(a0), 10 * math.sin(a0)), (10 * math.cos(a1), 10 * math.sin(a1))]))
    add("fan2", "half_fan5", P)
    P = Part()  # book: 6 pages at one edge with holes
    for i in range(6):
        a = TAU * i / 6
        c, s_ = math.cos(a), math.sin(a)
        hole = [(5 * c + 2 * math.cos(TAU * j / 6) * c, 5 * s_ + 2 * math.cos(TAU * j / 6) * s_, 5 + 2 * math.sin(TAU * j / 6)) for j in range(6)]
        P.patch([(0, 0, 0), (10 * c, 10 * s_, 0), (10 * c, 10 * s_, 10), (0, 0, 10)], [hole])
    add("fan2", "book6_holes", P)
    # near-coincident but distinct features
    add("tiny2", "sliver_gap", plate_holes(20, 10, [("rect", 2, 2, 18, 8)]))  # frame of width 2
    add("tiny2", "frame_thin", plate_holes(20, 10, [("rect", 0.3, 0.3, 19.7, 9.7)], size=0.5))
    add("tiny2", "hole_gap_1e-3", plate_holes(20, 10, [("rect", 2, 2, 9.9995, 8), ("rect", 10.0005, 2, 18, 8)]))
    add("tiny2", "hole_near_1e-3", plate_holes(20, 10, [("rect", 2, 0.001, 18, 8)]))



def gen3(add):
    rnd = random.Random(5)
    for ang in [5, 10, 30, 170, 175]:
        P = Part()
        P.patch(xy(rect(0, 0, 10, 20))); P.patch(xy(rect(10, 0, 20, 20)))
        a = math.radians(ang)
        P.patch([(10, 0, 0), (10, 20, 0), (10 + 8 * math.cos(a), 20, 8 * math.sin(a)), (10 + 8 * math.cos(a), 0, 8 * math.sin(a))])
        add("tee2", "rib_ang%d" % ang, P)
    for hh in [0.05, 0.2, 0.5]:
        P = Part(1.0)
        P.patch(xy(rect(0, 0, 10, 20))); P.patch(xy(rect(10, 0, 20, 20)))
        P.patch([(10, 0, 0), (10, 20, 0), (10, 20, hh), (10, 0, hh)])
        add("tee2", "rib_h%g" % hh, P)
    for m in [5, 20, 60]:
        seam = [(10 + rnd.uniform(-2, 2), 20 * i / m) for i in range(m + 1)]
        seam[0] = (10, 0); seam[-1] = (10, 20)
        P = Part()
        P.patch(xy([(0, 0)] + seam + [(0, 20)]))
        P.patch(xy([(20, 0), (20, 20)] + seam[::-1]))
        add("seam2", "jagged%d" % m, P)
    for n in [5, 9, 16]:
        angs = sorted(rnd.uniform(0, TAU) for _ in range(n))
        P = Part()
        for i in range(n):
            a0, a1 = angs[i], angs[(i + 1) % n] + (TAU if i == n - 1 else 0)
            k = max(1, int((a1 - a0) / 0.3))
            arcpts = [(10 * math.cos(a0 + (a1 - a0) * j / k), 10 * math.sin(a0 + (a1 - a0) * j / k)) for j in range(k + 1)]
            P.patch(xy([(0, 0)] + arcpts))
        add("seam2", "flatfan_uneven%d" % n, P)
    # found by hand: see failing/
    add("holes3", "bridge_1e-3", plate_holes(20, 10, [("rect", 2, 2, 9.9995, 8), ("rect", 10.0005, 2, 18, 8)]))
    add("holes3", "bridge_1e-2", plate_holes(20, 10, [("rect", 2, 2, 9.995, 8), ("rect", 10.005, 2, 18, 8)]))
    add("holes3", "wavy60_hole40", polygon_part(wavy_polygon(60, 20, 2, 20), holes=[circle_pts(0, 0, 6, 40)]))
    add("holes3", "wavy120_hole60", polygon_part(wavy_polygon(120, 20, 2, 20), holes=[circle_pts(0, 0, 6, 60)]))
    add("holes3", "star_hole", polygon_part([((10 if i % 2 else 14) * math.cos(TAU * i / 40), (10 if i % 2 else 14) * math.sin(TAU * i / 40)) for i in range(40)], holes=[circle_pts(0, 0, 5, 40)]))


def gen(outdir):
    rnd = random.Random(12345)
    os.makedirs(outdir, exist_ok=True)
    parts = {}

    def add(fam, name, P):
        parts["%s__%s" % (fam, name)] = P

    # closed faceted shells
    for n in [5, 6, 7, 9, 12, 17, 24]:
        add("prism", "n%d" % n, prism(n, 10, 15))
    add("prism", "n8_flat", prism(8, 20, 1.0))
    add("prism", "n6_tall", prism(6, 2, 40))
    add("prism", "n12_open", prism(12, 10, 15, caps=False))
    add("prism", "n5_twist", prism(5, 10, 10, caps=True, twist=0.0))
    for n in [32, 48, 64]:
        add("cyl", "n%d_open" % n, prism(n, 10, 30, caps=False))
        add("cyl", "n%d_closed" % n, prism(n, 10, 30))
    add("poly", "tetra", tetra())
    add("poly", "octa", octa())
    add("poly", "icosa", icosa())
    for (a, b, c) in [(1, 1, 1), (10, 1, 1), (20, 5, 0.5), (3, 2, 1), (100, 10, 10), (10, 10, 0.1)]:
        add("box", "%gx%gx%g" % (a, b, c), box(a, b, c))
    add("box", "hole_poly", box(20, 20, 10, ("poly", 12, 5)))
    add("box", "hole_arc", box(20, 20, 10, ("arc", 4, 5)))
    add("box", "hole_arc3", box(20, 20, 10, ("arc", 3, 5)))
    add("box", "hole_nearedge", box(20, 20, 10, ("arc", 4, 9.5)))
    add("box", "tunnel", box_tunnel(20, 20, 10, 6))
    add("box", "tunnel_thin", box_tunnel(20, 20, 10, 18))
    add("box", "open_flanges", box_flanges(20, 14, 8, 3))
    # sheet metal
    add("sheet", "U", profile_sheet([(0, 10), (0, 0), (15, 0), (15, 10)], 30))
    add("sheet", "Z", profile_sheet([(0, 0), (8, 0), (8, 12), (16, 12)], 30))
    add("sheet", "hat", profile_sheet([(0, 0), (5, 0), (5, 8), (15, 8), (15, 0), (20, 0)], 40))
    add("sheet", "hat_holes", profile_sheet([(0, 0), (5, 0), (5, 8), (15, 8), (15, 0), (20, 0)], 40, holes_in=(2, 0)))
    for ang in [30, 45, 120, 150, 170, 10]:
        pl = polyline_from_turns([10, 10, 10], [ang, ang])
        add("sheet", "fold%d" % ang, profile_sheet(pl, 20))
        pl = polyline_from_turns([10, 10, 10, 10], [ang, -ang, ang])
        add("sheet", "zig%d" % ang, profile_sheet(pl, 20))
    add("sheet", "mixed_folds", profile_sheet(polyline_from_turns([12, 8, 10, 6, 14], [30, 120, -45, 150]), 25, holes_in=(0, 2)))
    add("sheet", "U_seams", profile_sheet([(0, 10), (0, 0), (15, 0), (15, 10)], 30, nseg_y=3))
    add("sheet", "narrow_flange", profile_sheet([(0, 0.6), (0, 0), (30, 0), (30, 0.6)], 30))
    add("sheet", "polygon_tube", profile_sheet([(math.cos(TAU * i / 7) * 5, math.sin(TAU * i / 7) * 5) for i in range(8)], 20))
    # T-junctions
    add("tee", "rib1", rib_plate(30, 20, 5, 1))
    add("tee", "rib3", rib_plate(40, 20, 6, 3))
    add("tee", "rib1_both", rib_plate(30, 20, 5, 1, below=True))
    add("tee", "rib3_both", rib_plate(40, 20, 6, 3, below=True))
    add("tee", "crossing1", rib_plate(30, 20, 5, 1, crossing=True))
    add("tee", "crossing3", rib_plate(40, 20, 5, 3, crossing=True))
    add("tee", "tray2", tray_ribs(60, 30, 10, 2))
    add("tee", "tray5", tray_ribs(100, 30, 8, 5))
    add("tee", "fins3", two_plates_vertex_fan(3))
    add("tee", "fins5", two_plates_vertex_fan(5))
    add("tee", "fins8", two_plates_vertex_fan(8))
    # plates with holes
    h = 1.0
    add("holes", "several", plate_holes(40, 25, [("arc", 8, 8, 3, 4), ("poly", 20, 12, 4, 6), ("arc", 32, 16, 2.5, 3), ("poly", 10, 19, 2, 5)], size=h))
    for g in [0.2, 0.5, 1.0]:
        add("holes", "near_boundary_g%g" % g, plate_holes(40, 20, [("arc", 10, 3 + g * h, 3, 4), ("poly", 30, 20 - 3 - g * h, 3, 12)], size=h))
        add("holes", "near_each_g%g" % g, plate_holes(40, 20, [("arc", 14, 10, 5, 4), ("arc", 24 + g * h, 10, 5, 4)], size=h))
        add("holes", "rect_near_g%g" % g, plate_holes(40, 20, [("rect", 5, 5, 15, 15), ("rect", 15 + g * h, 5, 25, 15)], size=h))
    add("holes", "slots", plate_holes(50, 20, [("slot", 12, 10, 2, 10), ("slot", 35, 6, 1.5, 12), ("slot", 35, 14, 1.5, 12)], size=h))
    add("holes", "fillets", plate_holes(40, 20, [], size=h, fillet=4))
    add("holes", "fillets2", plate_holes(40, 20, [("arc", 20, 10, 4, 4)], size=h, fillet=3, nfil=2))
    add("holes", "fillets_full", plate_holes(40, 20, [], size=h, fillet=9.999, nfil=1))
    add("holes", "many_grid", plate_holes(60, 40, [("arc", 6 + 12 * i, 6 + 9.5 * j, 2.5, 4) for i in range(5) for j in range(4)], size=h))
    add("holes", "hole_tiny", plate_holes(30, 20, [("arc", 15, 10, 0.1, 4)], size=h))
    # thin strips / long aspect
    for w in [0.3, 0.7, 1.5, 3]:
        add("thin", "strip_w%g" % w, polygon_part(rect(0, 0, 30, w * h), size=h))
    add("thin", "long100", polygon_part(rect(0, 0, 100, 1)))
    add("thin", "long300", polygon_part(rect(0, 0, 300, 1)))
    add("thin", "long100_sized", polygon_part(rect(0, 0, 100, 1), size=0.25))
    P = Part(0.5)
    outer = arc_circle(P, 0, 0, 10, 4)
    inner = arc_circle(P, 0, 0, 9.7, 4, a0=0.3)
    P.patch(outer, [inner])
    add("thin", "annulus_thin", P)
    # tiny edges
    add("tiny", "edge1e-3", polygon_part([(0, 0), (20, 0), (20, 10), (10.01, 10), (10, 10), (0, 10)]))
    add("tiny", "edge1e-3_step", polygon_part([(0, 0), (20, 0), (20, 10), (10, 10), (10, 10.02), (0, 10.02)]))
    add("tiny", "edge1e-4", polygon_part([(0, 0), (20, 0), (20, 10), (10.002, 10), (10, 10.001), (0, 10)]))
    add("tiny", "notch", polygon_part([(0, 0), (20, 0), (20, 10), (10.01, 10), (10.005, 9.99), (10, 10), (0, 10)]))
    # near 180 degrees
    for dev in [5, 1, 0.5, 0.1]:
        d = 10 * math.tan(math.radians(dev) / 2)
        add("near180", "dev%g" % dev, polygon_part([(0, 0), (10, -d), (20, 0), (20, 10), (0, 10)]))
        add("near180", "concave_dev%g" % dev, polygon_part([(0, 0), (10, d), (20, 0), (20, 10), (0, 10)]))
    add("near180", "many", polygon_part([(20 * i / 30, 0.05 * (i % 2)) for i in range(31)] + [(20, 10), (0, 10)]))
    # acute
    for a in [2, 5, 10]:
        t = math.tan(math.radians(a))
        add("acute", "tri%d" % a, polygon_part([(0, 0), (30, 0), (30, 30 * t)]))
        add("acute", "kite%d" % a, polygon_part([(0, 0), (30, -15 * t), (40, 0), (30, 15 * t)]))
        add("acute", "notch%d" % a, polygon_part([(0, 0), (30, 0), (30, 4), (5, 4 + 25 * t), (30, 4 + 2 * 25 * t), (30, 20), (0, 20)]))
    # combs
    add("comb", "t10", polygon_part(comb(10, 2, 10, 2, 5)))
    add("comb", "t30_thin", polygon_part(comb(30, 1, 15, 1, 4)))
    add("comb", "t8_wide", polygon_part(comb(8, 4, 3, 0.5, 8)))
    # spirals
    add("spiral", "s3", polygon_part(spiral(3, 2, 4, 40)))
    add("spiral", "s5_fine", polygon_part(spiral(5, 1.5, 3, 80)))
    # many-vertex polygons
    add("manyv", "circle240", polygon_part(circle_pts(0, 0, 10, 240)))
    add("manyv", "wavy300", polygon_part(wavy_polygon(300, 10, 1.5, 12)))
    add("manyv", "wavy400_hole", polygon_part(wavy_polygon(400, 20, 2, 20), holes=[circle_pts(0, 0, 6, 200)]))
    add("manyv", "random_star250", polygon_part([(r * math.cos(TAU * i / 250), r * math.sin(TAU * i / 250)) for i, r in enumerate([10 + rnd.uniform(-3, 3) for _ in range(250)])]))
    # flat seams
    add("seam", "two", flat_seam_grid(2, 1, 30, 15))
    add("seam", "grid3x3", flat_seam_grid(3, 3, 30, 30))
    add("seam", "grid4x2_jit", flat_seam_grid(4, 2, 40, 20, 3, rnd))
    add("seam", "pie6", flat_seam_poly(24, 10, 6))
    add("seam", "pie3", flat_seam_poly(12, 10, 3))
    P = Part()  # plate split along a zigzag
    P.patch(xy([(0, 0), (20, 0), (18, 5), (22, 10), (20, 15), (0, 15)]))
    P.patch(xy([(20, 0), (40, 0), (40, 15), (20, 15), (22, 10), (18, 5)]))
    add("seam", "zigzag", P)
    P = Part()  # seam plus hole in one half, arc shared edge
    P.patch(xy([(0, 0), (20, 0), (20, 15), (0, 15)]), [xy(circle_pts(8, 7, 3, 10))])
    P.patch(xy([(20, 0), (40, 0), (40, 15), (20, 15)]))
    P.arc((20, 0, 0), (20, 15, 0), (23, 7.5, 0))
    add("seam", "arc_seam", P)
    # fans / umbrellas
    for n in [3, 6, 12, 24]:
        add("fan", "umbrella%d" % n, umbrella(n, 10, 3))
        add("fan", "flat%d" % n, umbrella(n, 10, 0))
    add("fan", "umbrella8_skirt", umbrella(8, 10, 4, rim_h=3))
    P = umbrella(6, 10, 5)
    P.patch([(10 * math.cos(TAU * i / 6), 10 * math.sin(TAU * i / 6), 0) for i in range(6)], name="base")
    add("fan", "pyramid_closed", P)

    # random mixtures: random plates with random holes
    for k in range(12):
        W, Hh = rnd.uniform(10, 60), rnd.uniform(5, 30)
        hs = []
        tries = 0
        while len(hs) < rnd.randint(1, 5) and tries < 100:
            tries += 1
            r = rnd.uniform(0.5, min(W, Hh) / 4)
            cx, cy = rnd.uniform(r + 0.3, W - r - 0.3), rnd.uniform(r + 0.3, Hh - r - 0.3)
            if all(math.hypot(cx - o[1], cy - o[2]) > r + o[3] + 0.3 for o in hs):
                hs.append((rnd.choice(["arc", "poly"]), cx, cy, r, rnd.choice([3, 4, 5, 8])))
        add("rndholes", "r%d" % k, plate_holes(W, Hh, hs, fillet=rnd.choice([0, 0, min(W, Hh) / 5])))
    # random closed prisms with random polygon base (convex)
    for k in range(6):
        n = rnd.randint(5, 24)
        add("rndprism", "r%d" % k, prism(n, rnd.uniform(1, 30), rnd.uniform(0.5, 50)))

    gen2(add)
    gen3(add)
    names = []
    for name, P in sorted(parts.items()):
        if P is None:
            continue
        with open(os.path.join(outdir, name + ".json"), "w") as f:
            json.dump(P.json(), f)
        names.append(name)
    for n in names:
        print(n)


# ---------- poses ---------------------------------------------------------------------
def rot_matrix(rnd):
    # random unit quaternion
    u1, u2, u3 = rnd.random(), rnd.random(), rnd.random()
    q = (math.sqrt(1 - u1) * math.sin(TAU * u2), math.sqrt(1 - u1) * math.cos(TAU * u2),
         math.sqrt(u1) * math.sin(TAU * u3), math.sqrt(u1) * math.cos(TAU * u3))
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def pose(inp, out, kind, seed=7):
    d = json.load(open(inp))
    rnd = random.Random(seed)
    if kind == "rot":
        M = rot_matrix(rnd)
        t = [rnd.uniform(-50, 50) for _ in range(3)]
        f = lambda p: [sum(M[i][j] * p[j] for j in range(3)) + t[i] for i in range(3)]
        s = 1.0
    elif kind == "mirror":
        f = lambda p: [-p[0], p[1], p[2]]
        s = 1.0
    elif kind.startswith("s"):
        s = float(kind[1:])
        f = lambda p: [c * s for c in p]
    d["vertices"] = [f(p) for p in d["vertices"]]
    for a in d.get("arcs", []):
        a["via"] = f(a["via"])
    if "mesh" in d and "size" in d["mesh"]:
        d["mesh"]["size"] *= s
    json.dump(d, open(out, "w"))


if __name__ == "__main__":
    if sys.argv[1] == "gen":
        gen(sys.argv[2])
    elif sys.argv[1] == "pose":
        pose(*sys.argv[2:5])
    elif sys.argv[1] == "malformed":
        import malformed
        malformed.main(sys.argv[2])
