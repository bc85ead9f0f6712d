// The quad stage. Rules (docs/mesher.md):
// 1. Boundary: every B-Rep edge is cut at its G-CUT-VERTs into pieces; a piece gets one mesh
//    edge, or round(length / h) when longer than kSplitPiece x h. Pieces are per B-Rep edge, so
//    every patch of an edge sees the same nodes (conformity across seams and junctions).
//    A G-CUT-VERT that no kept rail uses and that lies within kIdleBreakGap x h of the next
//    break or end of its edge is not a node (no sliver piece beside a B-Rep vertex).
// 2. Rails: a rail segment (CUT-VERT to MA point) of length R gets max(1, round(R / h)) edges
//    (Eq. 2-3; both halves of a rail have the same length, so the same count).
// 3. Faces: each patch, cut by its rails, falls into faces (half-edges traced with the face on
//    the left). A face needs an even number of boundary edges to be all quads (Eq. 5).
// 4. Parity: per shell, boundary pieces get one more edge where a patch's boundary count is odd
//    (a spanning tree over patches joined by shared pieces, free pieces joined to a ground
//    node); then per patch, odd faces are paired along the shortest path of rails between
//    them, each rail on it getting one more edge. Both keep every count local to where it was
//    odd; no global subdivision.
// 5. Each face is filled by the first template that gives good quads (fill.hpp).
#include "laytracks/mesher/build_quads.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "fill.hpp"
#include "laytracks/brep/error.hpp"
#include "laytracks/brep/polygon.hpp"
#include "laytracks/brep/union_find.hpp"
#include "laytracks/cutgraph/adaptive.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
/// A face given the moved quads of an earlier one keeps them when their worst corner is at
/// most this below the source's (rounding in the motion; a larger loss means the shapes
/// differ where the tolerance did not see it, and the face is filled anew).
constexpr double kSharedFaceSlack = 1e-6;
/// set_small_face_sharing's switch.
std::atomic<bool> g_small_face_sharing{true};
/// fill_patches fills the faces of at most this many nodes before the others.
constexpr std::size_t kSmallFaceFirst = 16;
/// A boundary piece longer than this x h is split into round(length / h) mesh edges.
constexpr double kSplitPiece = 2.0;
/// Lengths are compared with h this much below their exact value (relative), so that a length
/// of exactly 1.5 h gives the same count in every pose, whatever its rounding; the same slack
/// (x h) on the fan rules' length bounds (a hole's corner exactly kMaxWedgeFeet h from
/// another's, when that was 0.5: holes__rect_near_g0.5).
constexpr double kRoundingSlack = 1e-7;
/// A G-CUT-VERT within this x the part size of another break of its edge (or of the edge's
/// end) is that node: ten times above the checker's closest allowed nodes.
constexpr double kMergeBreakRel = 1e-8;
/// A G-CUT-VERT that no kept rail uses in any patch of its edge (its rails were dropped as a
/// narrow fan or wedge, or dangled) is not a node when it lies closer than this x the local
/// element size to the next break or end of its edge: it would leave a piece as short, and a
/// quad with a flat corner at the B-Rep vertex beside it (cgal_sample_0: 0.013). Farther ones
/// stay: merged with their neighbours' pieces, pieces of about h became single edges of 2 h.
constexpr double kIdleBreakGap = 0.1;
/// Breaks closer than this x the element size to the previous break or the edge's end are one
/// node, used or not (a piece of 0.002 h on a hole left a face no template could fill).
constexpr double kTinyPiece = 0.01;
/// A break closer than this x the local element size to an end of its edge (or arc) where the
/// boundary is tangent-continuous in every loop through it (a fillet's tangent point, the joint
/// of two arcs of one circle) is that vertex's node: the rail's foot moves onto the vertex, by
/// at most a tenth of an element along a boundary that is straight to first order there. Left
/// off it, the piece between was a quad edge of a tenth of the others, and the quad had a
/// nearly flat corner at the vertex or a sliver beside it (docs/mesher.md, "Smooth vertices").
constexpr double kTinyEndPiece = 0.1;
/// drop_disk_rails: at least this many rails, no two neighbours round the centre further apart
/// than kDiskGap (a regular hexagon's six rails stay: its wedges are good quads).
constexpr std::size_t kDiskRails = 8;
constexpr double kDiskGap = 60.0 * kPi / 180.0;
/// hub_nodes: at least this many rails, no two neighbours round the node further apart than
/// kHubGap (a five-pointed star's centre: five rails 72 degrees apart). Whether a hub's rails
/// go is decided by the meshes with and without them (mesh_part), so the bounds only say
/// where a second mesh is worth making.
constexpr std::size_t kHubRails = 5;
constexpr double kHubGap = 75.0 * kPi / 180.0;
/// drop_disk_rails on a nearly round loop: the rails' MA ends all within this x the shortest
/// rail of their centroid, and the loop round (mesher_detail::is_round, the O-grid's test).
constexpr double kDiskSpread = 0.1;
/// drop_sliver_caps: a cap face thinner than this (twice its area over its perimeter squared)
/// loses its rails. The fuzzed needles that no template filled were at 1.5e-5 to 8.2e-4; at
/// 1e-2 ten of the 402 set meshes changed (faceted cylinders' thin facets, an arc's base), at
/// 1e-3 none.
constexpr double kSliverCap = 1e-3;
/// drop_slit_rails and drop_sliver_caps: at most this many rounds of dropping and tracing the
/// faces again per patch.
constexpr int kSlitRounds = 4;
/// flip_edges: pairs of quads whose worse is below kFlipBelow are re-split when another
/// diagonal of their hexagon beats it by kFlipGain; at most kFlipPasses passes.
constexpr double kFlipBelow = 0.3;
constexpr double kFlipGain = 0.05;
constexpr int kFlipPasses = 4;
/// Two rails from one boundary node closer in angle than this are not both kept (10 degrees:
/// the quad at their tip would have a scaled Jacobian below sin 10 = 0.17).
constexpr double kMinFanAngle = 10.0 * kPi / 180.0;
/// At a reflex corner (an interior angle above kReflexFanCorner) two neighbouring rails both no
/// longer than kShortFanRail x h are not both kept closer than kMinReflexFanAngle: the corner's
/// quads get corners of 25 degrees or more, not ten (l_shape 0.707 -> 0.973).
constexpr double kReflexFanCorner = 200.0 * kPi / 180.0;
constexpr double kMinReflexFanAngle = 25.0 * kPi / 180.0;
constexpr double kShortFanRail = 6.0;
/// Angles (radians) this close are alike when a reflex corner's fan is thinned.
constexpr double kAngleTie = 1e-9;
/// Adaptive mode: the track widths beside a rail's foot count in Eq. (2) within this factor
/// of the width law's there.
constexpr double kFootWidthBound = 2.0;
/// The same at an MA point: two rails closer than kMinWedgeAngle whose feet are closer than
/// kMaxWedgeFeet x h bound a wedge that is one column of quads, each narrowing to the apex,
/// whose apex quad is as thin as its angle. Session 4 chose 15 degrees and half an element
/// (cgal_complex_1 0.18 -> 0.34 against 10 degrees). Session 30: 20 degrees and 1.25 h, so
/// that a fillet's fan of short rails (4 h long, feet h apart, 14.6 or 18.4 degrees) loses
/// every other rail: of the 402 set meshes 25 changed, worst corner higher on 10
/// (holes__fillets 0.751 -> 0.862, cbracket__s7 0.750 -> 0.793), lower on 1 by 0.009; the
/// wiggly's long converging rails (feet 1.9-3.7 h apart) keep theirs. Without the bound on
/// the feet (session 29) they were thinned too, into bent slivers (aspect >= 5 0.10% -> 0.32%).
constexpr double kMinWedgeAngle = 20.0 * kPi / 180.0;
constexpr double kMaxWedgeFeet = 1.25;
/// A wedge at an MA point thinner than this goes whatever its feet (session 15): long rails
/// converging at the axis from far-apart feet (cgal_wiggly_03_cgal's teeth, 1-2 degrees apart)
/// made wedges whose apex quads were 0.03; the face their dropped rail leaves is wide, and the
/// lattice template fills such faces with quads of the edge size.
constexpr double kThinWedgeAngle = 10.0 * kPi / 180.0;
/// Adaptive mode (session 29): any wedge at an MA point below kMinWedgeAngle goes, whatever
/// its feet (h there is the least track width, so the feet are nearly always "far"):
/// adaptive cgal_complex_1 0.193 -> 0.489.
/// Round fans (drop_narrow_fans): at least kRoundFanRails rails at one MA point, at most
/// kRoundFanOpenGaps wedges between them not capped by plain boundary; they are thinned to
/// wedges of at most kRoundFanAngle (thin_round_fan): a quarter arc's run (90 degrees) is one
/// wedge, whose apex is one quad's corner; a half arc's two. Off round values, so that no
/// run's angle sits on a multiple of it. Session 8 chose 40 degrees among 30 to 50 (30 and 35
/// left a keyhole's round tip at 0.256 and 0.540); a fillet's run of 74 degrees then kept two
/// wedges of 37 degrees, each split into kites (a rounded rectangle with fillets of 4.5 h:
/// taper <= 0.8 40.9%, worst 0.700); as one wedge 18.8% and 0.829 (docs/mesher.md, "Round
/// fans").
constexpr std::size_t kRoundFanRails = 6;
constexpr std::size_t kRoundFanOpenGaps = 2;
constexpr double kRoundFanAngle = 100.0 * kPi / 180.0;
/// drop_crowded_feet: neighbouring rail feet on a concave arc closer than this x the element
/// size are not both kept; gaps equal within kFootTie x the part's size are alike.
constexpr double kMinArcFoot = 0.65;
/// Rings round a round hole (graded_rail): the largest ratio of a ring's outer radius to its
/// inner one. A ring of radial quads between radii r and q r is a ring of trapezoids whose
/// parallel sides differ by q, with taper (quality.md) 2 / (1 + q): 0.83 at q = 1.4, 0.8 at
/// 1.5. Ratios within kRingTie of it (relative) count as equal to it in every pose.
constexpr double kRingRatio = 1.4;
constexpr double kRingTie = 1e-9;
/// Graded rails only round a hole whose longest mesh edge is at most this x the first ring's
/// width (kRingRatio - 1) r0: the ring's quads no flatter than that.
constexpr double kRingAspect = 2.0;
constexpr double kFootTie = 1e-9;
/// Two MA points of a patch closer than this x h (in adaptive mode h is MIN_END_WIDTH, the
/// finest track) are one node.
constexpr double kMergeMaPoints = 1e-3;
/// merge_fan_clusters: MA nodes of radius >= kFanMinRadius x h within kFanCluster x h of a
/// deeper one are merged into it.
constexpr double kFanCluster = 0.25;
/// ... and within kFanClusterArc x h when the rails of both start on arcs (an arc's own fan;
/// an obround strap's slot: 0.461 -> 0.753; for every cluster it spoiled cgal_wiggly_03_cgal).
constexpr double kFanClusterArc = 0.35;
constexpr double kFanMinRadius = 2.0;
/// Two MA points of a patch closer than this x the part size are one node.
constexpr double kSamePointRel = 1e-9;
/// unfold_darts: a corner is taken as turning (reflex, or convex in the kite) only when the
/// sine of its turn is beyond this: a straight one reads alike in every pose.
constexpr double kDartTurn = 1e-9;

/// Nodes of one B-Rep edge: breaks (its vertices and its G-CUT-VERTs, by parameter) and the
/// pieces between consecutive breaks.
struct EdgeNodes {
  std::vector<double> t;                        ///< break parameters, 0 and 1 included
  std::vector<std::uint32_t> node;              ///< mesh node of each break
  std::vector<std::uint32_t> count;             ///< mesh edges per piece
  std::vector<std::vector<std::uint32_t>> inner;  ///< per piece, its inner nodes from t[j] on
};

struct CNode {  // a node of a patch's coarse graph
  Vec2 p;
  std::uint32_t mesh = kNone;  ///< for boundary nodes; MA nodes get theirs when materialised
  bool ma = false;
};

struct CEdge {
  std::uint32_t a = 0, b = 0;  ///< boundary: along the loop; rail: from the cut to the MA point
  bool rail = false;
  std::uint32_t edge = 0;      ///< boundary: the unit (a straight B-Rep edge, or an arc)
  std::uint32_t piece = 0;     ///< boundary: its piece on that edge
  bool forward = true;         ///< boundary: loop direction = unit direction
  std::uint32_t count = 1;     ///< rail: mesh edges
  std::uint32_t seg = kNone;   ///< rail: its RailSegment in the cut graph
  std::vector<std::uint32_t> inner;  ///< rail: inner nodes from a to b
  std::uint32_t face[2] = {kNone, kNone};  ///< faces on the left of a->b and of b->a
};

struct Half {
  std::uint32_t edge;
  bool reverse;  ///< traversed b -> a
};

struct PatchGraph {
  std::vector<CNode> nodes;
  std::vector<CEdge> edges;
  std::vector<std::vector<Half>> faces;
  std::map<std::uint32_t, Vec2> boundary_2d;  ///< mesh node -> position in the patch frame
  std::map<std::uint32_t, BoundaryPoint> foot;  ///< adaptive: coarse node of a rail's foot
};

/// Erases the edges marked in `drop` (one flag per edge, in order).
void erase_marked(std::vector<CEdge>& edges, const std::vector<bool>& drop) {
  std::size_t k = 0;
  edges.erase(std::remove_if(edges.begin(), edges.end(), [&](const CEdge&) { return drop[k++]; }),
              edges.end());
}

class QuadBuilder {
 public:
  QuadBuilder(const Part& part, const CutGraph& graph, const QuadOptions& options)
      : part_(part),
        graph_(graph),
        h_(options.size),
        law_(options.adaptive),
        sliver_caps_(options.drop_sliver_caps),
        needle_tips_(options.needle_tips),
        face_memo_(options.face_memo),
        split_pieces_(options.split_pieces),
        drop_hubs_(options.drop_hubs) {
    if (!(h_ > 0.0) && !law_) throw InternalError("mesher: the element size must be positive");
  }

