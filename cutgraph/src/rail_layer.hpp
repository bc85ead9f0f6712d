// Private: the rail layer of Algorithm II, shared by the cut graph and the removal of narrow
// corridors.
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <sstream>

#include "boundary_index.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

/// Two G-CUT-VERTs closer than this x the part size are one point (a rail closing a loop lands
/// on its start, up to rounding).
constexpr double kSamePointRel = 1e-7;
/// An MA point within this parameter distance of an edge's end is that end's vertex.
constexpr double kAtVertexT = 1e-9;
/// Nodes of the rail network: a G-CUT-VERT index, or this flag with an MA-CUT-VERT index.
constexpr std::uint32_t kMaNodeFlag = 1u << 31;
/// A rail chain may cross this many shared edges per patch of the part (plus kMaxHopsExtra)
/// before it closes on the nearest existing point of its landing edge: a closed chain crosses
/// each shared edge at most a few times.
constexpr std::size_t kMaxHopsPerPatch = 2;
constexpr std::size_t kMaxHopsExtra = 8;

class RailLayer {
 public:
  RailLayer(const Part& part, const std::vector<MedialAxis>& axes, CutGraph& graph)
      : part_(part),
        axes_(axes),
        g_(graph),
        index_(part),
        registry_(part, kSamePointRel * part.size),
        max_hops_(static_cast<std::uint32_t>(kMaxHopsPerPatch * part.patches.size() + kMaxHopsExtra)) {}

  /// Registers the touching points of every branch point as sources and lays their rails.
  void lay_sources() {
    for (std::size_t p = 0; p < axes_.size(); ++p) {
      const PatchId pid(p);
      for (MaVertexId v : axes_[p].branch_points()) {
        for (const BoundaryPoint& bp : axes_[p].touching_points(v)) {
          if (is_suppressed(part_.patches[p].frame.to_3d(bp.position))) continue;
          const GCutId g = gcut_of(pid, bp, nullptr);
          g_.gverts[g.index()].source = true;
          if (const auto corner = corner_in(pid, g)) {
            // A branch point touching a reflex corner: the rail is one ray of the corner's fan
            // (Fig. 13), laid here; the corner's other images end there.
            const LoopPoint at{corner->loop, corner->index, 0.0};
            const std::optional<CutVertId> known = cut_of(g, pid);
            const CutVertId c = known ? *known : make_cut(g, pid, at);
            MaPoint m;
            const MedialAxis& ma = axes_[p];
            m.edge = ma.incident(v).front();
            m.t = ma.edge(m.edge).a == v ? 0.0 : 1.0;
            m.position = ma.vertex(v).position;
            m.radius = ma.vertex(v).radius;
            const MaCutId mc = make_macut(pid, m);
            g_.segments.push_back({c, mc});
            links_.push_back({g.value, node_of(mc), pid, 0.0});
          }
          queue_.push_back(g);
        }
      }
    }
    run();
  }

  /// Source points at these places are not laid: their rails were deleted (narrow corridors).
  void suppress(std::vector<Vec3> points) { suppressed_ = std::move(points); }

  /// Lays the rail through a boundary point of patch p (a track rail), and all it leads to.
  void lay_from(PatchId p, const BoundaryPoint& bp) {
    queue_.push_back(gcut_of(p, bp, nullptr));
    run();
  }

  /// The CUT-VERT of G-CUT-VERT g on patch p, if one was made.
  std::optional<CutVertId> cut_of(GCutId g, PatchId p) const {
    const auto it = cut_at_.find({g.value, p.value});
    if (it == cut_at_.end()) return std::nullopt;
    return it->second;
  }

  /// Per landing: the two G-CUT-VERTs a rail piece joins in a patch, through an MA-CUT-VERT.
  struct Link {
    std::uint32_t from;  ///< node: a G-CUT-VERT index, or kMaNodeFlag | an MA-CUT-VERT index
    std::uint32_t to;
    PatchId patch;
    double gap = 0.0;
  };
  const std::vector<Link>& links() const { return links_; }

 private:
  /// Breadth first over the queued G-CUT-VERTs: each unvisited image lays its rail.
  void run() {
    while (!queue_.empty()) {
      const GCutId g = queue_.front();
      queue_.pop_front();
      for (const auto& [p, at] : images(g)) {
        if (cut_at_.count({g.value, p.value})) continue;  // visited
        const CutVertId c = make_cut(g, p, at);
        lay_rail(c);
      }
    }
  }

