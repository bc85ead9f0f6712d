#!/usr/bin/env python3
"""Writes the sample parts in samples/ (B-Rep JSON, ../shared/spec/brep-json.md).

The parts are built from a few parameters so that they stay consistent: every shared edge is
split where another patch meets it, and arcs carry exact via points. Run it from anywhere:
    python3 scripts/make_samples.py
"""
import json
import math
import os

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples")


class Part:
    def __init__(self):
        self.vertices = []
        self.index = {}
        self.patches = []
        self.arcs = []

    def v(self, x, y, z):
        key = (round(x, 9), round(y, 9), round(z, 9))
        if key not in self.index:
            self.index[key] = len(self.vertices)
            self.vertices.append([float(x), float(y), float(z)])
        return self.index[key]

    def patch(self, name, *loops):
        self.patches.append({"name": name, "loops": [list(l) for l in loops]})

    def arc(self, a, b, via):
        self.arcs.append({"from": a, "to": b, "via": [float(c) for c in via]})

    def circle(self, centre, radius, axes, pieces=4, phase=0.0):
        """A hole loop of `pieces` arcs; axes = (u, v) unit vectors of the plane."""
        (u, w) = axes
        pt = lambda a: [centre[i] + radius * (math.cos(a) * u[i] + math.sin(a) * w[i]) for i in range(3)]
        loop = [self.v(*pt(phase + 2 * math.pi * k / pieces)) for k in range(pieces)]
        for k in range(pieces):
            mid = phase + 2 * math.pi * (k + 0.5) / pieces
            self.arc(loop[k], loop[(k + 1) % pieces], pt(mid))
        return loop

    def write(self, name, mesh):
        doc = {"laytracks": "brep/1", "units": "mm", "vertices": self.vertices,
               "patches": self.patches, "mesh": mesh}
        if self.arcs:
            doc["arcs"] = self.arcs
        with open(os.path.join(OUT, name), "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")


def tray():
    """A moulded tray: a 120 x 80 floor, walls 20 high, and two crossing ribs 10 high.

    The ribs split the floor into four quadrants (each floor-rib edge is shared by three
    patches), they split each other at the crossing (a vertical edge shared by four patches),
    and they meet the walls, which are split at the rib's height. Two quadrants have round
    holes for screw bosses."""
    p = Part()
    L, W, H, R = 120.0, 80.0, 20.0, 10.0
    xm, ym = L / 2, W / 2
    v = p.v
    # Floor quadrants (z = 0), counter-clockwise seen from above.
    p.patch("floor_sw", [v(0, 0, 0), v(xm, 0, 0), v(xm, ym, 0), v(0, ym, 0)],
            p.circle((25, 20, 0), 5, ((1, 0, 0), (0, -1, 0))))
    p.patch("floor_se", [v(xm, 0, 0), v(L, 0, 0), v(L, ym, 0), v(xm, ym, 0)])
    p.patch("floor_ne", [v(xm, ym, 0), v(L, ym, 0), v(L, W, 0), v(xm, W, 0)],
            p.circle((95, 60, 0), 5, ((1, 0, 0), (0, -1, 0))))
    p.patch("floor_nw", [v(0, ym, 0), v(xm, ym, 0), v(xm, W, 0), v(0, W, 0)])
    # Ribs, split at the crossing.
    p.patch("rib_x_west", [v(0, ym, 0), v(xm, ym, 0), v(xm, ym, R), v(0, ym, R)])
    p.patch("rib_x_east", [v(xm, ym, 0), v(L, ym, 0), v(L, ym, R), v(xm, ym, R)])
    p.patch("rib_y_south", [v(xm, 0, 0), v(xm, ym, 0), v(xm, ym, R), v(xm, 0, R)])
    p.patch("rib_y_north", [v(xm, ym, 0), v(xm, W, 0), v(xm, W, R), v(xm, ym, R)])
    # Walls: each split where a rib meets it, below the rib's top, and one band above.
    p.patch("wall_south_w", [v(0, 0, 0), v(xm, 0, 0), v(xm, 0, R), v(0, 0, R)])
    p.patch("wall_south_e", [v(xm, 0, 0), v(L, 0, 0), v(L, 0, R), v(xm, 0, R)])
    p.patch("wall_south_top", [v(0, 0, R), v(xm, 0, R), v(L, 0, R), v(L, 0, H), v(0, 0, H)])
    p.patch("wall_east_s", [v(L, 0, 0), v(L, ym, 0), v(L, ym, R), v(L, 0, R)])
    p.patch("wall_east_n", [v(L, ym, 0), v(L, W, 0), v(L, W, R), v(L, ym, R)])
    p.patch("wall_east_top", [v(L, 0, R), v(L, ym, R), v(L, W, R), v(L, W, H), v(L, 0, H)])
    p.patch("wall_north_e", [v(L, W, 0), v(xm, W, 0), v(xm, W, R), v(L, W, R)])
    p.patch("wall_north_w", [v(xm, W, 0), v(0, W, 0), v(0, W, R), v(xm, W, R)])
    p.patch("wall_north_top", [v(L, W, R), v(xm, W, R), v(0, W, R), v(0, W, H), v(L, W, H)])
    p.patch("wall_west_n", [v(0, W, 0), v(0, ym, 0), v(0, ym, R), v(0, W, R)])
    p.patch("wall_west_s", [v(0, ym, 0), v(0, 0, 0), v(0, 0, R), v(0, ym, R)])
    p.patch("wall_west_top", [v(0, W, R), v(0, ym, R), v(0, 0, R), v(0, 0, H), v(0, W, H)])
    p.write("tray_ribs.json", {"size": 2.5})