  QuadResult run() {
    // First pass: every G-CUT-VERT is a break; the rails are laid and the narrow-fan,
    // narrow-wedge and dangling rules drop some. A break that no kept rail uses, in any patch
    // of its edge, and that lies closer than kIdleBreakGap x h to a neighbouring break or to
    // the edge's end, only leaves a sliver piece: the second pass lays the nodes without it,
    // and only the rails the first pass kept (the same in both, so conformity and the rails
    // of every other patch are untouched).
    make_boundary_nodes({});
    const std::size_t np = part_.patches.size();
    patches_.assign(np, {});
    for (std::size_t p = 0; p < np; ++p) build_patch_rails(PatchId(p), nullptr);
    std::vector<bool> kept(graph_.segments.size(), false);
    std::vector<bool> used_node(result_.mesh.nodes.size(), false);
    for (const PatchGraph& g : patches_) {
      for (const CEdge& c : g.edges) {
        if (!c.rail) continue;
        kept[c.seg] = true;
        used_node[g.nodes[c.a].mesh] = true;
      }
    }
    // Per break node: the distance to the nearer of its neighbouring breaks (or the unit's
    // ends), over the local element size.
    std::vector<double> gap(result_.mesh.nodes.size(), 0.0);
    for (std::size_t u = 0; u < edges_.size(); ++u) {
      const EdgeNodes& en = edges_[u];
      const double len = unit_length(u);
      for (std::size_t j = 1; j + 1 < en.node.size(); ++j) {
        const double near = std::min(en.t[j] - en.t[j - 1], en.t[j + 1] - en.t[j]) * len;
        gap[en.node[j]] = near / local_size(u, en.t[j]);
      }
    }
    std::vector<bool> unused(graph_.gverts.size(), false);
    bool any = false;
    for (std::size_t gv = 0; gv < graph_.gverts.size(); ++gv) {
      const std::uint32_t node = gcut_node_[gv];
      if (node != kNone && !used_node[node] && !is_vertex_node_[node] &&
          gap[node] < kIdleBreakGap) {
        unused[gv] = any = true;
      }
    }
    if (any) {
      result_.mesh.nodes.clear();
      make_boundary_nodes(unused);
      patches_.assign(np, {});
      for (std::size_t p = 0; p < np; ++p) build_patch_rails(PatchId(p), &kept);
    }
    for (std::size_t p = 0; p < np; ++p) {
      if (law_) adaptive_rail_counts(PatchId(p), patches_[p]);
      drop_outward_rails(patches_[p]);
      if (needle_tips_) drop_crossing_rails(patches_[p]);
      bridge_loose_loops(patches_[p]);
      trace_faces(PatchId(p), patches_[p]);
      // Each round drops rails for good, but bridging may add rails back: a few rounds.
      for (int round = 0; round < kSlitRounds && (drop_slit_rails(patches_[p]) ||
                                                  (sliver_caps_ && drop_sliver_caps(patches_[p])));
           ++round) {
        bridge_loose_loops(patches_[p]);
        trace_faces(PatchId(p), patches_[p]);
      }
    }
    for (std::size_t p = 0; p < np; ++p)
      if (!hub_nodes(patches_[p]).empty()) result_.hubs.push_back(static_cast<std::uint32_t>(p));
    fix_parity();
    for (std::size_t p = 0; p < np; ++p) unfold_darts(patches_[p]);
    // Split boundary pieces (mesh_part, after an UnfilledFace): two more edges each, which
    // keeps every face at the piece even, in every patch of its edge.
    for (const PieceRef& s : split_pieces_)
      if (s.unit < edges_.size() && s.piece < edges_[s.unit].count.size())
        edges_[s.unit].count[s.piece] += 2;
    materialise_pieces();
    fill_patches();
    return std::move(result_);
  }

 private:
  std::uint32_t add_node(Vec3 x) {
    result_.mesh.nodes.push_back(x);
    return static_cast<std::uint32_t>(result_.mesh.nodes.size() - 1);
  }

  // ---- 1. boundary nodes ----------------------------------------------------------------
  /// `skip`: G-CUT-VERTs left out (idle breaks: no kept rail, within kIdleBreakGap x h of a
  /// neighbour), empty for none.
  void make_boundary_nodes(const std::vector<bool>& skip) {
    result_.stats.smooth_vertex_feet = 0;  // counted by the last call
    // Units: every straight B-Rep edge is one; every arc (all the edges that discretise it) is
    // one, with its nodes on the circle and no node at its discretisation points.
    const std::size_t ne = part_.edges.size();
    unit_of_edge_.assign(ne, 0);
    units_.clear();
    std::vector<std::uint32_t> unit_of_arc(part_.arcs.size(), kNone);
    for (std::size_t e = 0; e < ne; ++e) {
      const BrepEdge& edge = part_.edges[e];
      if (edge.arc < 0) {
        unit_of_edge_[e] = static_cast<std::uint32_t>(units_.size());
        units_.push_back({-1, EdgeId(e), edge.a, edge.b});
        continue;
      }
      const auto arc = static_cast<std::size_t>(edge.arc);
      if (unit_of_arc[arc] == kNone) {
        unit_of_arc[arc] = static_cast<std::uint32_t>(units_.size());
        units_.push_back({edge.arc, EdgeId(e), part_.arcs[arc].from, part_.arcs[arc].to});
      }
      unit_of_edge_[e] = unit_of_arc[arc];
    }
    // Position of a discretisation point along its arc: index / segments.
    std::map<std::uint32_t, std::pair<std::uint32_t, double>> arc_point;  // vertex -> (unit, u)
    for (std::size_t a = 0; a < part_.arcs.size(); ++a) {
      const PartArc& arc = part_.arcs[a];
      const double n = static_cast<double>(arc.points.size() + 1);
      for (std::size_t k = 0; k < arc.points.size(); ++k)
        arc_point[arc.points[k].value] = {unit_of_arc[a], static_cast<double>(k + 1) / n};
    }
    auto arc_u = [&](const PartArc& arc, VertexId v) {
      if (v == arc.from) return 0.0;
      if (v == arc.to) return 1.0;
      return arc_point.at(v.value).second;
    };
    arc_edges_.assign(part_.arcs.size(), {});
    for (std::size_t e = 0; e < ne; ++e) {
      const BrepEdge& edge = part_.edges[e];
      if (edge.arc < 0) continue;
      const PartArc& arc = part_.arcs[static_cast<std::size_t>(edge.arc)];
      arc_edges_[static_cast<std::size_t>(edge.arc)].push_back(
          {arc_u(arc, edge.a), arc_u(arc, edge.b), EdgeId(e)});
    }
    vertex_node_.assign(part_.vertices.size(), kNone);
    for (const Patch& patch : part_.patches)
      for (const Loop& loop : patch.loops)
        for (VertexId v : loop.vertices)
          if (vertex_node_[v.index()] == kNone && !part_.vertices[v.index()].from_arc)
            vertex_node_[v.index()] = add_node(part_.vertices[v.index()].position);
    // A vertex where the boundary is tangent-continuous in every loop through it (an arc's
    // joint with a line or another arc): a rail foot this close to it is better on it. The
    // same for both calls: found once.
    if (smooth_vertex_.empty()) {
      smooth_vertex_.assign(part_.vertices.size(), 1);
      for (const Patch& patch : part_.patches)
        for (std::size_t l = 0; l < patch.loops.size(); ++l)
          for (std::size_t i = 0; i < patch.loops[l].vertices.size(); ++i)
            if (!patch.polygon.smooth[l][i]) smooth_vertex_[patch.loops[l].vertices[i].index()] = 0;
    }
    std::vector<std::vector<std::pair<double, std::uint32_t>>> breaks(units_.size());
    gcut_node_.assign(graph_.gverts.size(), kNone);
    for (std::size_t g = 0; g < graph_.gverts.size(); ++g) {
      const GCutVert& gv = graph_.gverts[g];
      const auto gid = static_cast<std::uint32_t>(g);
      if (!skip.empty() && skip[g]) continue;
      if (gv.vertex && !part_.vertices[gv.vertex->index()].from_arc) {
        gcut_node_[g] = vertex_node_[gv.vertex->index()];
        continue;
      }
      if (gv.vertex) {  // a discretisation point of an arc: a break of the arc like any other
        const auto& [unit, u] = arc_point.at(gv.vertex->value);
        breaks[unit].push_back({u, gid});
        continue;
      }
      const std::uint32_t unit = unit_of_edge_[gv.edge.index()];
      const Unit& un = units_[unit];
      if (un.arc < 0) {
        breaks[unit].push_back({gv.t, gid});
      } else {
        const PartArc& arc = part_.arcs[static_cast<std::size_t>(un.arc)];
        const BrepEdge& edge = part_.edges[gv.edge.index()];
        const double ua = arc_u(arc, edge.a), ub = arc_u(arc, edge.b);
        breaks[unit].push_back({ua + (ub - ua) * gv.t, gid});
      }
    }
    edges_.assign(units_.size(), {});
    is_vertex_node_.assign(result_.mesh.nodes.size(), true);
    for (std::size_t e = 0; e < units_.size(); ++e) {
      const Unit& un = units_[e];
      EdgeNodes& en = edges_[e];
      auto& br = breaks[e];
      std::sort(br.begin(), br.end());
      en.t.push_back(0.0);
      en.node.push_back(vertex_node_[un.a.index()]);
      const double len = unit_length(e);
      for (const auto& [t, g] : br) {
        // A break at (or within rounding of) the previous break or the edge's end is that node,
        // and so is one closer than kTinyPiece x the element size: no quad fits such a piece.
        const double merge =
            std::max(kMergeBreakRel * part_.size, kTinyPiece * local_size(e, t));
        const double merge_end =
            std::max(kMergeBreakRel * part_.size, kTinyEndPiece * local_size(e, t));
        const double merge_a = smooth_vertex_[un.a.index()] ? merge_end : merge;
        const double merge_b = smooth_vertex_[un.b.index()] ? merge_end : merge;
        const double from_prev = (t - en.t.back()) * len;
        if (from_prev <= (en.t.size() == 1 ? merge_a : merge)) {
          if (from_prev > merge) ++result_.stats.smooth_vertex_feet;
          gcut_node_[g] = en.node.back();
          continue;
        }
        if ((1.0 - t) * len <= merge_b) {
          if ((1.0 - t) * len > merge) ++result_.stats.smooth_vertex_feet;
          gcut_node_[g] = vertex_node_[un.b.index()];
          continue;
        }
        en.t.push_back(t);
        en.node.push_back(add_node(unit_point(e, t)));
        is_vertex_node_.push_back(false);
        gcut_node_[g] = en.node.back();
      }
      en.t.push_back(1.0);
      en.node.push_back(vertex_node_[un.b.index()]);
      for (std::size_t j = 0; j + 1 < en.t.size(); ++j) {
        const double piece = (en.t[j + 1] - en.t[j]) * len;
        const double h = local_size(e, 0.5 * (en.t[j] + en.t[j + 1]));
        std::uint32_t count =
            piece > (kSplitPiece + kRoundingSlack) * h ? edges_for(piece, h) : 1u;
        if (un.arc >= 0) {  // chords within the chord tolerance
          const PartArc& arc = part_.arcs[static_cast<std::size_t>(un.arc)];
          const double angle = (en.t[j + 1] - en.t[j]) * arc.span;
          const double step = max_chord_angle(arc.radius, part_.chord_tol);
          count = std::max(count, static_cast<std::uint32_t>(std::ceil(angle / step - 1e-9)));
        }
        en.count.push_back(count);
      }
      en.inner.resize(en.count.size());
    }
  }

  /// Length of a unit: its chord, or its arc.
  double unit_length(std::size_t u) const {
    const Unit& un = units_[u];
    if (un.arc < 0)
      return distance(part_.vertices[un.a.index()].position, part_.vertices[un.b.index()].position);
    const PartArc& arc = part_.arcs[static_cast<std::size_t>(un.arc)];
    return arc.radius * arc.span;
  }
  /// The length of a boundary piece (along its unit: straight, or along the arc).
  double piece_length(const CEdge& c) const {
    const EdgeNodes& en = edges_[c.edge];
    return (en.t[c.piece + 1] - en.t[c.piece]) * unit_length(c.edge);
  }

  /// The round hole a boundary piece of patch pid lies on: its circle's index in
  /// CutGraph::round_arcs (a concave circle mapped along rays), or -1 (a rail, a straight
  /// piece, another arc, or a cut graph made by hand without round_arcs).
  std::int32_t round_circle(PatchId pid, const CEdge& c) const {
    const auto arc = units_[c.edge].arc;
    if (c.rail || arc < 0 || pid.index() >= graph_.round_arcs.size()) return -1;
    return graph_.round_arcs[pid.index()][static_cast<std::size_t>(arc)];
  }

  /// The point at parameter t of a unit (from its a to its b).
  Vec3 unit_point(std::size_t u, double t) const {
    const Unit& un = units_[u];
    if (un.arc < 0)
      return lerp3(part_.vertices[un.a.index()].position, part_.vertices[un.b.index()].position, t);
    return part_.arcs[static_cast<std::size_t>(un.arc)].at(t);
  }


  static Vec3 lerp3(Vec3 a, Vec3 b, double t) { return a + t * (b - a); }

  /// The element size at parameter t of a unit: h, or in adaptive mode the track width there
  /// (for an arc, on the discretisation edge under that parameter).
  double local_size(std::size_t u, double t) const {
    if (!law_) return h_;
    const Unit& un = units_[u];
    if (un.arc < 0) return law_->width_on_edge(un.edge, t);
    for (const auto& [ua, ub, e] : arc_edges_[static_cast<std::size_t>(un.arc)]) {
      const double lo = std::min(ua, ub), hi = std::max(ua, ub);
      if (t >= lo && t <= hi && hi > lo) return law_->width_on_edge(e, (t - ua) / (ub - ua));
    }
    return law_->end_width();
  }

  /// Mesh edges for a length: round(length / h), at least 1, halves rounded down whatever the
  /// last bits of the length (so every pose of a part gets the same counts).
  std::uint32_t edges_for(double length) const { return edges_for(length, h_); }
  static std::uint32_t edges_for(double length, double h) {
    const double x = length / h;
    return std::max<std::uint32_t>(1, static_cast<std::uint32_t>(std::floor(x + 0.5 - kRoundingSlack)));
  }

  // ---- 2-3. the coarse graph and its faces ------------------------------------------------
  /// The rail segments whose CUT-VERT is in patch pid, ascending (bucketed once: a scan of
  /// all of them per patch was quadratic in a shell of many facets).
  const std::vector<std::uint32_t>& segments_in(PatchId pid) {
    if (segments_by_patch_.empty()) {
      segments_by_patch_.resize(part_.patches.size());
      for (std::size_t si = 0; si < graph_.segments.size(); ++si)
        segments_by_patch_[graph_.cuts[graph_.segments[si].cut.index()].patch.index()].push_back(
            static_cast<std::uint32_t>(si));
    }
    return segments_by_patch_[pid.index()];
  }
  std::vector<std::vector<std::uint32_t>> segments_by_patch_;