  std::vector<std::pair<PatchId, LoopPoint>> images(GCutId id) const {
    const GCutVert& g = g_.gverts[id.index()];
    std::vector<std::pair<PatchId, LoopPoint>> out;
    if (g.vertex) {
      for (const auto& c : index_.corners_of(*g.vertex))
        out.push_back({c.patch, {c.loop, c.index, 0.0}});
      return out;
    }
    for (const auto& s : index_.segments_of(g.edge)) {
      out.push_back({s.patch, {s.loop, s.seg, s.forward ? g.t : 1.0 - g.t}});
    }
    return out;
  }

  CutVertId make_cut(GCutId g, PatchId p, const LoopPoint& at) {
    CutVert c;
    c.g = g;
    c.patch = p;
    c.at = at;
    const auto& loop = part_.patches[p.index()].polygon.loops[at.loop];
    c.position = lerp(loop[at.segment], loop[(at.segment + 1) % loop.size()], at.s);
    const CutVertId id(g_.cuts.size());
    g_.cuts.push_back(c);
    cut_at_[{g.value, p.value}] = id;
    return id;
  }

  /// The corner of patch p where G-CUT-VERT g sits, if g is at a B-Rep vertex.
  std::optional<cutgraph_detail::CornerRef> corner_in(PatchId p, GCutId g) const {
    const GCutVert& gv = g_.gverts[g.index()];
    if (!gv.vertex) return std::nullopt;
    for (const auto& c : index_.corners_of(*gv.vertex)) {
      if (c.patch == p) return c;
    }
    return std::nullopt;
  }

  /// The G-CUT-VERT at a boundary point of patch p (a segment point or a corner).
  GCutId gcut_of(PatchId p, const BoundaryPoint& bp, double* gap) {
    bool created = false;
    double d = 0.0;
    GCutId id;
    if (bp.site.kind == BoundarySite::Kind::Corner) {
      const VertexId v = part_.patches[p.index()].loops[bp.site.loop].vertices[bp.site.index];
      id = registry_.find_or_add_vertex(v, g_.gverts, &created);
    } else {
      const EdgeId e = index_.edge_at(p, bp.site.loop, bp.site.index);
      id = registry_.find_or_add(e, index_.edge_param(p, bp.site.loop, bp.site.index, bp.s),
                                 g_.gverts, &d, &created);
    }
    if (gap) *gap = d;
    return id;
  }

  /// The rail from CUT-VERT c into its patch: to the MA, and on to the other side(s).
  void lay_rail(CutVertId cid) {
    const CutVert c = g_.cuts[cid.index()];
    const PatchId p = c.patch;
    BoundaryPoint bp;
    bp.site = {BoundarySite::Kind::Segment, c.at.loop, c.at.segment};
    bp.s = c.at.s;
    bp.position = c.position;
    if (c.at.s == 0.0 && g_.gverts[c.g.index()].vertex) {
      const int turn = corner_turn(part_, p, c.at.loop, c.at.segment);
      if (turn != 0) return;  // a rail ends at a corner: concave (fan) or convex (length 0)
    }
    const MedialAxis& ma = axes_[p.index()];
    const std::optional<MaPoint> m = ma.project(bp);
    if (!m) {
      problem("a rail from " + where(cid) + " found no medial axis point");
      return;
    }
    const MaCutId mc = make_macut(p, *m);
    g_.segments.push_back({cid, mc});
    const MaCutVert& mcv = g_.macuts[mc.index()];
    if (mcv.branch || mcv.round_end) {
      // The touching points of a branch point are the sources: their CUT-VERTs exist or will.
      // At the centre of a rounded corner the rails of the arc meet, and end.
      links_.push_back({c.g.value, node_of(mc), p, 0.0});
      return;
    }
    const MaEdge& e = ma.edge(m->edge);
    const Side other = e.left == bp.site ? Side::Right : Side::Left;
    const BoundaryPoint target = ma.touching_point(*m, other);
    double gap = 0.0;
    // A rail that has crossed more shared edges than a closed chain could need without closing
    // (a spiral round the draft walls of a tray, whose landings never meet their start) ends
    // on the landing edge's nearest existing point instead of making another.
    const std::uint32_t hop = hops_of(c.g) + 1;
    GCutId g2;
    if (hop > max_hops_ && target.site.kind != BoundarySite::Kind::Corner) {
      g2 = registry_.nearest(index_.edge_at(p, target.site.loop, target.site.index),
                             index_.edge_param(p, target.site.loop, target.site.index, target.s),
                             &gap);
    }
    if (g2.valid()) {
      ++g_.spiral_closures;  // its gap is not a closure error: not in max_landing_gap
    } else {
      g2 = gcut_of(p, target, &gap);
      g_.max_landing_gap = std::max(g_.max_landing_gap, gap);
    }
    if (g2.index() >= hops_.size()) hops_.resize(g2.index() + 1, hop);
    std::optional<CutVertId> landed = cut_of(g2, p);
    if (!landed) {
      LoopPoint at{target.site.loop, target.site.index,
                   target.site.kind == BoundarySite::Kind::Corner ? 0.0 : target.s};
      landed = make_cut(g2, p, at);
    }
    g_.segments.push_back({*landed, mc});
    links_.push_back({c.g.value, g2.value, p, gap});
    queue_.push_back(g2);
  }

