"""malformed parts: malformed.main(OUTDIR) writes OUTDIR/<name>.json and OUTDIR/expected.tsv
(name, what the refusal message should mention)."""
import json, os
SQ = [[0, 0, 0], [10, 0, 0], [10, 10, 0], [0, 10, 0]]
def part(vertices, patches, **kw):
    d = {"laytracks": "brep/1", "vertices": vertices, "patches": patches}
    d.update(kw)
    return d
def pl(*loops, name="plate"):
    return {"name": name, "loops": list(loops)}
CASES = []
def case(name, what, d):
    CASES.append((name, what, d))

# hole touching the outer loop at one point (hole vertex lies on outer edge 0-1)
case("hole_touches_outer_point", "loop 1 touches the outer loop near (5,0,0)",
     part(SQ + [[5, 0, 0], [6, 2, 0], [4, 2, 0]], [pl([0, 1, 2, 3], [4, 5, 6])]))
# hole shares a vertex index with the outer loop
case("hole_shares_outer_vertex", "loop 1 touches outer loop at vertex 1",
     part(SQ + [[8, 2, 0], [9, 3, 0]], [pl([0, 1, 2, 3], [1, 4, 5])]))
# two holes touching at a vertex
case("holes_touch_vertex", "loop 2 touches loop 1 at vertex 6",
     part(SQ + [[2, 2, 0], [4, 2, 0], [4, 4, 0], [6, 4, 0], [6, 6, 0], [2, 4, 0], [4, 6, 0]],
          [pl([0, 1, 2, 3], [4, 5, 6, 9], [6, 7, 8, 10])]))
# nested holes: hole 2 inside hole 1
case("hole_inside_hole", "loop 2 (a hole) lies inside loop 1 (a hole)",
     part(SQ + [[2, 2, 0], [8, 2, 0], [8, 8, 0], [2, 8, 0], [4, 4, 0], [6, 4, 0], [6, 6, 0], [4, 6, 0]],
          [pl([0, 1, 2, 3], [4, 5, 6, 7], [8, 9, 10, 11])]))
# a hole loop that crosses itself (bowtie hole)
case("hole_self_intersecting", "loop 1 crosses itself",
     part(SQ + [[2, 2, 0], [6, 6, 0], [6, 2, 0], [2, 6, 0]], [pl([0, 1, 2, 3], [4, 5, 6, 7])]))
# hole repeats a vertex
case("hole_repeats_vertex", "loop 1 repeats vertex 4",
     part(SQ + [[2, 2, 0], [6, 2, 0], [6, 6, 0], [2, 6, 0]], [pl([0, 1, 2, 3], [4, 5, 6, 4, 7])]))
# arc via equal to an endpoint
case("arc_via_is_endpoint", "arc 0 via point coincides with vertex 1",
     part(SQ, [pl([0, 1, 2, 3])], arcs=[{"from": 0, "to": 1, "via": [10, 0, 0]}]))
# two arcs on the same edge (opposite direction) with different via points
case("arc_conflicting", "edge 0-1 has two arcs (arc 0 and arc 1)",
     part(SQ, [pl([0, 1, 2, 3])], arcs=[{"from": 0, "to": 1, "via": [5, -2, 0]}, {"from": 1, "to": 0, "via": [5, -3, 0]}]))
# arc from == to
case("arc_from_equals_to", "arc 0 joins vertex 0 to itself",
     part(SQ, [pl([0, 1, 2, 3])], arcs=[{"from": 0, "to": 0, "via": [5, -2, 0]}]))
# arc index out of range
case("arc_index_out_of_range", "arcs[0].to 9 out of range",
     part(SQ, [pl([0, 1, 2, 3])], arcs=[{"from": 0, "to": 9, "via": [5, -2, 0]}]))
# arc bulging inward so far that it crosses the opposite edge (loop no longer simple)
case("arc_crosses_edge", "outer loop crosses itself (arc 0-1 and edge 2-3)",
     part([[0, 0, 0], [10, 0, 0], [10, 2, 0], [0, 2, 0]], [pl([0, 1, 2, 3])],
          arcs=[{"from": 0, "to": 1, "via": [5, 4, 0]}]))
# a hole's arc bulging out across the outer loop
case("hole_arc_crosses_outer", "loop 1 crosses the outer loop",
     part(SQ + [[2, 2, 0], [8, 2, 0], [8, 8, 0], [2, 8, 0]], [pl([0, 1, 2, 3], [4, 5, 6, 7])],
          arcs=[{"from": 4, "to": 5, "via": [5, -3, 0]}]))