  /// The patch's boundary pieces and rails. `keep` (per rail segment): lay only these, and
  /// drop nothing more; without it every rail is laid and the narrow-fan, narrow-wedge and
  /// dangling rules drop some.
  void build_patch_rails(PatchId pid, const std::vector<bool>* keep) {
    const Patch& patch = part_.patches[pid.index()];
    PatchGraph& g = patches_[pid.index()];
    std::map<std::uint32_t, std::uint32_t> by_mesh;  // boundary mesh node -> coarse node
    auto boundary_node = [&](std::uint32_t mesh, Vec2 p) {
      const auto it = by_mesh.find(mesh);
      if (it != by_mesh.end()) return it->second;
      const auto id = static_cast<std::uint32_t>(g.nodes.size());
      g.nodes.push_back({p, mesh, false});
      by_mesh.emplace(mesh, id);
      g.boundary_2d.emplace(mesh, p);
      return id;
    };
    for (std::size_t l = 0; l < patch.loops.size(); ++l) {
      const Loop& loop = patch.loops[l];
      const auto& poly = patch.polygon.loops[l];
      const std::size_t n = loop.vertices.size();
      std::uint32_t first = kNone, prev = kNone;
      std::uint32_t prev_edge = 0;
      std::uint32_t prev_piece = 0;
      bool prev_forward = true;
      // Start at a vertex that is not inside an arc, and take each arc's edges as one unit.
      std::size_t start = 0;
      while (start < n && part_.vertices[loop.vertices[start].index()].from_arc) ++start;
      if (start == n) throw InternalError("mesher: a loop of " + part_.patch_label(pid) +
                                          " has no vertex outside its arcs");
      for (std::size_t step = 0; step < n;) {
        const std::size_t i = (start + step) % n;
        const EdgeId e = loop.edges[i];
        const std::uint32_t unit = unit_of_edge_[e.index()];
        const Unit& un = units_[unit];
        const EdgeNodes& en = edges_[unit];
        const bool forward = loop.vertices[i] == un.a;
        std::size_t span = 1;  // loop edges this unit covers
        if (un.arc >= 0) {
          while (step + span < n && part_.edges[loop.edges[(i + span) % n].index()].arc == un.arc)
            ++span;
        }
        const Vec2 p0 = poly[i], p1 = poly[(i + 1) % n];
        const std::size_t pieces = en.count.size();
        for (std::size_t k = 0; k < pieces; ++k) {
          const std::size_t j = forward ? k : pieces - 1 - k;  // piece index on the unit
          const std::size_t from = forward ? j : j + 1;         // break at the piece's start
          const double s = forward ? en.t[from] : 1.0 - en.t[from];
          const Vec2 at = un.arc < 0 ? lerp(p0, p1, s)
                                     : patch.frame.to_2d(result_.mesh.nodes[en.node[from]]);
          const std::uint32_t c = boundary_node(en.node[from], at);
          if (first == kNone) first = c;
          if (prev != kNone) add_boundary_edge(g, prev, c, prev_edge, prev_piece, prev_forward);
          prev = c;
          prev_edge = unit;
          prev_piece = static_cast<std::uint32_t>(j);
          prev_forward = forward;
        }
        step += span;
      }
      add_boundary_edge(g, prev, first, prev_edge, prev_piece, prev_forward);
    }
    // Rails of this patch.
    std::map<std::uint32_t, std::uint32_t> by_macut;
    std::vector<std::uint32_t> ma_nodes;
    std::vector<double> ma_radius;  // per ma_nodes entry
    const double tol = kSamePointRel * part_.size;
    std::map<std::pair<std::uint32_t, std::uint32_t>, bool> seen;
    for (const std::uint32_t si : segments_in(pid)) {
      const RailSegment& seg = graph_.segments[si];
      const CutVert& cut = graph_.cuts[seg.cut.index()];
      if (keep && !(*keep)[si]) continue;
      const MaCutVert& mc = graph_.macuts[seg.ma.index()];
      const auto cit = by_mesh.find(gcut_node_[cut.g.index()]);
      if (cit == by_mesh.end()) {
        throw InternalError("mesher: a rail of " + part_.patch_label(pid) +
                            " starts at a point that is not on its boundary nodes");
      }
      const std::uint32_t a = cit->second;
      if (law_ && !g.foot.count(a)) {
        BoundaryPoint bp;
        bp.site = {BoundarySite::Kind::Segment, cut.at.loop, cut.at.segment};
        bp.s = cut.at.s;
        bp.position = cut.position;
        g.foot.emplace(a, bp);
      }
      // A rail to a convex corner, or to where the axis touches the boundary (radius 0),
      // bounds nothing: it lies on the boundary.
      if (distance(g.nodes[a].p, mc.point.position) <= tol || mc.point.radius <= tol) continue;
      std::uint32_t b = kNone;
      const auto mit = by_macut.find(seg.ma.value);
      if (mit != by_macut.end()) {
        b = mit->second;
      } else {
        // The nearest MA node within kMergeMaPoints x h is this one: where many branches of the
        // axis meet nearly at one point (the centre of a polygonised hub), the axis has several
        // vertices microns apart, and the faces between them would have to hold specks.
        const double ma_tol = std::max(tol, kMergeMaPoints * h_);
        double nearest = ma_tol;
        for (std::uint32_t m : ma_nodes) {
          const double d = distance(g.nodes[m].p, mc.point.position);
          if (d <= nearest) {
            nearest = d;
            b = m;
          }
        }
        if (b == kNone) {
          b = static_cast<std::uint32_t>(g.nodes.size());
          g.nodes.push_back({mc.point.position, kNone, true});
          ma_nodes.push_back(b);
          ma_radius.push_back(mc.point.radius);
        }
        by_macut.emplace(seg.ma.value, b);
      }
      if (distance(g.nodes[a].p, g.nodes[b].p) <= tol) continue;  // a convex corner: length 0
      if (!seen.emplace(std::make_pair(a, b), true).second) continue;
      CEdge r;
      r.a = a;
      r.b = b;
      r.rail = true;
      r.seg = static_cast<std::uint32_t>(si);
      const double len = distance(g.nodes[a].p, g.nodes[b].p);
      r.count = edges_for(len);
      g.edges.push_back(r);
    }
    const std::size_t merged = merge_fan_clusters(g, ma_nodes, ma_radius);
    if (!keep) result_.stats.fan_clusters += merged;  // the second pass merges them again
    if (keep) return;
    drop_crowded_feet(pid, g);
    drop_narrow_fans(g, false);
    drop_narrow_fans(g, true);
    drop_twin_rails(g);
    drop_dangling_rails(g);
    drop_disk_rails(pid, g);
    if (std::find(drop_hubs_.begin(), drop_hubs_.end(), pid.value) != drop_hubs_.end())
      drop_hub_rails(g);
  }

  /// Hubs (docs/mesher.md, "Hubs"): MA nodes where kHubRails or more rails of a patch end,
  /// no two neighbours round it further apart than kHubGap (uniform mode). A gear's centre:
  /// the rails from its tooth gaps all end there, and the wedges between them, whose far
  /// ends are the teeth's own tracks, get a handful of quads across.
  std::vector<std::uint32_t> hub_nodes(const PatchGraph& g) const {
    std::vector<std::uint32_t> hubs;
    if (law_) return hubs;
    std::map<std::uint32_t, std::vector<std::size_t>> at;
    for (std::size_t i = 0; i < g.edges.size(); ++i)
      if (g.edges[i].rail && g.nodes[g.edges[i].b].ma) at[g.edges[i].b].push_back(i);
    for (const auto& [m, rails] : at) {
      if (rails.size() < kHubRails) continue;
      if (widest_gap(g, rails, g.nodes[m].p) <= kHubGap) hubs.push_back(m);
    }
    return hubs;
  }

  /// The rails that end at a hub of the patch go (QuadOptions::drop_hubs): the hub and the
  /// wedges round it are one face, which the templates fill (a large one by the lattice).
  void drop_hub_rails(PatchGraph& g) {
    const std::vector<std::uint32_t> hubs = hub_nodes(g);
    if (hubs.empty()) return;
    std::vector<bool> drop(g.edges.size(), false);
    for (std::size_t i = 0; i < g.edges.size(); ++i)
      drop[i] = g.edges[i].rail &&
                std::find(hubs.begin(), hubs.end(), g.edges[i].b) != hubs.end();
    erase_marked(g.edges, drop);
    ++result_.stats.hub_patches;
  }

  /// Twin rails: two rails that cross the patch between the same two boundary nodes (their
  /// feet were one node on each side, breaks closer than kTinyPiece x h: on a needle facet two
  /// chains 0.008 h apart) bound a face of four rail edges and no boundary, and the MA point of
  /// one lies on the wrong side of the other's feet: the face beyond it is a dart. Of such
  /// twins (MA nodes with exactly two rails, to the same two feet, nothing inside the four
  /// edges between them) the one whose MA node is nearest the midpoint of its feet stays, the
  /// others' rails go (the chains go on in the other patches, to the same nodes). Distances
  /// decide, then the position in the patch frame, never the order of the graph's rails,
  /// which follows the pose; counted as twin_rails.
  void drop_twin_rails(PatchGraph& g) {
    std::vector<std::vector<std::uint32_t>> rails_of(g.nodes.size());
    for (std::uint32_t i = 0; i < g.edges.size(); ++i)
      if (g.edges[i].rail) rails_of[g.edges[i].b].push_back(i);
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> by_feet;
    for (std::uint32_t m = 0; m < g.nodes.size(); ++m) {
      if (rails_of[m].size() != 2) continue;
      std::uint32_t a = g.edges[rails_of[m][0]].a, b = g.edges[rails_of[m][1]].a;
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      by_feet[{a, b}].push_back(m);
    }
    std::vector<bool> drop(g.edges.size(), false);
    const double tie = kFootTie * part_.size;
    for (const auto& [feet, twins] : by_feet) {
      if (twins.size() < 2) continue;
      const Vec2 pa = g.nodes[feet.first].p, pb = g.nodes[feet.second].p;
      const Vec2 mid = 0.5 * (pa + pb);
      // The keeper: nearest the feet's midpoint; on a tie the lower, then leftmost, in the
      // patch frame (which turns with the part).
      std::uint32_t keep = twins[0];
      for (std::uint32_t m : twins) {
        const double dm = distance(g.nodes[m].p, mid), dk = distance(g.nodes[keep].p, mid);
        const Vec2 pm = g.nodes[m].p, pk = g.nodes[keep].p;
        if (dm < dk - tie || (dm <= dk + tie && (pm.y < pk.y || (pm.y == pk.y && pm.x < pk.x))))
          keep = m;
      }
      for (std::uint32_t m : twins) {
        if (m == keep) continue;
        // Nothing of the graph inside the four rail edges between the two.
        const std::vector<Vec2> quad = {pa, g.nodes[keep].p, pb, g.nodes[m].p};
        bool empty = true;
        for (std::uint32_t o = 0; o < g.nodes.size() && empty; ++o) {
          if (o == feet.first || o == feet.second || o == keep || o == m) continue;
          empty = !mesher_detail::inside_polygon(g.nodes[o].p, quad);
        }
        if (!empty) continue;
        for (std::uint32_t r : rails_of[m]) drop[r] = true;
        ++result_.stats.twin_rails;
      }
    }
    erase_marked(g.edges, drop);
  }

  /// Fan clusters: where the boundary curves round a point of the axis (an arc a little wider
  /// than its maximal disk, an arc meeting a flat side), the rails of the arc converge on
  /// the axis at points a fraction of an element apart, each wedge between two of them a
  /// sliver strip whose quads shrink to that fraction. The MA nodes of radius at least
  /// kFanMinRadius x h within kFanCluster x h of one another become one: the deepest (largest
  /// radius; on a tie the one whose rails' feet have the least mesh id) takes the rails of
  /// those within that distance of it, deepest first. The rails then meet at one point, where
  /// the narrow-fan and round-fan rules (drop_narrow_fans) thin them. A rail moves by at most
  /// kFanCluster x h inside a maximal disk of radius kFanMinRadius x h or more, so it stays in
  /// the patch; a cluster whose moved rails would cross another rail is left as it was.
  /// Returns the count of MA nodes merged into another.
  std::size_t merge_fan_clusters(PatchGraph& g, const std::vector<std::uint32_t>& ma_nodes,
                                 const std::vector<double>& ma_radius) {
    const double tol = kSamePointRel * part_.size;
    std::vector<std::uint32_t> least_foot(g.nodes.size(), kNone);
    for (const CEdge& e : g.edges) {
      if (!e.rail) continue;
      least_foot[e.b] = std::min(least_foot[e.b], g.nodes[e.a].mesh);
    }
    // MA nodes whose rails all start on arcs (an arc's fan converging on the axis) merge from
    // further apart, kFanClusterArc x h.
    std::vector<char> on_arc(g.nodes.size(), 0), arc_fed(g.nodes.size(), 1);
    for (const CEdge& e : g.edges)
      if (!e.rail && units_[e.edge].arc >= 0) on_arc[e.a] = on_arc[e.b] = 1;
    for (const CEdge& e : g.edges)
      if (e.rail && !on_arc[e.a]) arc_fed[e.b] = 0;
    const auto reach = [&](std::uint32_t a, std::uint32_t b) {
      return (arc_fed[a] && arc_fed[b] ? kFanClusterArc : kFanCluster) * h_;
    };
    // Deepest first: radii compared on a grid of the point tolerance, then by least foot.
    std::vector<std::tuple<long long, std::uint32_t, std::size_t>> order;
    for (std::size_t i = 0; i < ma_nodes.size(); ++i)
      if (ma_radius[i] >= kFanMinRadius * h_)
        order.emplace_back(-std::llround(ma_radius[i] / tol), least_foot[ma_nodes[i]], i);
    if (order.size() < 2) return 0;
    std::sort(order.begin(), order.end());
    std::size_t merged = 0;
    std::vector<std::uint32_t> target(g.nodes.size(), kNone);
    std::vector<bool> taken(ma_nodes.size(), false);
    for (std::size_t oi = 0; oi < order.size(); ++oi) {
      const std::size_t c = std::get<2>(order[oi]);
      if (taken[c]) continue;
      taken[c] = true;
      const std::uint32_t centre = ma_nodes[c];
      std::vector<std::size_t> members;  // indices into ma_nodes
      for (std::size_t oj = oi + 1; oj < order.size(); ++oj) {
        const std::size_t m = std::get<2>(order[oj]);
        if (taken[m]) continue;
        if (distance(g.nodes[ma_nodes[m]].p, g.nodes[centre].p) <= reach(ma_nodes[m], centre))
          members.push_back(m);
      }
      if (members.empty()) continue;
      for (std::size_t m : members) target[ma_nodes[m]] = centre;
      // Would a moved rail cross another rail (either moved or not)?
      const auto end_of = [&](const CEdge& e) {
        return target[e.b] != kNone ? g.nodes[target[e.b]].p : g.nodes[e.b].p;
      };
      bool clash = false;
      for (std::size_t i = 0; i < g.edges.size() && !clash; ++i) {
        const CEdge& e = g.edges[i];
        if (!e.rail || target[e.b] != centre) continue;
        const Vec2 a = g.nodes[e.a].p, b = end_of(e);
        for (std::size_t j = 0; j < g.edges.size() && !clash; ++j) {
          const CEdge& f = g.edges[j];
          if (j == i || !f.rail) continue;
          clash = mesher_detail::segments_meet(a, b, g.nodes[f.a].p, end_of(f));
        }
      }
      for (std::size_t m : members) {
        if (clash) {
          target[ma_nodes[m]] = kNone;
        } else {
          taken[m] = true;
        }
      }
      if (!clash) merged += members.size();
    }
    std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
    std::vector<CEdge> kept;
    for (CEdge e : g.edges) {
      if (e.rail) {
        if (target[e.b] != kNone) {
          e.b = target[e.b];
          e.count = edges_for(distance(g.nodes[e.a].p, g.nodes[e.b].p));
        }
        if (!seen.emplace(e.a, e.b).second) continue;
      }
      kept.push_back(e);
    }
    g.edges = std::move(kept);
    return merged;
  }

  /// A patch with one loop whose rails all meet at one MA point, all round it (a disk, a
  /// polygonised circle: its axis is that point), would be cut into wedges whose quads shrink
  /// to slivers at the centre. Its rails go: the patch is one face, which the O-grid template
  /// meshes. Nodes on its edges stay (rails of other patches may land there).
  /// A nearly round outline (a circle's vertices off it by a little, inputcircle of CGAL's
  /// straight-skeleton data: 34 vertices, radius 50 +- 1) has a small tree for its axis, not a
  /// point, and its rails end at several MA nodes of that tree: a pole of 16 quads of worst
  /// corner 0.377 at the centre. Rails whose ends all lie within kDiskSpread x the shortest
  /// rail of their centroid are read the same way when the loop is round (every boundary
  /// node's interior angle within kRoundMin..kRoundMax, the O-grid's own test).
  void drop_disk_rails(PatchId pid, PatchGraph& g) {
    if (part_.patches[pid.index()].loops.size() != 1) return;
    std::vector<std::uint32_t> ends;
    double shortest = std::numeric_limits<double>::infinity();
    for (const CEdge& e : g.edges) {
      if (!e.rail) continue;
      if (!g.nodes[e.b].ma) return;
      ends.push_back(e.b);
      shortest = std::min(shortest, distance(g.nodes[e.a].p, g.nodes[e.b].p));
    }
    if (ends.size() < kDiskRails) return;
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    Vec2 centre = g.nodes[ends.front()].p;
    if (ends.size() > 1) {
      Vec2 sum{0.0, 0.0};
      for (std::uint32_t m : ends) sum = sum + g.nodes[m].p;
      centre = (1.0 / static_cast<double>(ends.size())) * sum;
      double spread = 0.0;
      for (std::uint32_t m : ends) spread = std::max(spread, distance(g.nodes[m].p, centre));
      if (spread > kDiskSpread * shortest || !round_loop(g)) return;
    }
    std::vector<std::size_t> rails;
    for (std::size_t i = 0; i < g.edges.size(); ++i)
      if (g.edges[i].rail) rails.push_back(i);
    if (widest_gap(g, rails, centre) > kDiskGap) return;
    g.edges.erase(std::remove_if(g.edges.begin(), g.edges.end(), [](const CEdge& e) { return e.rail; }),
                  g.edges.end());
    ++result_.stats.disk_patches;
  }