  MaCutId make_macut(PatchId p, const MaPoint& m) {
    const MedialAxis& ma = axes_[p.index()];
    if (!m.edge.valid()) {
      // The axis is a single point (a polygonised disk): every rail ends at its centre.
      const auto it = branch_at_.find({p.value, 0u});
      if (it != branch_at_.end()) return it->second;
      MaCutVert mc;
      mc.patch = p;
      mc.point = m;
      mc.vertex = MaVertexId(std::size_t{0});
      mc.round_end = true;
      const MaCutId id(g_.macuts.size());
      g_.macuts.push_back(mc);
      branch_at_[{p.value, 0u}] = id;
      return id;
    }
    const MaEdge& e = ma.edge(m.edge);
    // At a vertex when within the point tolerance of it (a distance, not a parameter: the
    // same decision in every pose and at every scale).
    std::optional<MaVertexId> v;
    const double tol = kSamePointRel * part_.size;
    if (m.t <= kAtVertexT || distance(m.position, ma.vertex(e.a).position) <= tol) v = e.a;
    if (m.t >= 1.0 - kAtVertexT || distance(m.position, ma.vertex(e.b).position) <= tol) v = e.b;
    const bool branch = v && ma.vertex(*v).degree >= 3;
    const bool round_end = v && ma.vertex(*v).degree == 1 && ma.vertex(*v).radius > 0.0;
    if (branch || round_end) {
      const auto it = branch_at_.find({p.value, v->value});
      if (it != branch_at_.end()) return it->second;
    }
    MaCutVert mc;
    mc.patch = p;
    mc.point = m;
    mc.vertex = v;
    mc.branch = branch;
    mc.round_end = round_end;
    const MaCutId id(g_.macuts.size());
    g_.macuts.push_back(mc);
    if (branch || round_end) branch_at_[{p.value, v->value}] = id;
    return id;
  }

  static std::uint32_t node_of(MaCutId m) { return kMaNodeFlag | m.value; }

  std::string where(CutVertId c) const {
    const CutVert& cv = g_.cuts[c.index()];
    const Vec3 x = g_.gverts[cv.g.index()].position;
    std::ostringstream s;
    s << part_.patch_label(cv.patch) << " at (" << x.x << ", " << x.y << ", " << x.z << ")";
    return s.str();
  }

  void problem(const std::string& what) { g_.problems.push_back(what); }

  /// Shared edges crossed by the rail that reached G-CUT-VERT g (0 for sources and seeds).
  std::uint32_t hops_of(GCutId g) const { return g.index() < hops_.size() ? hops_[g.index()] : 0; }

  bool is_suppressed(Vec3 x) const {
    const double tol = kSamePointRel * part_.size;
    return std::any_of(suppressed_.begin(), suppressed_.end(),
                       [&](Vec3 q) { return distance(q, x) <= tol; });
  }

  const Part& part_;
  const std::vector<MedialAxis>& axes_;
  CutGraph& g_;
  BoundaryIndex index_;
  GCutRegistry registry_;
  std::uint32_t max_hops_;
  std::vector<std::uint32_t> hops_;  ///< per G-CUT-VERT: see hops_of
  std::deque<GCutId> queue_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, CutVertId> cut_at_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, MaCutId> branch_at_;
  std::vector<Link> links_;
  std::vector<Vec3> suppressed_;
};

}  // namespace laytracks::cutgraph_detail