# arc on a fold edge: via in the plane of patch 0 but not patch 1
case("arc_on_fold_off_plane", "via point off the plane of patch wall",
     part(SQ + [[10, 0, 5], [0, 0, 5]], [pl([0, 1, 2, 3], name="floor"), pl([0, 1, 4, 5], name="wall")],
          arcs=[{"from": 0, "to": 1, "via": [5, -2, 0]}]))
# rib vertex lies inside the plate edge in 3D (not coplanar), unsplit
case("unsplit_edge_3d", "vertex 4 lies on edge 2-3 of patch plate",
     part(SQ + [[5, 10, 0], [5, 10, 5], [0, 10, 5]], [pl([0, 1, 2, 3]), pl([3, 4, 5, 6], name="wall")]))
# bad mesh settings
case("mesh_mode_bad", "mesh.mode must be uniform or adaptive",
     part(SQ, [pl([0, 1, 2, 3])], mesh={"mode": "adaptve"}))
case("mesh_dtheta_negative", "mesh.dtheta_deg must be positive",
     part(SQ, [pl([0, 1, 2, 3])], mesh={"mode": "adaptive", "dtheta_deg": -5}))
case("mesh_dtheta_zero", "mesh.dtheta_deg must be positive",
     part(SQ, [pl([0, 1, 2, 3])], mesh={"mode": "adaptive", "dtheta_deg": 0}))
case("mesh_size_string", "mesh.size expected a number",
     part(SQ, [pl([0, 1, 2, 3])], mesh={"size": "2"}))
case("mesh_unknown_key", "unknown key in mesh",
     part(SQ, [pl([0, 1, 2, 3])], mesh={"sise": 2}))
case("units_number", "units expected a string",
     part(SQ, [pl([0, 1, 2, 3])], units=25.4))
case("name_number", "patches[0].name expected a string",
     part(SQ, [{"name": 3, "loops": [[0, 1, 2, 3]]}]))
case("patches_empty", "at least one patch",
     part(SQ, []))
case("loops_empty", "patches[0].loops is empty",
     part(SQ, [{"loops": []}]))
case("index_fractional", "vertex index 1.5 is not an integer",
     part(SQ, [pl([0, 1.5, 2, 3])]))
case("coordinate_string", "expected a number for vertices[1][0]",
     part([[0, 0, 0], ["10", 0, 0], [10, 10, 0], [0, 10, 0]], [pl([0, 1, 2, 3])]))
case("dual_graph_self", "dual_graph pair [0,0]",
     part(SQ, [pl([0, 1, 2, 3])], dual_graph=[[0, 0]]))
case("dual_graph_out_of_range", "dual_graph patch index 5 out of range",
     part(SQ, [pl([0, 1, 2, 3])], dual_graph=[[0, 5]]))
case("patch_unknown_key", "unknown key 'loop' in patches[0]",
     part(SQ, [{"name": "p", "loop": [[0, 1, 2, 3]]}]))
case("arc_missing_via", "arcs[0] missing via",
     part(SQ, [pl([0, 1, 2, 3])], arcs=[{"from": 0, "to": 1}]))
# same edge used twice in one patch: outer loop and hole share edge 1-2 (touching loops)
case("hole_shares_outer_edge", "loop 1 touches outer loop along edge 1-2",
     part(SQ + [[8, 5, 0]], [pl([0, 1, 2, 3], [1, 2, 4])]))
# a patch whose outer loop is only 2 distinct points after an arc, with 3 points collinear + arc: fine, skip
# zero-length-ish edge: two vertices 1e-14 apart
case("vertices_nearly_coincide", "vertices 1 and 4 coincide",
     part(SQ + [[10, 1e-14, 0]], [pl([0, 1, 4, 2, 3])]))

# vertex of a wall lies on the ARC edge of the plate (on the curve, not the chord), unsplit
import math as _m
case("unsplit_arc_edge", "vertex 4 lies on arc edge 0-1 of patch plate but edge not split",
     part(SQ + [[5, -2, 0], [5, -2, 5], [0, 0, 5]], [pl([0, 1, 2, 3]), pl([0, 4, 5, 6], name="wall")],
          arcs=[{"from": 0, "to": 1, "via": [5, -2, 0]}]))
# vertex of one patch on a HOLE edge of another patch, unsplit
case("unsplit_hole_edge", "vertex 8 lies on edge 4-5 of patch plate (a hole edge)",
     part(SQ + [[2, 2, 0], [8, 2, 0], [8, 8, 0], [2, 8, 0], [5, 2, 0], [5, 2, 4], [2, 2, 4]],
          [pl([0, 1, 2, 3], [4, 7, 6, 5]), pl([4, 8, 9, 10], name="tube")]))