  /// The widest angle round `centre` between the feet of two neighbouring rails of `rails`
  /// (indices of g.edges; at least one).
  static double widest_gap(const PatchGraph& g, const std::vector<std::size_t>& rails, Vec2 centre) {
    std::vector<double> angles;
    for (std::size_t i : rails) {
      const Vec2 d = g.nodes[g.edges[i].a].p - centre;
      angles.push_back(std::atan2(d.y, d.x));
    }
    std::sort(angles.begin(), angles.end());
    double widest = angles.front() + 2.0 * kPi - angles.back();
    for (std::size_t k = 1; k < angles.size(); ++k)
      widest = std::max(widest, angles[k] - angles[k - 1]);
    return widest;
  }

  /// Whether the patch's one loop, as its boundary nodes, is round.
  static bool round_loop(const PatchGraph& g) {
    std::map<std::uint32_t, std::uint32_t> next;
    for (const CEdge& e : g.edges)
      if (!e.rail) next[e.a] = e.b;
    std::vector<Vec2> cycle;
    for (auto it = next.begin(); cycle.size() < next.size(); it = next.find(it->second)) {
      if (it == next.end()) return false;
      cycle.push_back(g.nodes[it->first].p);
    }
    if (cycle.size() < 3) return false;
    if (twice_signed_area(cycle) < 0.0) std::reverse(cycle.begin(), cycle.end());
    return mesher_detail::is_round(cycle);
  }

  void add_boundary_edge(PatchGraph& g, std::uint32_t a, std::uint32_t b, std::uint32_t e,
                         std::uint32_t piece, bool forward) {
    CEdge c;
    c.a = a;
    c.b = b;
    c.edge = e;
    c.piece = piece;
    c.forward = forward;
    g.edges.push_back(c);
  }