def bracket():
    """An angle bracket: a 60 x 40 base with two bolt holes, an upright 50 high with a slot and
    rounded top corners, and a triangular gusset in the middle that splits both plates."""
    p = Part()
    v = p.v
    B, D, Hh, G = 60.0, 40.0, 50.0, 25.0  # base length, depth, upright height, gusset size
    ym = D / 2
    # Base (z = 0), split by the gusset's foot along y = 20.
    p.patch("base_front", [v(0, 0, 0), v(B, 0, 0), v(B, ym, 0), v(G, ym, 0), v(0, ym, 0)],
            p.circle((42, 10, 0), 4, ((1, 0, 0), (0, -1, 0))))
    p.patch("base_back", [v(0, ym, 0), v(G, ym, 0), v(B, ym, 0), v(B, D, 0), v(0, D, 0)],
            p.circle((42, 30, 0), 4, ((1, 0, 0), (0, -1, 0))))
    # Upright (x = 0): two panels below the gusset's top, one above with a slot and fillets.
    p.patch("upright_front", [v(0, 0, 0), v(0, ym, 0), v(0, ym, G), v(0, 0, G)])
    p.patch("upright_back", [v(0, ym, 0), v(0, D, 0), v(0, D, G), v(0, ym, G)])
    f = 6.0  # fillet radius at the top corners
    top = [v(0, 0, G), v(0, ym, G), v(0, D, G), v(0, D, Hh - f), v(0, D - f, Hh),
           v(0, f, Hh), v(0, 0, Hh - f)]
    s = math.sqrt(0.5)
    p.arc(v(0, D, Hh - f), v(0, D - f, Hh), (0, D - f + f * s, Hh - f + f * s))
    p.arc(v(0, f, Hh), v(0, 0, Hh - f), (0, f - f * s, Hh - f + f * s))
    # A slot: two half circles of radius 3 joined by straight sides, centres at y = 13 and 27.
    r, zc = 3.0, 38.0
    a, b, c, d = v(0, 13, zc - r), v(0, 27, zc - r), v(0, 27, zc + r), v(0, 13, zc + r)
    p.arc(b, c, (0, 27 + r, zc))
    p.arc(d, a, (0, 13 - r, zc))
    p.patch("upright_top", top, [a, d, c, b])
    # Gusset (y = 20).
    p.patch("gusset", [v(0, ym, 0), v(G, ym, 0), v(0, ym, G)])
    p.write("bracket.json", {"size": 2.0})


def cover():
    """A flat cover 100 x 70 with rounded corners, four boss holes and a rectangular window."""
    p = Part()
    v = p.v
    L, W, f = 100.0, 70.0, 8.0
    s = math.sqrt(0.5)
    outer = [v(f, 0, 0), v(L - f, 0, 0), v(L, f, 0), v(L, W - f, 0), v(L - f, W, 0),
             v(f, W, 0), v(0, W - f, 0), v(0, f, 0)]
    for (i, (cx, cy, ang)) in zip([1, 3, 5, 7], [(L - f, f, -45), (L - f, W - f, 45),
                                                   (f, W - f, 135), (f, f, -135)]):
        a = math.radians(ang)
        p.arc(outer[i], outer[(i + 1) % 8], (cx + f * math.cos(a), cy + f * math.sin(a), 0))
    holes = [p.circle((12 + dx, 12 + dy, 0), 3.5, ((1, 0, 0), (0, -1, 0)))
             for dx in (0, L - 24) for dy in (0, W - 24)]
    window = [v(35, 25, 0), v(35, 45, 0), v(65, 45, 0), v(65, 25, 0)]
    p.patch("cover", outer, *holes, window)
    p.write("cover_bosses.json", {"size": 2.0})


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    tray()
    bracket()
    cover()