# vertex on another patch's edge, 1e-12 off it (should still count as on the edge)
case("unsplit_edge_near", "vertex 4 lies on edge 2-3 of patch plate (within tolerance)",
     part(SQ + [[5, 10 + 1e-12, 0], [5, 10, 5], [0, 10, 5]], [pl([0, 1, 2, 3]), pl([3, 4, 5, 6], name="wall")]))
# outer loop passes through one of its own vertices (vertex 4 lies on edge 0-1)
case("loop_vertex_on_own_edge", "outer loop touches itself at vertex 4",
     part([[0, 0, 0], [10, 0, 0], [10, 10, 0], [5, 5, 0], [5, 0, 0], [0, 10, 0]], [pl([0, 1, 2, 3, 4, 3 + 2])]))
# zero-area hole (collinear)
case("hole_collinear", "loop 1 (a hole) is degenerate",
     part(SQ + [[2, 2, 0], [4, 2, 0], [6, 2, 0]], [pl([0, 1, 2, 3], [4, 5, 6])]))
# hole with 2 vertices
case("hole_two_vertices", "loop 1 has only 2 vertices",
     part(SQ + [[2, 2, 0], [4, 4, 0]], [pl([0, 1, 2, 3], [4, 5])]))
# NaN literal
RAW_EXTRA = [("nan_literal", "malformed JSON NaN",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[NaN,0,0],[1,1,0],[0,1,0]],\n "patches": [{"loops": [[0,1,2,3]]}]}\n'),
    ("huge_index", "vertex index 1e20 out of range",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"loops": [[0,1,2,100000000000000000000]]}]}\n'),
    ("index_as_float_int", "1.0 as a vertex index (accept or refuse clearly)",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"loops": [[0,1,2,3.0]]}]}\n'),
    ("bad_utf8", "invalid UTF-8 in a name",
     b'{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"name": "\xff\xfe", "loops": [[0,1,2,3]]}]}\n'.decode('latin1')),
    ("unterminated_string", "unterminated string",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"name": "abc, "loops": [[0,1,2,3]]}]}\n'),
]
# two coplanar patches overlapping (not sharing an edge)
case("coplanar_overlap", "patches 0 and 1 overlap (questionable: not a listed rule)",
     part(SQ + [[5, 5, 0], [15, 5, 0], [15, 15, 0], [5, 15, 0]], [pl([0, 1, 2, 3]), pl([4, 5, 6, 7], name="p2")]))
# a rib piercing a plate interior (patches intersect without sharing an edge)
case("rib_pierces_plate", "patches intersect (questionable: not a listed rule)",
     part(SQ + [[2, 5, -3], [8, 5, -3], [8, 5, 3], [2, 5, 3]], [pl([0, 1, 2, 3]), pl([4, 5, 6, 7], name="rib")]))
# a rib whose bottom edge lies in the interior of a plate (no shared edge, touches the face)
case("rib_on_plate_interior", "rib touches plate interior along a line (questionable: not a listed rule)",
     part(SQ + [[2, 5, 0], [8, 5, 0], [8, 5, 3], [2, 5, 3]], [pl([0, 1, 2, 3]), pl([4, 5, 6, 7], name="rib")]))
# vertex of one patch touching the interior of another patch's face at a point
case("vertex_on_plate_interior", "vertex 4 of tri touches plate interior (questionable)",
     part(SQ + [[5, 5, 0], [6, 5, 3], [4, 5, 3]], [pl([0, 1, 2, 3]), pl([4, 5, 6], name="tri")]))
# text-level malformations (raw strings)
RAW = [
    ("duplicate_key", "duplicate key \"vertices\"",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0]], "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"loops": [[0,1,2,3]]}]}\n'),
    ("trailing_garbage", "unexpected text after the JSON value",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],\n "patches": [{"loops": [[0,1,2,3]]}]} x\n'),
    ("empty_file", "empty / malformed JSON", ''),
    ("root_array", "expected an object at the root", '[1,2,3]\n'),
    ("trailing_comma", "malformed JSON at 2:30",
     '{"laytracks": "brep/1", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],],\n "patches": [{"loops": [[0,1,2,3]]}]}\n'),
]

def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, "expected.tsv"), "w") as t:
        for name, what, d in CASES:
            with open(os.path.join(outdir, name + ".json"), "w") as f:
                json.dump(d, f, indent=1)
            t.write("%s.json\t%s\n" % (name, what))
        for name, what, s in RAW + RAW_EXTRA:
            with open(os.path.join(outdir, name + ".json"), "w", encoding="latin1") as f:
                f.write(s)
            t.write("%s.json\t%s\n" % (name, what))