  /// Thins a round fan (drop_narrow_fans): each run of consecutive plain-capped wedges
  /// (rails r_0 .. r_n, angle A in all) keeps its two end rails and k - 1 between them,
  /// k = ceil(A / kRoundFanAngle): r_(i n / k) rounded, i = 1 .. k - 1, counted from the end
  /// whose foot has the smaller mesh node id. Node ids and the wedges' count, not which angle
  /// is the smallest (the wedges of an arc are all alike, and rounding would choose), so every
  /// pose keeps the same rails. `rails` is sorted round the centre and loses the dropped ones.
  template <class Gap, class Plain>
  void thin_round_fan(const PatchGraph& g, std::vector<std::uint32_t>& rails, const Gap& gap,
                      const Plain& plain_cap, std::vector<bool>& drop, std::vector<int>& feet) {
    const std::size_t r = rails.size();
    // Start after a gap that ends a run: an open one, else the widest.
    std::size_t start = r;
    for (std::size_t k = 0; k < r && start == r; ++k)
      if (!plain_cap(k)) start = (k + 1) % r;
    if (start == r) {
      std::size_t widest = 0;
      for (std::size_t k = 1; k < r; ++k)
        if (gap(k) > gap(widest)) widest = k;
      start = (widest + 1) % r;
    }
    std::vector<bool> gone(r, false);
    std::vector<std::size_t> run{start};  // positions in `rails`
    double angle = 0.0;
    auto finish_run = [&] {
      const std::size_t n = run.size() - 1;  // wedges
      const std::size_t k =
          std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(angle / kRoundFanAngle - 1e-9)));
      if (n >= 2 && k < n) {
        const auto id = [&](std::size_t pos) { return g.nodes[g.edges[rails[pos]].a].mesh; };
        if (id(run.back()) < id(run.front())) std::reverse(run.begin(), run.end());
        std::vector<bool> keep(n + 1, false);
        for (std::size_t i = 0; i <= k; ++i) keep[(i * n + k / 2) / k] = true;
        for (std::size_t i = 0; i <= n; ++i)
          if (!keep[i]) gone[run[i]] = true;
      }
    };
    for (std::size_t step = 0; step < r; ++step) {
      const std::size_t k = (start + step) % r;
      if (plain_cap(k) && step + 1 < r) {
        angle += gap(k);
        run.push_back((k + 1) % r);
        continue;
      }
      finish_run();
      run.assign(1, (k + 1) % r);
      angle = 0.0;
    }
    std::vector<std::uint32_t> kept;
    for (std::size_t i = 0; i < r; ++i) {
      if (!gone[i]) {
        kept.push_back(rails[i]);
        continue;
      }
      drop[rails[i]] = true;
      --feet[g.edges[rails[i]].a];
      ++result_.stats.narrow_fans;
    }
    rails = std::move(kept);
  }

  /// Two rails leaving one boundary node (a concave corner's fan) less than kMinFanAngle apart
  /// bound a sliver no quad fits well: of the closest pair of neighbouring rails, the longer is
  /// dropped, and again until no pair is that close (its MA end may then dangle, and the rest
  /// of its chain goes with it). The same at an MA point (`at_ma`: a branch point whose
  /// touching points lie close together, or the centre of a finely cut arc), where rails as
  /// long as each other (the radius) leave the one whose loss leaves the smaller angle to its
  /// other neighbour. Angles and lengths choose, never the order of the rails, so that every
  /// pose drops the same rails.
  /// A round fan (uniform mode): an MA point where at least kRoundFanRails rails meet, all but
  /// kRoundFanOpenGaps of the wedges between them capped by plain boundary (the feet joined
  /// along the boundary through no other rail's foot: an arc or a polygonised arc whose
  /// centre this is, a fillet, a slot's or a gear tooth's round end), and not a disk (a gap
  /// above kDiskGap), is thinned first (thin_round_fan) to wedges of about kRoundFanAngle,
  /// however far apart their feet: every rail of the arc meets at the centre, and the apex
  /// quad of a wedge is as thin as its angle (a 180-degree round end of radius 10 h: 28
  /// wedges of 6.4 degrees, worst corner 0.105).
  void drop_narrow_fans(PatchGraph& g, bool at_ma) {
    std::map<std::uint32_t, std::vector<std::uint32_t>> at;  // node -> its rails
    for (std::uint32_t e = 0; e < g.edges.size(); ++e)
      if (g.edges[e].rail) at[at_ma ? g.edges[e].b : g.edges[e].a].push_back(e);
    // Round fans (MA points, uniform mode): rails (kept so far) leaving each boundary node,
    // and each boundary node's neighbours along the boundary.
    const bool fans = at_ma && !law_;
    std::vector<int> feet(g.nodes.size(), 0);
    std::map<std::uint32_t, std::vector<std::uint32_t>> along;
    for (const CEdge& e : g.edges) {
      if (!fans) break;
      if (e.rail) {
        ++feet[e.a];
      } else {
        along[e.a].push_back(e.b);
        along[e.b].push_back(e.a);
      }
    }
    const double tol = kSamePointRel * part_.size;
    // Reflex fans (uniform mode): each boundary node's neighbours along its loop, and the
    // nodes on arcs (the angle between chords there is no corner).
    std::map<std::uint32_t, std::uint32_t> next_of, prev_of;
    std::set<std::uint32_t> by_arc;
    for (const CEdge& e : g.edges)
      if (!at_ma && !law_ && !e.rail) {
        next_of[e.a] = e.b;
        prev_of[e.b] = e.a;
        if (units_[e.edge].arc >= 0) by_arc.insert({e.a, e.b});
      }
    std::vector<bool> drop(g.edges.size(), false);
    for (auto& [node, rails] : at) {
      const Vec2 o = g.nodes[node].p;
      auto dir = [&](std::uint32_t e) {
        return g.nodes[at_ma ? g.edges[e].a : g.edges[e].b].p - o;
      };
      std::sort(rails.begin(), rails.end(), [&](std::uint32_t x, std::uint32_t y) {
        const Vec2 u = dir(x), v = dir(y);
        return std::atan2(u.y, u.x) < std::atan2(v.y, v.x);
      });
      auto gap = [&](std::size_t k) {  // angle from rail k to the next counter-clockwise
        const Vec2 u = dir(rails[k]), v = dir(rails[(k + 1) % rails.size()]);
        return std::abs(std::atan2(cross(u, v), dot(u, v)));
      };
      // Is this MA point the centre of a round fan (round_fan below)? Its wedges' caps are
      // plain boundary: feet of rails k and k + 1 joined along the boundary through no foot of
      // any other rail (topology only: the same in every pose).
      auto plain_cap = [&](std::size_t k) {
        const std::uint32_t f1 = g.edges[rails[k]].a, f2 = g.edges[rails[(k + 1) % rails.size()]].a;
        const auto neighbours = along.find(f1);
        if (neighbours == along.end()) return false;
        for (std::uint32_t first : neighbours->second) {
          std::uint32_t prev = f1, cur = first;
          for (std::size_t step = 0; step <= g.nodes.size(); ++step) {
            if (cur == f2) return true;
            const auto nb = along.find(cur);
            if (feet[cur] > 0 || nb == along.end() || nb->second.size() != 2) break;
            const std::uint32_t next = nb->second[0] == prev ? nb->second[1] : nb->second[0];
            prev = cur;
            cur = next;
          }
        }
        return false;
      };
      bool round_fan = false;
      if (fans && rails.size() >= kRoundFanRails) {
        std::size_t open = 0;
        double widest = 0.0;
        for (std::size_t k = 0; k < rails.size(); ++k) {
          if (!plain_cap(k)) ++open;
          widest = std::max(widest, gap(k));
        }
        round_fan = open <= kRoundFanOpenGaps && widest > kDiskGap;
      }
      if (round_fan) thin_round_fan(g, rails, gap, plain_cap, drop, feet);
      // The boundary's interior angle at a boundary node (the patch lies left of its loops).
      bool reflex = false;
      if (!at_ma && !law_) {
        const auto n = next_of.find(node), p = prev_of.find(node);
        const std::uint32_t mesh = g.nodes[node].mesh;
        if (n != next_of.end() && p != prev_of.end() && mesh != kNone && is_vertex_node_[mesh] &&
            !by_arc.count(node)) {
          const Vec2 w = g.nodes[n->second].p - o, u = g.nodes[p->second].p - o;
          reflex = ccw_angle(w, u) > kReflexFanCorner;
        }
      }
      const double limit = at_ma ? kMinWedgeAngle : reflex ? kMinReflexFanAngle : kMinFanAngle;
      const auto pair_id = [&](std::size_t k) {
        return std::min(g.edges[rails[k]].seg, g.edges[rails[(k + 1) % rails.size()]].seg);
      };
      while (rails.size() >= 2) {
        // A gap within kAngleTie of the limit is not below it: a regular fan of 18 wedges has
        // gaps of 20 degrees, kMinWedgeAngle exactly, and rounding read some of them below it
        // in one pose only (fuzz seeds 42042 and 44044's 18-tipped stars).
        double closest = limit - kAngleTie;
        std::size_t pick = rails.size();
        for (std::size_t k = 0; k < rails.size(); ++k) {
          const double angle = gap(k);
          // At an MA point only a wedge whose feet are closer than kMaxWedgeFeet x h, or one
          // thinner than kThinWedgeAngle: a wider one holds quads of its own, and merging it
          // made long fans (cgal_wiggly_03_cgal, before the lattice template). Adaptive mode:
          // any wedge below kMinWedgeAngle.
          if (at_ma && !law_ && angle >= kThinWedgeAngle &&
              distance(dir(rails[k]), dir(rails[(k + 1) % rails.size()])) >
                  (kMaxWedgeFeet + kRoundingSlack) * h_)
            continue;
          // At a reflex corner the wider limit holds for short rails only: dropping a long
          // one takes a long chain, and wide faces far from the corner, with it.
          if (reflex && (norm(dir(rails[k])) > (kShortFanRail + kRoundingSlack) * h_ ||
                         norm(dir(rails[(k + 1) % rails.size()])) >
                             (kShortFanRail + kRoundingSlack) * h_) &&
              angle >= kMinFanAngle)
            continue;
          if (pick < rails.size() && std::abs(angle - closest) <= kAngleTie) {
            // A fan is often regular (a reflex corner's, a symmetric part's): of gaps alike
            // (to rounding), the pair with the least rail segment id, the same in every pose.
            if (pair_id(k) < pair_id(pick)) pick = k;
            continue;
          }
          if (angle < closest) {
            closest = angle;
            pick = k;
          }
        }
        if (pick == rails.size()) break;
        const std::size_t other = (pick + 1) % rails.size();
        const double lp = norm(dir(rails[pick])), lo = norm(dir(rails[other]));
        std::size_t gone = lp >= lo ? pick : other;
        // Of two rails as long as each other (to rounding) at a boundary node, the one with
        // the greater segment id goes: a symmetric part's fans lose the same rail in every
        // pose (holes__hole_tiny lost its mirror image when turned).
        if (!at_ma && std::abs(lp - lo) <= tol)
          gone = g.edges[rails[pick]].seg > g.edges[rails[other]].seg ? pick : other;
        if (at_ma && std::abs(lp - lo) <= tol && rails.size() >= 3) {
          const double before = gap((pick + rails.size() - 1) % rails.size());
          const double after = gap(other);
          // Alike to rounding (a regular fan round the point, a symmetric part): the first of
          // the pair goes, which the pick's ties leave the same in every pose.
          gone = before <= after + kAngleTie ? pick : other;
        }
        drop[rails[gone]] = true;
        if (fans) --feet[g.edges[rails[gone]].a];
        ++result_.stats.narrow_fans;
        rails.erase(rails.begin() + static_cast<std::ptrdiff_t>(gone));
      }
    }
    erase_marked(g.edges, drop);
  }

  /// Round holes (docs/medial.md, "Round holes"): rails land on a concave arc (a hole's, or a
  /// concave fillet's) along rays from its centre, so the rails of a wider boundary across the
  /// axis crowd onto a small hole, their feet R / (R + r) of their spacing apart (R the hole's
  /// radius, r the axis' radius there). Along each run of boundary on one such circle (the
  /// arcs of one circle in a row, round their joints; a whole hole is a closed run), of two
  /// neighbouring feet closer than kMinArcFoot x the element size one goes with its rails
  /// (its chain's rest then dangles, and goes too), the closest pair first, until none is that
  /// close. Of the pair, the foot whose other gap is the smaller goes, so that the gaps even
  /// out; the run's own ends stay. Gaps alike to kFootTie x the part's size are a tie, which
  /// the foot with the greater mesh node id loses: every pose drops the same rails.
  void drop_crowded_feet(PatchId pid, PatchGraph& g) {
    std::vector<std::vector<std::uint32_t>> rails_at(g.nodes.size());
    for (std::uint32_t i = 0; i < g.edges.size(); ++i)
      if (g.edges[i].rail) rails_at[g.edges[i].a].push_back(i);
    // The boundary edges come first, loop by loop, each loop's in order from its first node.
    std::vector<std::vector<std::uint32_t>> loops;
    for (std::uint32_t i = 0; i < g.edges.size() && !g.edges[i].rail; ++i) {
      if (loops.empty() || g.edges[loops.back().back()].b != g.edges[i].a) loops.emplace_back();
      loops.back().push_back(i);
    }
    std::vector<bool> drop(g.edges.size(), false);
    struct Foot {
      double at;           // length along the run from its start
      double size;         // the element size there
      std::uint32_t node;  // coarse node
      bool fixed;          // an end of an open run
    };
    for (const std::vector<std::uint32_t>& loop : loops) {
      const std::size_t n = loop.size();
      std::vector<std::int32_t> circle(n);
      for (std::size_t i = 0; i < n; ++i) circle[i] = round_circle(pid, g.edges[loop[i]]);
      // Runs: maximal stretches of one circle. Start after a change, if the loop has one.
      std::size_t start = 0;
      while (start < n && circle[start] == circle[(start + n - 1) % n]) ++start;
      const bool closed = start == n;  // the whole loop is one circle (or none)
      if (closed) start = 0;
      for (std::size_t step = 0; step < n;) {
        const std::size_t first = (start + step) % n;
        std::size_t len = 1;
        while (step + len < n && circle[(first + len) % n] == circle[first]) ++len;
        step += len;
        if (circle[first] < 0) continue;
        std::vector<Foot> feet;
        double at = 0.0;
        for (std::size_t k = 0; k <= len; ++k) {
          if (k == len && closed) break;
          const CEdge& e = g.edges[loop[(first + std::min(k, len - 1)) % n]];
          const std::uint32_t node = k < len ? e.a : e.b;
          const EdgeNodes& en = edges_[e.edge];
          const double t = en.t[e.piece + ((k < len) != e.forward ? 1 : 0)];
          if (!rails_at[node].empty())
            feet.push_back({at, local_size(e.edge, t), node, !closed && (k == 0 || k == len)});
          if (k < len) at += piece_length(e);
        }
        const double total = at;
        const std::size_t m0 = feet.size();
        if (m0 < 2) continue;
        // gap(k): from feet[k] to the next (round a closed run), or infinite.
        const auto gap = [&](std::size_t k) {
          if (k + 1 < feet.size()) return feet[k + 1].at - feet[k].at;
          return closed && feet.size() > 1 ? feet.front().at + total - feet[k].at : INFINITY;
        };
        for (;;) {
          const std::size_t m = feet.size();
          std::size_t pick = m;
          double closest = INFINITY;
          for (std::size_t k = 0; k < m && m >= 2; ++k) {
            const std::size_t k1 = (k + 1) % m;
            if (feet[k].fixed && feet[k1].fixed) continue;
            const double d = gap(k);
            if (!(d < kMinArcFoot * std::min(feet[k].size, feet[k1].size))) continue;
            if (d < closest - kFootTie * part_.size ||
                (std::abs(d - closest) <= kFootTie * part_.size &&
                 std::min(g.nodes[feet[k].node].mesh, g.nodes[feet[k1].node].mesh) <
                     std::min(g.nodes[feet[pick].node].mesh,
                              g.nodes[feet[(pick + 1) % m].node].mesh))) {
              closest = std::min(d, closest);
              pick = k;
            }
          }
          if (pick == m) break;
          const std::size_t next = (pick + 1) % m;
          const double before = pick > 0 || closed ? gap((pick + m - 1) % m) : INFINITY;
          const double after = next > 0 || closed ? gap(next) : INFINITY;
          std::size_t gone;
          if (feet[pick].fixed) {
            gone = next;
          } else if (feet[next].fixed) {
            gone = pick;
          } else if (std::abs(before - after) > kFootTie * part_.size) {
            gone = before < after ? pick : next;
          } else {
            gone = g.nodes[feet[pick].node].mesh > g.nodes[feet[next].node].mesh ? pick : next;
          }
          for (std::uint32_t r : rails_at[feet[gone].node]) {
            drop[r] = true;
            ++result_.stats.crowded_feet;
          }
          feet.erase(feet.begin() + static_cast<std::ptrdiff_t>(gone));
        }
      }
    }
    erase_marked(g.edges, drop);
  }

  /// Per node of a patch graph: the mean mesh-edge length of the boundary pieces at it (0 for
  /// a node on no boundary piece, an MA point).
  std::vector<double> boundary_steps(const PatchGraph& g) const {
    std::vector<double> sum(g.nodes.size(), 0.0);
    std::vector<int> count(g.nodes.size(), 0);
    for (const CEdge& e : g.edges) {
      if (e.rail) continue;
      const double step = distance(g.nodes[e.a].p, g.nodes[e.b].p) / edges_[e.edge].count[e.piece];
      for (std::uint32_t v : {e.a, e.b}) {
        sum[v] += step;
        ++count[v];
      }
    }
    for (std::size_t v = 0; v < sum.size(); ++v)
      if (count[v] > 0) sum[v] /= count[v];
    return sum;
  }

  /// Adaptive mode, Eq. (2): the rails meeting at one MA point all get N = round(L_avg / W),
  /// L_avg their mean length and W the mean, over their boundary nodes, of the mean length of
  /// the two boundary mesh edges there (the widths of the tracks either side), each held
  /// within a factor kFootWidthBound of the law's width at that node: a sliver track beside
  /// a rail (two rails landing close) must not make it thousands of edges long. Eq. (3) then
  /// spaces the nodes R_i / N along each rail.
  void adaptive_rail_counts(PatchId pid, PatchGraph& g) const {
    const std::vector<double> step = boundary_steps(g);
    std::map<std::uint32_t, std::pair<double, double>> at;  // MA node -> (sum R, sum W)
    std::map<std::uint32_t, int> rails;
    for (const CEdge& e : g.edges) {
      if (!e.rail || step[e.a] == 0.0) continue;
      auto& [r, w] = at[e.b];
      r += distance(g.nodes[e.a].p, g.nodes[e.b].p);
      const double law_w = law_->width(pid, g.foot.at(e.a));
      w += std::clamp(step[e.a], law_w / kFootWidthBound, law_w * kFootWidthBound);
      ++rails[e.b];
    }
    for (CEdge& e : g.edges) {
      if (!e.rail) continue;
      const auto it = at.find(e.b);
      if (it == at.end()) continue;
      const double n = rails.at(e.b);
      e.count = edges_for(it->second.first / n, it->second.second / n);
    }
  }

  /// A rail that leaves its boundary node outside the patch's corner there (between the next
  /// boundary piece and the previous one, counter-clockwise) would make a face run outside the
  /// patch: dropped, then the rails left dangling. A tooth of a sawtooth outline narrower than
  /// rounding at the rail's scale puts its axis point's rail just outside the tooth.
  void drop_outward_rails(PatchGraph& g) {
    const auto n = static_cast<std::uint32_t>(g.nodes.size());
    std::vector<std::uint32_t> next(n, kNone), prev(n, kNone);
    for (const CEdge& e : g.edges) {
      if (e.rail) continue;
      next[e.a] = e.b;
      prev[e.b] = e.a;
    }
    std::vector<bool> drop(g.edges.size(), false);
    bool any = false;
    for (std::size_t k = 0; k < g.edges.size(); ++k) {
      const CEdge& e = g.edges[k];
      if (!e.rail || next[e.a] == kNone || prev[e.a] == kNone) continue;
      const Vec2 v = g.nodes[e.a].p;
      const Vec2 out = g.nodes[next[e.a]].p - v;
      const double corner = ccw_angle(out, g.nodes[prev[e.a]].p - v);
      const double rail = ccw_angle(out, g.nodes[e.b].p - v);
      if (!(rail > 0.0 && rail < corner)) drop[k] = any = true;
    }
    if (any) result_.stats.outward_rails += drop_marked_rails(g, drop);
  }

  /// A rail with the same face on both sides that is no bridge of the patch's graph (its ends
  /// stay joined without it) cannot be: in a plane, an edge on a cycle parts its two sides.
  /// It is there when the rails round an axis point are out of order: three rails through one
  /// axis point in a tooth of a sawtooth outline far narrower than the element (axis points
  /// within rounding of one another) ran round it in the wrong order, the face passed each of
  /// them both ways and visited their nodes twice, and no template fills a face that runs
  /// into itself that way. Such rails are dropped, then the rails left dangling, and the
  /// faces traced again (bridging loose loops first, as before). A true bridge (the one rail
  /// chain joining a hole to the rest, a keyhole face) stays: templates fill those. Parity is
  /// kept: a slit of k edges is 2k nodes of its face's cycle. True when any was dropped.
  bool drop_slit_rails(PatchGraph& g) {
    std::vector<bool> drop(g.edges.size(), false);
    bool any = false;
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      const CEdge& c = g.edges[e];
      if (!c.rail || c.face[0] == kNone || c.face[0] != c.face[1]) continue;
      // Not a bridge: its ends are joined by the other edges.
      UnionFind uf(g.nodes.size());
      for (std::size_t k = 0; k < g.edges.size(); ++k)
        if (k != e) uf.unite(g.edges[k].a, g.edges[k].b);
      if (uf.find(c.a) == uf.find(c.b)) drop[e] = any = true;
    }
    if (any) result_.stats.slit_rails += drop_marked_rails(g, drop);
    return any;
  }

  /// A face of one run of boundary and one run of rails (a cap: the rails cut it off) so thin
  /// that twice its area is below kSliverCap x its perimeter squared (a needle of a sawtooth
  /// outline, its tip under a quarter of a degree: for a triangle of apex angle a the ratio is
  /// about sin(a) / 4) loses its rails, and the rails left dangling: the needle joins the face
  /// beyond them, where the templates have room for its nodes, and the faces are traced again.
  /// No template fills such a cap by itself: with its two sides a needle's width apart, every
  /// quad of it has a corner at the tip or a flat one on a side. True when any was dropped.
  bool drop_sliver_caps(PatchGraph& g) {
    std::vector<bool> drop(g.edges.size(), false);
    bool any = false;
    for (const std::vector<Half>& face : g.faces) {
      const std::size_t m = face.size();
      std::size_t changes = 0;
      for (std::size_t k = 0; k < m; ++k)
        if (g.edges[face[k].edge].rail != g.edges[face[(k + 1) % m].edge].rail) ++changes;
      if (changes != 2) continue;
      double twice_area = 0.0, perimeter = 0.0;
      for (const Half& h : face) {
        const CEdge& c = g.edges[h.edge];
        const Vec2 p = g.nodes[h.reverse ? c.b : c.a].p, q = g.nodes[h.reverse ? c.a : c.b].p;
        twice_area += cross(p, q);
        perimeter += distance(p, q);
      }
      if (!(twice_area < kSliverCap * perimeter * perimeter)) continue;
      for (const Half& h : face)
        if (g.edges[h.edge].rail) drop[h.edge] = any = true;
    }
    if (any) result_.stats.sliver_cap_rails += drop_marked_rails(g, drop);
    return any;
  }

  /// In the third attempt (QuadOptions::needle_tips), a rail that crosses another edge
  /// of the patch's graph (a boundary piece of a sawtooth's tooth far narrower than h, or
  /// another rail) goes, with the rails left dangling: no face between such edges is a simple
  /// polygon ("a region that no rail reaches", or no template: docs/mesher.md, "Needle tips").
  /// True when any was dropped.
  bool drop_crossing_rails(PatchGraph& g) {
    const std::size_t m = g.edges.size();
    std::vector<Box2> box(m);
    for (std::size_t e = 0; e < m; ++e) {
      box[e].add(g.nodes[g.edges[e].a].p);
      box[e].add(g.nodes[g.edges[e].b].p);
    }
    std::vector<bool> drop(m, false);
    bool any = false;
    for (std::size_t e = 0; e < m; ++e) {
      if (!g.edges[e].rail) continue;
      const Vec2 p = g.nodes[g.edges[e].a].p, q = g.nodes[g.edges[e].b].p;
      for (std::size_t k = 0; k < m && !drop[e]; ++k) {
        if (k == e || box[k].lo.x > box[e].hi.x || box[e].lo.x > box[k].hi.x ||
            box[k].lo.y > box[e].hi.y || box[e].lo.y > box[k].hi.y)
          continue;
        if (mesher_detail::segments_meet(p, q, g.nodes[g.edges[k].a].p, g.nodes[g.edges[k].b].p))
          drop[e] = any = true;
      }
    }
    if (any) result_.stats.crossing_rails += drop_marked_rails(g, drop);
    return any;
  }

  /// Drops the edges `drop` marks, then the rails left dangling, and forgets the faces if any
  /// were traced (to be traced again). Returns how many were marked.
  std::size_t drop_marked_rails(PatchGraph& g, const std::vector<bool>& drop) {
    std::size_t kept = 0;
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      if (drop[e]) continue;
      if (kept != e) g.edges[kept] = std::move(g.edges[e]);
      ++kept;
    }
    const std::size_t dropped = g.edges.size() - kept;
    g.edges.resize(kept);
    drop_dangling_rails(g);
    g.faces.clear();
    for (CEdge& c : g.edges) c.face[0] = c.face[1] = kNone;
    return dropped;
  }

  /// Rails whose MA end meets no other rail bound no face: dropped (repeatedly).
  void drop_dangling_rails(PatchGraph& g) {
    for (;;) {
      std::vector<std::uint32_t> degree(g.nodes.size(), 0);
      for (const CEdge& e : g.edges)
        if (e.rail) ++degree[e.b];
      const auto before = g.edges.size();
      g.edges.erase(std::remove_if(g.edges.begin(), g.edges.end(),
                                   [&](const CEdge& e) { return e.rail && degree[e.b] == 1; }),
                    g.edges.end());
      result_.stats.dangling_rails += before - g.edges.size();
      if (before == g.edges.size()) break;
    }
  }

  /// A loop of the patch that no rail joins to the rest of its graph (a hole whose corridors
  /// were all narrow, so their rails went) would leave a face with a hole in it, which no
  /// template meshes. Such a loop (or a group of loops joined only among themselves) gets two
  /// bridges to the rest: straight rails from two of its nodes to the nearest nodes outside it
  /// that they reach crossing no edge of the graph, the second as far from the first as it can
  /// be for its length; a bridge to a boundary node passes through a new axis node at its
  /// middle, one to an axis node ends there. Mesh edges: its length over the mean boundary
  /// step at its ends. The two bridges cut the region round the loop into simple faces.
  void bridge_loose_loops(PatchGraph& g) {
    const double tol = kSamePointRel * part_.size;
    auto side = [&](Vec2 a, Vec2 b, Vec2 c) {
      const double d = cross(b - a, c - a);
      return d > tol * norm(b - a) ? 1 : (d < -tol * norm(b - a) ? -1 : 0);
    };
    // True when segment pq meets segment rt other than at a shared end node.
    auto meets = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r, std::uint32_t t) {
      if (p == r || p == t || q == r || q == t) return false;
      const Vec2 P = g.nodes[p].p, Q = g.nodes[q].p, R = g.nodes[r].p, T = g.nodes[t].p;
      const int d1 = side(P, Q, R), d2 = side(P, Q, T), d3 = side(R, T, P), d4 = side(R, T, Q);
      return d1 * d2 <= 0 && d3 * d4 <= 0;
    };
    const std::vector<double> step = boundary_steps(g);
    for (std::size_t round = 0; round < g.nodes.size(); ++round) {
      UnionFind uf(g.nodes.size());
      for (const CEdge& e : g.edges) uf.unite(e.a, e.b);
      // Node 0 is on the outer loop (loops are laid outer first).
      const std::size_t main = uf.find(0);
      std::size_t loose = kNone;
      for (std::uint32_t v = 0; v < g.nodes.size() && loose == kNone; ++v)
        if (uf.find(v) != main) loose = uf.find(v);
      if (loose == kNone) return;
      // Candidate bridges: a loose boundary node to any node of another set, nearest first.
      // Lengths settled (settled_length): in a symmetric part many bridges are as long as one
      // another but for rounding, and the nearest (then the least node ids) must be the same
      // in every pose (manyv__wavy400_hole scaled by 1e-3 bridged its hole elsewhere, and its
      // two large faces and count followed).
      struct Bridge {
        long long length;
        std::uint32_t a, b;
      };
      std::vector<Bridge> all;
      for (std::uint32_t a = 0; a < g.nodes.size(); ++a) {
        if (uf.find(a) != loose || g.nodes[a].ma) continue;
        for (std::uint32_t b = 0; b < g.nodes.size(); ++b)
          if (uf.find(b) != loose)
            all.push_back({settled_length(distance(g.nodes[a].p, g.nodes[b].p)), a, b});
      }
      std::sort(all.begin(), all.end(), [](const Bridge& x, const Bridge& y) {
        return x.length != y.length ? x.length < y.length : std::tie(x.a, x.b) < std::tie(y.a, y.b);
      });
      auto clear = [&](const Bridge& br, const Bridge* other) {
        for (const CEdge& e : g.edges)
          if (meets(br.a, br.b, e.a, e.b)) return false;
        return !other || !meets(br.a, br.b, other->a, other->b);
      };
      const Bridge* first = nullptr;
      for (const Bridge& br : all)
        if (clear(br, nullptr)) {
          first = &br;
          break;
        }
      if (!first) break;
      // The second: the clear one (not at the first's ends) that is shortest for its distance
      // from the first's foot.
      std::vector<std::pair<long long, std::size_t>> order;  // (score, index in all), best first
      for (std::size_t k = 0; k < all.size(); ++k) {
        const Bridge& br = all[k];
        if (br.a == first->a || br.b == first->b) continue;
        order.push_back(
            {br.length - settled_length(distance(g.nodes[br.a].p, g.nodes[first->a].p)), k});
      }
      std::sort(order.begin(), order.end());
      const Bridge* second = nullptr;
      for (const auto& [score, k] : order)
        if (clear(all[k], first)) {
          second = &all[k];
          break;
        }
      if (!second) break;
      for (const Bridge* br : {first, second}) {
        const double local = std::max(step[br->a], step[br->b]);
        const double h = local > 0.0 ? local : h_;
        auto rail = [&](std::uint32_t from, std::uint32_t to) {
          CEdge r;
          r.a = from;
          r.b = to;
          r.rail = true;
          r.count = edges_for(distance(g.nodes[from].p, g.nodes[to].p), h);
          g.edges.push_back(r);
        };
        if (g.nodes[br->b].ma) {
          rail(br->a, br->b);
        } else {
          const auto m = static_cast<std::uint32_t>(g.nodes.size());
          g.nodes.push_back({lerp(g.nodes[br->a].p, g.nodes[br->b].p, 0.5), kNone, true});
          rail(br->a, m);
          rail(br->b, m);
        }
      }
      ++result_.stats.loop_bridges;
    }
  }

  /// Darts at sharp tips: a face of four single edges, two boundary edges at a tip T and two
  /// rails of one MA node X (its only rails), where X lies on T's side of the chord between the
  /// rails' feet A and B: the face is a dart, and a template splits the tip between quads. A
  /// rail that leaned onto another chain's point (kCoincideRel: the foot moves by up to 0.15
  /// of the radius) does that at a tip under about 8 degrees, where the axis point lies only
  /// d sin^2(a/2) beyond the chord. X moves along the line from T to where T, A, X and B are
  /// concyclic (as a kite with right angles at A and B, the rails without leaning), when the
  /// face is then convex, X stays inside the face across the rails, and its rails cross none
  /// of that face's edges. Counted as unfolded_darts.
  void unfold_darts(PatchGraph& g) {
    const double tol = kSamePointRel * part_.size;
    std::vector<std::uint32_t> rails_at(g.nodes.size(), 0);
    for (const CEdge& e : g.edges)
      if (e.rail) ++rails_at[e.b];
    auto tail = [&](Half h) { return h.reverse ? g.edges[h.edge].b : g.edges[h.edge].a; };
    for (std::uint32_t f = 0; f < g.faces.size(); ++f) {
      const std::vector<Half>& face = g.faces[f];
      if (face.size() != 4) continue;
      // X: the MA node whose two rails are consecutive in the face; T opposite.
      // Every edge single; edges i and i - 1 rails, i + 1 and i + 2 not.
      const auto edge = [&](std::size_t i) -> const CEdge& { return g.edges[face[i % 4].edge]; };
      std::size_t k = 4;
      for (std::size_t i = 0; i < 4; ++i) {
        const std::uint32_t v = tail(face[i]);
        if (edge(i + 3).rail && edge(i).rail && !edge(i + 1).rail && !edge(i + 2).rail &&
            g.nodes[v].ma && rails_at[v] == 2 &&
            std::all_of(face.begin(), face.end(), [&](Half h) { return g.edges[h.edge].count == 1; }))
          k = i;
      }
      if (k == 4) continue;
      const std::uint32_t x = tail(face[k]), b = tail(face[(k + 1) % 4]),
                          t = tail(face[(k + 2) % 4]), a = tail(face[(k + 3) % 4]);
      const Vec2 X = g.nodes[x].p, B = g.nodes[b].p, T = g.nodes[t].p, A = g.nodes[a].p;
      // The face runs counter-clockwise: X is reflex when the turn A -> X -> B is clockwise.
      if (cross(X - A, B - X) >= -kDartTurn * norm(X - A) * norm(B - X)) continue;
      // Y: where the line from T through X meets the circle through T, A and B again. T, A, Y, B
      // are then concyclic, so the corner at Y is 180 degrees less the tip's: the kite as the
      // rails would make it without leaning (right angles at the feet), and no worse a corner
      // at Y than the tip's own.
      const Vec2 u = X - T;
      const double lu = norm(u);
      const double d = 2.0 * cross(A - T, B - T);
      if (lu <= tol || std::abs(d) <= tol * tol) continue;
      const Vec2 ta = A - T, tb = B - T;
      const Vec2 o{(tb.y * dot(ta, ta) - ta.y * dot(tb, tb)) / d,
                   (ta.x * dot(tb, tb) - tb.x * dot(ta, ta)) / d};  // circumcentre - T
      const Vec2 dir = (1.0 / lu) * u;
      const Vec2 Y = T + (2.0 * dot(o, dir)) * dir;
      const std::array<Vec2, 4> kite = {Y, B, T, A};
      bool convex = true;
      for (std::size_t i = 0; i < 4; ++i) {
        const Vec2 e0 = kite[(i + 1) % 4] - kite[i], e1 = kite[(i + 2) % 4] - kite[(i + 1) % 4];
        convex = convex && cross(e0, e1) > kDartTurn * norm(e0) * norm(e1);
      }
      if (!convex) continue;
      // The face across the rails (on the other side of A-X and X-B) must keep Y inside and
      // no edge of it may cross A-Y or Y-B.
      const CEdge& rx = g.edges[face[k].edge];
      const std::uint32_t other = rx.face[face[k].reverse ? 0 : 1];
      if (other == kNone || other == f) continue;
      std::vector<Vec2> across;
      bool clear = true;
      for (const Half& h : g.faces[other]) {
        const CEdge& e = g.edges[h.edge];
        across.push_back(g.nodes[tail(h)].p);
        if (e.a == x || e.b == x || e.a == a || e.b == a || e.a == b || e.b == b) continue;
        const Vec2 P = g.nodes[e.a].p, Q = g.nodes[e.b].p;
        clear = clear && !mesher_detail::segments_meet(A, Y, P, Q) &&
                !mesher_detail::segments_meet(Y, B, P, Q);
      }
      const bool inside = mesher_detail::inside_polygon(Y, across);
      if (!inside || !clear) continue;
      g.nodes[x].p = Y;
      ++result_.stats.unfolded_darts;
    }
  }

  void trace_faces(PatchId pid, PatchGraph& g) {
    // Outgoing half-edges per node, counter-clockwise by angle.
    struct Out {
      double angle;
      std::uint32_t edge;
      bool reverse;
    };
    std::vector<std::vector<Out>> out(g.nodes.size());
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      const CEdge& c = g.edges[e];
      const Vec2 d = g.nodes[c.b].p - g.nodes[c.a].p;
      out[c.a].push_back({std::atan2(d.y, d.x), e, false});
      out[c.b].push_back({std::atan2(-d.y, -d.x), e, true});
    }
    for (auto& o : out)
      std::sort(o.begin(), o.end(), [](const Out& x, const Out& y) {
        return x.angle != y.angle ? x.angle < y.angle : x.edge < y.edge;
      });
    auto head = [&](Half h) { return h.reverse ? g.edges[h.edge].a : g.edges[h.edge].b; };
    auto next = [&](Half h) {
      const std::uint32_t v = head(h);
      const auto& o = out[v];
      std::size_t k = 0;
      while (k < o.size() && !(o[k].edge == h.edge && o[k].reverse != h.reverse)) ++k;
      const Out& n = o[(k + o.size() - 1) % o.size()];
      return Half{n.edge, n.reverse};
    };
    auto fid = [&](Half h) -> std::uint32_t& { return g.edges[h.edge].face[h.reverse ? 1 : 0]; };
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      for (int r = 0; r < 2; ++r) {
        const Half start{e, r == 1};
        if (!g.edges[e].rail && start.reverse) continue;  // outside the patch
        if (fid(start) != kNone) continue;
        const auto f = static_cast<std::uint32_t>(g.faces.size());
        std::vector<Half> cycle;
        Half h = start;
        double twice_area = 0.0;
        do {
          if (fid(h) != kNone || cycle.size() > 4 * g.edges.size()) {
            throw InternalError("mesher: the rails of " + part_.patch_label(pid) +
                                " do not cut it into faces (a face boundary runs into itself)");
          }
          if (!g.edges[h.edge].rail && h.reverse) {
            throw InternalError("mesher: a face of " + part_.patch_label(pid) +
                                " leaves the patch (rails out of order at a boundary node)");
          }
          fid(h) = f;
          cycle.push_back(h);
          const Vec2 p = g.nodes[h.reverse ? g.edges[h.edge].b : g.edges[h.edge].a].p;
          const Vec2 q = g.nodes[head(h)].p;
          twice_area += cross(p, q);
          h = next(h);
        } while (!(h.edge == start.edge && h.reverse == start.reverse));
        if (!(twice_area > 0.0)) {
          throw InternalError("mesher: " + part_.patch_label(pid) +
                              " has a region that no rail reaches (a hole's boundary not joined "
                              "to the rest by rails)");
        }
        g.faces.push_back(std::move(cycle));
      }
    }
  }

  std::uint32_t half_count(const PatchGraph& g, Half h) const {
    const CEdge& c = g.edges[h.edge];
    return c.rail ? c.count : edges_[c.edge].count[c.piece];
  }

  std::uint32_t face_count(const PatchGraph& g, std::size_t f) const {
    std::uint32_t n = 0;
    for (Half h : g.faces[f]) n += half_count(g, h);
    return n;
  }

  /// A strip's run with fewer edges takes the extra one only where its edges stay at least this
  /// x the other run's mean edge: a narrow end split finer makes quads of aspect >= 5 across
  /// the strip (cover_bosses' strips between its corner bosses and the outline).
  static constexpr double kStripMatchRel = 0.5;

  /// A length on a grid of kSamePointRel x the part's size: lengths equal but for rounding
  /// (a symmetric part's) compare equal in every pose, and their ties go by ids.
  long long settled_length(double length) const {
    return std::llround(length / (kSamePointRel * part_.size));
  }

  /// For fix_parity: in face f of a strip's shape (two runs of boundary pieces and two runs
  /// of rails with as many edges as each other) whose boundary runs differ in edge count, the
  /// half of the run with fewer edges that is a free piece (`free_piece(edge, piece)`) and
  /// whose edges stay longest with one more; kNone otherwise. Lengths settled
  /// (settled_length), ties to the first: the same in every pose.
  template <class FreePiece>
  std::uint32_t strip_piece(const PatchGraph& g, std::uint32_t f, FreePiece free_piece) const {
    const std::vector<Half>& hs = g.faces[f];
    const auto m = static_cast<std::uint32_t>(hs.size());
    const auto is_rail = [&](std::uint32_t k) { return g.edges[hs[k].edge].rail; };
    // Start at a boundary half that follows a rail.
    std::uint32_t start = kNone;
    for (std::uint32_t k = 0; k < m; ++k)
      if (!is_rail(k) && is_rail((k + m - 1) % m)) {
        start = k;
        break;
      }
    if (start == kNone) return kNone;
    // Its sides: runs of boundary pieces, and runs of rails (two rails meeting at a boundary
    // node, a concave corner's fan, are two sides with an empty boundary side between).
    std::vector<std::vector<std::uint32_t>> runs;
    std::uint32_t rail_count[2] = {0, 0};
    std::size_t rail_runs = 0;
    bool in_run = false, in_rails = false;
    for (std::uint32_t i = 0; i < m; ++i) {
      const std::uint32_t k = (start + i) % m;
      if (is_rail(k)) {
        const Half prev = hs[(k + m - 1) % m];
        const CEdge& pc = g.edges[prev.edge];
        const std::uint32_t joint = prev.reverse ? pc.a : pc.b;
        if (in_rails && !g.nodes[joint].ma) return kNone;  // a fan's empty side: not a strip
        if (!in_rails && ++rail_runs > 2) return kNone;
        rail_count[rail_runs - 1] += half_count(g, hs[k]);
        in_run = false;
        in_rails = true;
        continue;
      }
      if (!in_run) runs.emplace_back();
      in_run = true;
      in_rails = false;
      runs.back().push_back(k);
    }
    // Two sides of boundary pieces, two of rails as long as each other: matching the
    // boundary sides makes a grid.
    if (runs.size() != 2 || rail_runs != 2 || rail_count[0] != rail_count[1]) return kNone;
    std::uint32_t count[2] = {0, 0};
    for (int r = 0; r < 2; ++r)
      for (std::uint32_t k : runs[static_cast<std::size_t>(r)]) count[r] += half_count(g, hs[k]);
    if (count[0] == count[1]) return kNone;
    const int fewer = count[0] < count[1] ? 0 : 1;
    // The other run's mean edge, which the new edges should not fall far below.
    double other = 0.0;
    for (std::uint32_t k : runs[static_cast<std::size_t>(1 - fewer)])
      other += piece_length(g.edges[hs[k].edge]);
    other /= count[1 - fewer];
    std::uint32_t best = kNone;
    long long best_len = -1;
    for (std::uint32_t k : runs[static_cast<std::size_t>(fewer)]) {
      const CEdge& c = g.edges[hs[k].edge];
      if (!free_piece(c.edge, c.piece)) continue;  // only a free piece changes this face alone
      const double len = piece_length(c) / (edges_[c.edge].count[c.piece] + 1);
      if (settled_length(len) < settled_length(kStripMatchRel * other)) continue;
      const long long q = settled_length(len);
      if (q > best_len) {
        best = k;
        best_len = q;
      }
    }
    return best;
  }

  // ---- 4. parity ---------------------------------------------------------------------------
  /// Pairs every face with an odd edge count with the nearest other odd face, or with a free
  /// boundary piece (the "ground": a free piece changes the count of one face only), through
  /// a graph whose links are boundary pieces (free first, then pieces of two patches) and rail
  /// segments; every link on the path gets one more edge. Breadth first, so the path is the
  /// shortest, and a face with a free piece of its own takes it.
  void fix_parity() {
    std::vector<std::uint32_t> offset(part_.patches.size() + 1, 0);
    for (std::size_t p = 0; p < part_.patches.size(); ++p)
      offset[p + 1] = offset[p] + static_cast<std::uint32_t>(patches_[p].faces.size());
    const std::uint32_t nf = offset.back();
    const std::uint32_t ground = nf;
    // Faces of each piece (e, j): one per patch of e.
    std::vector<std::vector<std::vector<std::uint32_t>>> piece_faces(units_.size());
    for (std::size_t e = 0; e < units_.size(); ++e)
      piece_faces[e].resize(edges_[e].count.size());
    for (std::size_t p = 0; p < part_.patches.size(); ++p) {
      for (const CEdge& c : patches_[p].edges) {
        if (c.rail) continue;
        piece_faces[c.edge][c.piece].push_back(offset[p] + c.face[0]);
      }
    }
    struct Link {
      std::uint32_t to;
      std::uint32_t rank;  // 0 free piece, 1 two-patch piece, 2 rail
      std::uint32_t a, b;  // piece: (edge, piece); rail: (patch, coarse edge)
    };
    std::vector<std::vector<Link>> adj(nf + 1);
    for (std::uint32_t e = 0; e < piece_faces.size(); ++e) {
      for (std::uint32_t j = 0; j < piece_faces[e].size(); ++j) {
        const auto& f = piece_faces[e][j];
        if (f.size() == 1) {
          adj[f[0]].push_back({ground, 0, e, j});
          adj[ground].push_back({f[0], 0, e, j});
        } else if (f.size() == 2 && f[0] != f[1]) {
          adj[f[0]].push_back({f[1], 1, e, j});
          adj[f[1]].push_back({f[0], 1, e, j});
        }
      }
    }
    for (std::uint32_t p = 0; p < part_.patches.size(); ++p) {
      const PatchGraph& g = patches_[p];
      for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
        const CEdge& c = g.edges[e];
        if (!c.rail || c.face[0] == c.face[1]) continue;
        adj[offset[p] + c.face[0]].push_back({offset[p] + c.face[1], 2, p, e});
        adj[offset[p] + c.face[1]].push_back({offset[p] + c.face[0], 2, p, e});
      }
    }
    for (auto& a : adj)
      std::stable_sort(a.begin(), a.end(),
                       [](const Link& x, const Link& y) { return x.rank < y.rank; });
    // A strip (strip_piece) whose boundary runs differ in edge count takes its own extra edge
    // on the run with fewer edges, in the piece whose edges stay longest: the runs then match,
    // as a grid needs. Else the first free piece. (A thin ring whose outer arc has a B-Rep
    // vertex inside a track: the vertex's two pieces of one edge each got the edge, three
    // edges against one, worst corner 0.535; now two against two.)
    const auto free_piece = [&](std::uint32_t e, std::uint32_t j) {
      return piece_faces[e][j].size() == 1;
    };
    for (std::uint32_t p = 0; p < part_.patches.size(); ++p) {
      const PatchGraph& g = patches_[p];
      for (std::uint32_t f = 0; f < g.faces.size(); ++f) {
        const std::uint32_t take = strip_piece(g, f, free_piece);
        if (take == kNone) continue;
        auto& a = adj[offset[p] + f];
        const Half h = g.faces[f][take];
        const CEdge& c = g.edges[h.edge];
        const auto it = std::find_if(a.begin(), a.end(), [&](const Link& l) {
          return l.rank == 0 && l.a == c.edge && l.b == c.piece;
        });
        if (it == a.end()) continue;
        std::rotate(a.begin(), it, it + 1);
        if (face_count(g, f) % 2 != 0) ++result_.stats.parity_strips;
      }
    }
    std::vector<int> odd(nf + 1, 0);
    for (std::uint32_t p = 0; p < part_.patches.size(); ++p)
      for (std::uint32_t f = 0; f < patches_[p].faces.size(); ++f)
        odd[offset[p] + f] = static_cast<int>(face_count(patches_[p], f) % 2);
    std::vector<std::uint32_t> from(nf + 1), stamp(nf + 1, kNone);
    std::vector<const Link*> via(nf + 1, nullptr);
    for (std::uint32_t f = 0; f < nf; ++f) {
      if (!odd[f]) continue;
      std::deque<std::uint32_t> q{f};
      stamp[f] = f;
      std::uint32_t found = kNone;
      while (!q.empty() && found == kNone) {
        const std::uint32_t u = q.front();
        q.pop_front();
        for (const Link& l : adj[u]) {
          if (stamp[l.to] == f) continue;
          stamp[l.to] = f;
          from[l.to] = u;
          via[l.to] = &l;
          if (l.to == ground || odd[l.to]) {
            found = l.to;
            break;
          }
          if (l.to != ground) q.push_back(l.to);
        }
      }
      if (found == kNone) {
        std::uint32_t p = 0;
        while (offset[p + 1] <= f) ++p;
        throw InternalError("mesher: a face of " + part_.patch_label(PatchId(p)) +
                            " has an odd number of edges and nothing to pair it with (only "
                            "edges shared by three or more patches join it to the rest)");
      }
      for (std::uint32_t w = found; w != f; w = from[w]) {
        const Link& l = *via[w];
        if (l.rank == 2) {
          ++patches_[l.a].edges[l.b].count;
          ++result_.stats.parity_rails;
        } else {
          ++edges_[l.a].count[l.b];
          ++result_.stats.parity_boundary;
        }
      }
      odd[f] = 0;
      if (found != ground) odd[found] = 0;
    }
  }

  // ---- 5. nodes and quads -----------------------------------------------------------------
  void materialise_pieces() {
    for (std::size_t e = 0; e < units_.size(); ++e) {
      EdgeNodes& en = edges_[e];
      for (std::size_t j = 0; j < en.count.size(); ++j) {
        for (std::uint32_t k = 1; k < en.count[j]; ++k) {
          const double t = en.t[j] + (en.t[j + 1] - en.t[j]) * k / en.count[j];
          en.inner[j].push_back(add_node(unit_point(e, t)));
        }
      }
    }
  }

  /// Face f's boundary pieces, the one of the longest mesh edge first (ties by unit, then
  /// piece): what mesh_part may split when no template fills the face (UnfilledFace).
  std::vector<PieceRef> pieces_by_length(const PatchGraph& g, std::size_t f) const {
    struct Ranked {
      double edge;
      PieceRef piece;
    };
    std::vector<Ranked> ranked;
    for (const Half& h : g.faces[f]) {
      const CEdge& c = g.edges[h.edge];
      if (c.rail) continue;
      const double edge = piece_length(c) / edges_[c.edge].count[c.piece];
      ranked.push_back({edge, PieceRef{c.edge, c.piece}});
    }
    std::sort(ranked.begin(), ranked.end(), [](const Ranked& a, const Ranked& b) {
      if (a.edge != b.edge) return a.edge > b.edge;
      return std::make_pair(a.piece.unit, a.piece.piece) <
             std::make_pair(b.piece.unit, b.piece.piece);
    });
    std::vector<PieceRef> out;
    for (const Ranked& r : ranked)
      if (std::none_of(out.begin(), out.end(), [&](const PieceRef& o) {
            return o.unit == r.piece.unit && o.piece == r.piece.piece;
          }))
        out.push_back(r.piece);
    return out;
  }

  /// A face's cycle: its positions and sides (FaceInput), and its nodes' mesh ids.
  struct Pending {
    FaceInput in;
    std::vector<std::uint32_t> mesh_ids;
    std::string where;
  };

  /// Fills every face of every patch. A patch's MA and rail nodes are made first, patch by
  /// patch; then the faces of all the patches are filled on all cores (a face's fill reads
  /// only its own input; a shell of many small patches, each with few faces, keeps the cores
  /// busy: an icosphere of 1280 triangles, quads stage 0.56 -> 0.26 s); then each patch's
  /// inner nodes and quads are added in patch and face order, and the nodes are numbered as if
  /// each patch had been filled in turn (its rail nodes, then its faces' inner nodes), so the
  /// mesh is the same as filled one by one.
  void fill_patches() {
    const std::size_t np = part_.patches.size();
    std::vector<std::vector<Pending>> pending(np);
    std::vector<std::size_t> rails_from(np), rails_to(np);
    for (std::size_t p = 0; p < np; ++p) {
      rails_from[p] = result_.mesh.nodes.size();
      pending[p] = prepare_patch(PatchId(p));
      rails_to[p] = result_.mesh.nodes.size();
    }
    std::vector<std::pair<std::size_t, std::size_t>> jobs;  // (patch, face)
    std::vector<std::vector<FaceMesh>> filled(np);
    for (std::size_t p = 0; p < np; ++p) {
      filled[p].resize(pending[p].size());
      for (std::size_t f = 0; f < pending[p].size(); ++f) jobs.emplace_back(p, f);
    }
    // A face that is an earlier one moved takes its quads, moved: a large face (kSharedFaceNodes)
    // turned, mirrored, scaled or shifted, a small one (kSharedSmallFaceNodes) only turned,
    // scaled or shifted with its cycle from the same node. The first of its kind in job order
    // is filled, in every pose.
    struct Copy {
      std::size_t source;
      FaceMotion motion;
    };
    std::vector<std::optional<Copy>> copy(jobs.size());
    // Faces filled from scratch, by face_shape_key: only those whose keys are within the
    // tolerance are tried; small faces also by their first edge over their perimeter (squared:
    // a node off by the tolerance moves it by 4 x the tolerance over n at most), since their
    // copies start where they do. A shell of many equal facets (a cylinder's, a torus')
    // has thousands of small faces of one key.
    std::multimap<double, std::size_t> originals, small_originals;
    std::vector<double> lead(jobs.size(), 0.0);
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      const FaceInput& in = pending[jobs[j].first][jobs[j].second].in;
      const std::size_t n = in.cycle.size();
      const bool small = n < kSharedFaceNodes;
      if (n < kSharedSmallFaceNodes || (small && !g_small_face_sharing)) continue;
      const double key = face_shape_key(in);
      const double reach =
          16.0 * kCongruentTolerance * key;  // a node off by the tolerance moves it by 8x at most
      if (small) lead[j] = leading_edge_key(in);
      std::multimap<double, std::size_t>& pool = small ? small_originals : originals;
      for (auto it = pool.lower_bound(key - reach); it != pool.end() && it->first <= key + reach;
           ++it) {
        if (small && std::abs(lead[it->second] - lead[j]) > 16.0 * kCongruentTolerance) continue;
        const auto [p, f] = jobs[it->second];
        if (std::optional<FaceMotion> m = face_motion(pending[p][f].in, in, small)) {
          copy[j] = Copy{it->second, std::move(*m)};
          break;
        }
      }
      if (!copy[j]) pool.emplace(key, j);
    }
    const auto fill_jobs = [&](const std::vector<std::size_t>& which) {
      parallel_for(which.size(), [&](std::size_t w) {
        const auto [p, f] = jobs[which[w]];
        try {
          filled[p][f] =
              fill_face(pending[p][f].in, pending[p][f].where, needle_tips_, face_memo_);
        } catch (const InternalError& e) {
          if (!needle_tips_) throw;
          throw UnfilledFace(e.what(), pending[p][f].where, pending[p][f].in.cycle.size(),
                             pieces_by_length(patches_[p], f));
        }
      });
    };
    std::vector<std::size_t> first_pass;
    for (std::size_t j = 0; j < jobs.size(); ++j)
      if (!copy[j]) first_pass.push_back(j);
    // Faces of at most kSmallFaceFirst nodes first, then the others largest first (their
    // fills take longest), so that the threads end together; each fill goes to its own place,
    // so the order changes no result. The faces no template fills are most often small (a
    // needle's, a notch's), and a size that fails is known before the large faces' fills
    // (parallel_for starts no face after one that failed), for the retry at a smaller size.
    const auto nodes_of = [&](std::size_t j) {
      return pending[jobs[j].first][jobs[j].second].in.cycle.size();
    };
    std::stable_sort(first_pass.begin(), first_pass.end(), [&](std::size_t a, std::size_t b) {
      const bool small_a = nodes_of(a) <= kSmallFaceFirst, small_b = nodes_of(b) <= kSmallFaceFirst;
      if (small_a != small_b) return small_a;
      return !small_a && nodes_of(a) > nodes_of(b);
    });
    fill_jobs(first_pass);
    // A moved copy must score as its source did (up to rounding), else it is filled anew.
    std::vector<std::size_t> second_pass;
    for (std::size_t j = 0; j < jobs.size(); ++j) {
      if (!copy[j]) continue;
      const auto [p, f] = jobs[j];
      const FaceMesh& from = filled[jobs[copy[j]->source].first][jobs[copy[j]->source].second];
      FaceMesh moved = moved_fill(from, pending[p][f].in, copy[j]->motion);
      // A large face filled badly is filled anew (a mirrored copy may take another template);
      // a small face's copy starts and turns as its source, and takes what its source took.
      const bool small = pending[p][f].in.cycle.size() < kSharedFaceNodes;
      if ((small || from.min_jacobian >= kAcceptJacobian) &&
          moved.min_jacobian >= from.min_jacobian - kSharedFaceSlack) {
        filled[p][f] = std::move(moved);
        ++result_.stats.shared_faces;
      } else {
        second_pass.push_back(j);
      }
    }
    fill_jobs(second_pass);
    std::vector<std::size_t> inner_from(np), inner_to(np);
    for (std::size_t p = 0; p < np; ++p) {
      inner_from[p] = result_.mesh.nodes.size();
      emit_patch(PatchId(p), pending[p], filled[p]);
      inner_to[p] = result_.mesh.nodes.size();
    }
    // Renumber: the nodes before the first patch's rails stay; then per patch its rail nodes
    // and its inner nodes.
    std::vector<std::uint32_t> order(result_.mesh.nodes.size());
    std::size_t next = np > 0 ? rails_from[0] : result_.mesh.nodes.size();
    for (std::size_t v = 0; v < next; ++v) order[v] = static_cast<std::uint32_t>(v);
    const auto take = [&](std::size_t from, std::size_t to) {
      for (std::size_t v = from; v < to; ++v) order[v] = static_cast<std::uint32_t>(next++);
    };
    for (std::size_t p = 0; p < np; ++p) {
      take(rails_from[p], rails_to[p]);
      take(inner_from[p], inner_to[p]);
    }
    std::vector<Vec3> nodes(result_.mesh.nodes.size());
    for (std::size_t v = 0; v < nodes.size(); ++v) nodes[order[v]] = result_.mesh.nodes[v];
    result_.mesh.nodes = std::move(nodes);
    for (MeshElement& e : result_.mesh.elements)
      for (std::uint32_t& v : e.nodes) v = order[v];
  }

  /// A coarse node's round hole (a concave circle that the cut graph maps along rays,
  /// CutGraph::round_arcs): its radius, and the longest mesh edge on the whole circle.
  struct HoleFoot {
    double radius = 0.0;  ///< 0: on no round hole
    double edge = 0.0;
  };

  std::vector<HoleFoot> round_hole_feet(PatchId pid, const PatchGraph& g) const {
    std::vector<HoleFoot> feet(g.nodes.size());
    std::map<std::int32_t, double> longest;  // per circle
    for (const CEdge& c : g.edges) {
      const std::int32_t k = round_circle(pid, c);
      if (k >= 0)
        longest[k] = std::max(longest[k], piece_length(c) / edges_[c.edge].count[c.piece]);
    }
    for (const CEdge& c : g.edges) {
      const std::int32_t k = round_circle(pid, c);
      if (k < 0) continue;
      const double radius = part_.arcs[static_cast<std::size_t>(units_[c.edge].arc)].radius;
      feet[c.a] = feet[c.b] = {radius, longest[k]};
    }
    return feet;
  }

  /// Rings round a round hole (docs/mesher.md, "Graded rails at round holes"). A rail from a
  /// foot on a round hole of radius r0 runs along a ray from its centre; with `count` uniform
  /// steps of len / count its first ring of quads is a ring of trapezoids whose radii differ
  /// by (r0 + len / count) / r0. Where that exceeds kRingRatio, the rail's inner nodes are
  /// graded: the first m steps geometric at kRingRatio (radii r0 q^k), the rest uniform, m the
  /// least that keeps the uniform steps' ring within kRingRatio too. Not where even a rail
  /// geometric all the way could not (a hole far smaller than h: every ring would be that
  /// tapered instead of the first alone), nor round a hole with a mesh edge longer than
  /// kRingAspect x the first ring's width (a few wide chords: the ring would be slivers
  /// cutting into the hole). Returns the inner nodes' parameters along the rail (k = 1 ..
  /// count - 1), or nothing for uniform steps.
  static std::vector<double> graded_rail(const HoleFoot& foot, double len, std::uint32_t count) {
    const double r0 = foot.radius, q = kRingRatio * (1.0 + kRingTie);
    if (!(r0 > 0.0) || count < 2 || !(len > 0.0) || r0 + len / count <= q * r0) return {};
    if (foot.edge > kRingAspect * (kRingRatio - 1.0) * r0 * (1.0 + kRingTie)) return {};
    const double end = r0 + len;
    std::uint32_t m = 0;
    double rm = r0;
    while (m < count && rm * q < end && rm + (end - rm) / (count - m) > q * rm) {
      rm *= kRingRatio;
      ++m;
    }
    if (m == count) return {};
    std::vector<double> at;
    for (std::uint32_t k = 1; k < count; ++k) {
      const double radius = k <= m ? r0 * std::pow(kRingRatio, static_cast<double>(k))
                                   : rm + (end - rm) * (k - m) / (count - m);
      at.push_back((radius - r0) / len);
    }
    return at;
  }

  std::vector<Pending> prepare_patch(PatchId pid) {
    const Patch& patch = part_.patches[pid.index()];
    PatchGraph& g = patches_[pid.index()];
    // MA nodes and rail nodes.
    std::vector<bool> used(g.nodes.size(), false);
    for (const CEdge& c : g.edges) used[c.a] = used[c.b] = true;
    for (std::size_t i = 0; i < g.nodes.size(); ++i)
      if (g.nodes[i].ma && used[i]) g.nodes[i].mesh = add_node(patch.frame.to_3d(g.nodes[i].p));
    std::map<std::uint32_t, Vec2> pos2(g.boundary_2d);
    for (const CNode& c : g.nodes)
      if (c.ma && c.mesh != kNone) pos2[c.mesh] = c.p;
    const std::vector<HoleFoot> hole_feet = round_hole_feet(pid, g);
    for (CEdge& c : g.edges) {
      if (!c.rail) continue;
      const std::vector<double> at =
          graded_rail(hole_feet[c.a], distance(g.nodes[c.a].p, g.nodes[c.b].p), c.count);
      if (!at.empty()) ++result_.stats.graded_rails;
      for (std::uint32_t k = 1; k < c.count; ++k) {
        const double t = at.empty() ? static_cast<double>(k) / c.count : at[k - 1];
        const Vec2 p = lerp(g.nodes[c.a].p, g.nodes[c.b].p, t);
        c.inner.push_back(add_node(patch.frame.to_3d(p)));
        pos2[c.inner.back()] = p;
      }
    }
    // Boundary piece nodes in the patch frame.
    for (const CEdge& c : g.edges) {
      if (c.rail) continue;
      const EdgeNodes& en = edges_[c.edge];
      const auto& inner = en.inner[c.piece];
      const bool arc = units_[c.edge].arc >= 0;
      for (std::size_t k = 0; k < inner.size(); ++k) {
        const double s = static_cast<double>(k + 1) / en.count[c.piece];
        pos2[inner[k]] = arc ? patch.frame.to_2d(result_.mesh.nodes[inner[k]])
                             : lerp(g.nodes[c.a].p, g.nodes[c.b].p, c.forward ? s : 1.0 - s);
      }
    }
    std::vector<Pending> pending(g.faces.size());
    for (std::size_t f = 0; f < g.faces.size(); ++f) {
      auto cycle = g.faces[f];
      // Start where a side starts, so that no side wraps round the cycle's start.
      for (std::size_t k = 0; k < cycle.size(); ++k) {
        const Half hk = cycle[k];
        const bool r0 = g.edges[hk.edge].rail;
        const bool r1 = g.edges[cycle[(k + cycle.size() - 1) % cycle.size()].edge].rail;
        const std::uint32_t tail = hk.reverse ? g.edges[hk.edge].b : g.edges[hk.edge].a;
        if (r0 != r1 || (r0 && !g.nodes[tail].ma)) {
          std::rotate(cycle.begin(), cycle.begin() + static_cast<std::ptrdiff_t>(k), cycle.end());
          break;
        }
      }
      FaceInput& in = pending[f].in;
      std::vector<std::uint32_t>& mesh_ids = pending[f].mesh_ids;
      auto emit = [&](std::uint32_t id, bool free) {
        mesh_ids.push_back(id);
        in.cycle.push_back(pos2.at(id));
        in.free_nodes.push_back(free);  // an MA node or a rail's inner node: off the boundary
      };
      for (std::size_t k = 0; k < cycle.size(); ++k) {
        const Half h = cycle[k];
        const CEdge& c = g.edges[h.edge];
        const bool rail = c.rail;
        const auto here = static_cast<std::uint32_t>(in.cycle.size());
        const std::uint32_t tail = h.reverse ? c.b : c.a;
        auto open_side = [&](FaceSide::Kind kind) {
          FaceSide s;
          s.kind = kind;
          s.first = here;
          in.sides.push_back(s);
        };
        if (in.sides.empty() || (in.sides.back().kind == FaceSide::Kind::Rail) != rail) {
          open_side(rail ? FaceSide::Kind::Rail : FaceSide::Kind::Boundary);
        } else if (rail && g.nodes[tail].ma) {
          in.sides.back().joints.push_back(here - in.sides.back().first);
        } else if (rail) {
          // Two rails meeting at a boundary node (a concave corner's fan): a boundary side
          // without an edge between them.
          open_side(FaceSide::Kind::Boundary);
          open_side(FaceSide::Kind::Rail);
        }
        emit(g.nodes[tail].mesh, g.nodes[tail].ma);
        const std::vector<std::uint32_t>& inner =
            rail ? c.inner : edges_[c.edge].inner[c.piece];
        // Along the half-edge: rails are stored from a to b, pieces in the edge's direction.
        const bool backwards = rail ? h.reverse : (c.forward == h.reverse);
        for (std::size_t i = 0; i < inner.size(); ++i)
          emit(inner[backwards ? inner.size() - 1 - i : i], rail);
        in.sides.back().edges += static_cast<std::uint32_t>(inner.size()) + 1;
      }
      std::ostringstream where;
      const Vec3 x = patch.frame.to_3d(in.cycle.front());
      where << "face " << f << " of " << part_.patch_label(pid) << " (near " << x.x << ", " << x.y
            << ", " << x.z << ")";
      pending[f].where = where.str();
    }
    return pending;
  }

  /// A patch's faces, filled: their inner nodes and quads, in face order.
  void emit_patch(PatchId pid, std::vector<Pending>& pending, const std::vector<FaceMesh>& filled) {
    const Patch& patch = part_.patches[pid.index()];
    for (std::size_t f = 0; f < pending.size(); ++f) {
      const FaceMesh& fm = filled[f];
      ++result_.stats.faces;
      ++result_.stats.by_template[static_cast<std::size_t>(fm.kind)];
      if (fm.min_jacobian <= mesher_detail::kLastResortJacobian) ++result_.stats.needle_tip_faces;
      std::vector<std::uint32_t>& ids = pending[f].mesh_ids;
      for (const Vec2& p : fm.interior) ids.push_back(add_node(patch.frame.to_3d(p)));
      for (const auto& q : fm.quads) {
        MeshElement el;
        for (std::size_t k = 0; k < 4; ++k) el.nodes[k] = ids[q[k]];
        el.patch = pid;
        el.shell = static_cast<std::uint32_t>(patch.shell);
        result_.mesh.elements.push_back(el);
      }
    }
  }

  const Part& part_;
  const CutGraph& graph_;
  double h_;
  QuadResult result_;
  /// A straight B-Rep edge, or an arc (all its discretisation edges): nodes are laid per unit.
  struct Unit {
    std::int64_t arc = -1;  ///< index into Part::arcs, or -1
    EdgeId edge;            ///< the straight edge, or the arc's first discretisation edge
    VertexId a, b;          ///< ends: the edge's a and b, or the arc's from and to
  };
  std::vector<Unit> units_;
  std::vector<std::uint32_t> unit_of_edge_;
  std::vector<std::uint32_t> vertex_node_;
  std::vector<char> smooth_vertex_;  ///< per part vertex: tangent-continuous in all its loops
  std::vector<std::uint32_t> gcut_node_;
  /// Per mesh node made by make_boundary_nodes: a B-Rep vertex's (true) or a break's (false).
  std::vector<bool> is_vertex_node_;
  std::vector<EdgeNodes> edges_;
  std::vector<PatchGraph> patches_;
  const TrackWidthLaw* law_ = nullptr;
  bool sliver_caps_ = false;  ///< QuadOptions::drop_sliver_caps
  bool needle_tips_ = false;  ///< QuadOptions::needle_tips
  mesher_detail::FaceFillMemo* face_memo_ = nullptr;  ///< QuadOptions::face_memo
  std::vector<PieceRef> split_pieces_;  ///< QuadOptions::split_pieces
  std::vector<std::uint32_t> drop_hubs_;  ///< QuadOptions::drop_hubs
  /// Per arc, its discretisation edges: parameters of the edge's a and b along the arc.
  std::vector<std::vector<std::tuple<double, double, EdgeId>>> arc_edges_;
};

}  // namespace

void set_small_face_sharing(bool on) { g_small_face_sharing = on; }

QuadResult build_quads(const Part& part, const CutGraph& graph, const QuadOptions& options) {
  return QuadBuilder(part, graph, options).run();
}

std::size_t flip_edges(const Part& part, QuadMesh& mesh, std::vector<std::uint32_t>* flipped) {
  std::size_t flips = 0;
  const std::size_t nq = mesh.elements.size();
  // Settled (rounded to kJacobianGrain): two diagonals whose worst corners are equal but for
  // rounding (two corners of one value in a symmetric hexagon) are a tie, which the first
  // wins in every pose; unrounded, the pose's rounding chose (a random star scaled by 1e3
  // flipped the other diagonal, and its re-fill and count followed).
  auto jacobian = [&](const Frame& frame, const std::array<std::uint32_t, 4>& x) {
    return mesher_detail::settled(mesher_detail::min_scaled_jacobian(
        frame.to_2d(mesh.nodes[x[0]]), frame.to_2d(mesh.nodes[x[1]]),
        frame.to_2d(mesh.nodes[x[2]]), frame.to_2d(mesh.nodes[x[3]])));
  };
  for (int pass = 0; pass < kFlipPasses; ++pass) {
    // The quads at each node (compressed rows), and every quad's worst corner.
    std::vector<std::uint32_t> start(mesh.nodes.size() + 1, 0), at;
    for (const MeshElement& e : mesh.elements)
      for (std::uint32_t v : e.nodes) ++start[v + 1];
    for (std::size_t v = 0; v < mesh.nodes.size(); ++v) start[v + 1] += start[v];
    at.resize(start.back());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t q = 0; q < nq; ++q)
      for (std::uint32_t v : mesh.elements[q].nodes) at[fill[v]++] = q;
    std::vector<bool> touched(nq, false);
    std::size_t done = 0;
    for (std::uint32_t q = 0; q < nq; ++q) {
      if (touched[q]) continue;
      MeshElement& e1 = mesh.elements[q];
      const Frame& frame = part.patches[e1.patch.index()].frame;
      const double j1 = jacobian(frame, e1.nodes);
      if (j1 >= kFlipBelow) continue;
      // Of the pairs q makes with a neighbour across one of its edges, the best re-split.
      double best = -std::numeric_limits<double>::infinity();
      std::uint32_t best_other = 0;
      std::array<std::uint32_t, 6> best_hex{};
      std::size_t best_d = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        const std::uint32_t t = e1.nodes[k], s = e1.nodes[(k + 1) % 4];  // e1 runs t -> s
        std::uint32_t other = kNone, count = 0;
        for (std::uint32_t i = start[t]; i < start[t + 1]; ++i) {
          const std::uint32_t o = at[i];
          if (o == q || mesh.elements[o].patch.value != e1.patch.value) continue;
          const auto& x = mesh.elements[o].nodes;
          if (std::find(x.begin(), x.end(), s) == x.end()) continue;
          other = o;
          ++count;
        }
        if (count != 1 || touched[other]) continue;  // a patch boundary, or not manifold
        const MeshElement& e2 = mesh.elements[other];
        // The hexagon: e1 from s round to t, then e2 from t round to s (the shared edge runs
        // s -> t in e2). Diagonal 0-3 is the shared edge.
        std::size_t i2 = 0;
        while (e2.nodes[i2] != t) ++i2;
        if (e2.nodes[(i2 + 3) % 4] != s) continue;  // e2 turns the other way: leave it
        std::array<std::uint32_t, 6> hex;
        for (std::size_t m = 0; m < 3; ++m) hex[m] = e1.nodes[(k + 1 + m) % 4];
        for (std::size_t m = 0; m < 3; ++m) hex[3 + m] = e2.nodes[(i2 + m) % 4];
        std::array<std::uint32_t, 6> sorted = hex;
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
        const double now = std::min(j1, jacobian(frame, e2.nodes));
        for (std::size_t d = 1; d < 3; ++d) {
          const std::array<std::uint32_t, 4> q1{hex[d], hex[d + 1], hex[d + 2], hex[(d + 3) % 6]};
          const std::array<std::uint32_t, 4> q2{hex[(d + 3) % 6], hex[(d + 4) % 6], hex[(d + 5) % 6], hex[d]};
          const double j = std::min(jacobian(frame, q1), jacobian(frame, q2));
          if (j > now + kFlipGain && j > best) {
            best = j;
            best_other = other;
            best_hex = hex;
            best_d = d;
          }
        }
      }
      if (best_d == 0) continue;
      const auto& h = best_hex;
      const std::size_t d = best_d;
      e1.nodes = {h[d], h[d + 1], h[d + 2], h[(d + 3) % 6]};
      mesh.elements[best_other].nodes = {h[(d + 3) % 6], h[(d + 4) % 6], h[(d + 5) % 6], h[d]};
      touched[q] = touched[best_other] = true;
      if (flipped) flipped->insert(flipped->end(), {q, best_other});
      ++done;
    }
    flips += done;
    if (done == 0) break;
  }
  return flips;
}

void smooth_mesh(const Part& part,
                 QuadMesh& mesh,
                 int iterations,
                 const std::vector<bool>* movable) {
  if (iterations <= 0) return;
  // Nodes used by elements of several patches, or on an edge used once in a patch, stay.
  std::vector<bool> pinned = pinned_nodes(mesh);
  std::vector<std::vector<std::uint32_t>> by_patch = elements_by_patch(part, mesh);
  if (movable) {
    for (std::size_t v = 0; v < pinned.size(); ++v) pinned[v] = pinned[v] || !(*movable)[v];
    for (auto& elements : by_patch) {
      elements.erase(std::remove_if(elements.begin(), elements.end(),
                                    [&](std::uint32_t q) {
                                      const auto& x = mesh.elements[q].nodes;
                                      return std::none_of(x.begin(), x.end(), [&](std::uint32_t v) {
                                        return (*movable)[v];
                                      });
                                    }),
                     elements.end());
    }
  }
  // A patch's sweeps move only its own nodes (pinned nodes stay), so patches run in parallel;
  // a large patch's sweeps run in blocks (SweepSchedule), on all threads. The schedule
  // depends on the patch alone, so the result is the same however the patches are spread.
  const auto smooth_patch = [&](std::size_t p) {
    const Frame& frame = part.patches[p].frame;
    PatchQuads pq = patch_quads(part, mesh, p, by_patch[p], pinned);
    const SweepSchedule schedule = sweep_schedule(pq.pos.size(), pq.fixed, pq.quads);
    const std::vector<Vec2> before = pq.pos;
    final_sweeps(pq.pos, pq.fixed, pq.quads, iterations, kFinalUntangleTarget, &schedule);
    untaper_nodes(pq.pos, pq.fixed, pq.quads, iterations, &schedule);
    keep_worst(pq.pos, before, pq.quads);
    for (std::size_t i = 0; i < pq.global.size(); ++i)
      if (pq.pos[i] != before[i]) mesh.nodes[pq.global[i]] = frame.to_3d(pq.pos[i]);
  };
  // Largest first. A patch with more than a thread's share of the quads left would keep one
  // thread busy after the others are done: such patches one after another, each on all
  // threads; then the rest, each on one.
  std::vector<std::size_t> order = busy_patches(by_patch);
  std::size_t left = 0;
  for (std::size_t p : order) left += by_patch[p].size();
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return by_patch[a].size() > by_patch[b].size();
  });
  std::size_t first = 0;
  for (; first < order.size(); ++first) {
    const std::size_t quads = by_patch[order[first]].size();
    if (quads < 2 * kSweepBlockNodes || quads * worker_threads() <= left) break;
    smooth_patch(order[first]);
    left -= quads;
  }
  parallel_for(order.size() - first, [&](std::size_t i) { smooth_patch(order[first + i]); });
}

}  // namespace laytracks
