// Private: the rail layer of Algorithm II, shared by the cut graph and the removal of narrow
// corridors.
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <tuple>
#include <utility>
#include <vector>

#include "boundary_index.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

/// Two G-CUT-VERTs closer than this x the part size are one point (a rail closing a loop lands
/// on its start, up to rounding).
constexpr double kSamePointRel = 1e-7;
/// An MA point within this parameter distance of an edge's end is that end's vertex.
constexpr double kAtVertexT = 1e-9;
/// The sources' order (RailLayer::sources_in_boundary_order) compares their places along a
/// loop (segment index + parameter) and their branch points' radii (over the part's size) on
/// this grid: values within rounding of each other are ties in every pose.
constexpr double kSourceGrid = 1e-9;
/// Nodes of the rail network: a G-CUT-VERT index, or this flag with an MA-CUT-VERT index.
constexpr std::uint32_t kMaNodeFlag = 1u << 31;
/// A rail chain may cross this many shared edges per patch of the part (plus kMaxHopsExtra)
/// before it closes on the nearest existing point of its landing edge: a closed chain crosses
/// each shared edge at most a few times.
constexpr std::size_t kMaxHopsPerPatch = 2;
constexpr std::size_t kMaxHopsExtra = 8;
/// A rail chain that comes back to a shared edge it has crossed before lands on that earlier
/// crossing when it is within this x the medial radius at the rail's MA point (the rail then
/// leans by at most atan(0.25), 14 degrees): the loop closes. Round the drafted walls of a
/// tray the chain's landings drift by a few percent of the wall per lap and never meet their
/// start (Fig. 4 assumes they do); left open, the laps make slivers.
constexpr double kLoopCloseRel = 0.25;
/// A rail landing within this x the medial radius of an existing point of another chain lands
/// on it (leaning by at most 8.5 degrees): two rails that coincide on the exact part (a drafted
/// wall's corner rail and the floor's) would leave a sliver corridor between them. 0.05 until
/// session 16: on a faceted shell (an icosphere of 1280 triangles, three tracks a side) rails
/// from neighbouring facets ran 0.12 track widths apart across many facets, strips of quads
/// of aspect 8 (9.3% of the quads at aspect >= 5, worst corner 0.38; now 1.9% and 0.47, and
/// 17,744 -> 11,770 quads). The 20 test parts are unchanged in uniform mode (in adaptive mode
/// the bracket's worst corner 0.518 -> 0.445); of the 217 generated parts three change at
/// their default size, two at half size, and in adaptive mode 11 worst corners rise (three
/// folded flanges 0.27 -> 0.64), 6 fall.
constexpr double kCoincideRel = 0.15;
/// ... and within this x the track width there (when tracks are laid): at a third of
/// open_box's size its tracks (0.167) were closer than 0.05 x its walls' radius (0.3), and a
/// track rail landing between two others' points took whichever rounding made nearer, so the
/// box got 6959, 7038 or 7115 quads by pose.
constexpr double kCoincideTrack = 0.25;

/// Widths and distances that decide are compared on a grid of this x the part's size
/// (width_quantum): values within rounding of each other decide alike in every pose.
constexpr double kWidthGrainRel = 1e-9;
inline long long width_quantum(const Part& part, double x) {
  return std::llround(x / (kWidthGrainRel * part.size));
}

/// Small facets (join_source): two branch points on either side of a shared edge whose radii
/// are both below kSmallFacetRel x the track width (facets thinner than half a track there)
/// join their touching points on it within kSmallFacetJoin x the track width, not only within
/// the coincide limit: one rail per edge, and each such facet three kites round its incentre.
/// A torus of 96 x 48 triangle pairs at size 1.25 had each facet's and each neighbour's
/// touching points as rails of their own on every shared edge: 95,566 quads, ten a facet,
/// whatever the size asked; now 27,661 (docs/cutgraph.md, "Coincident rails").
constexpr double kSmallFacetRel = 0.25;
constexpr double kSmallFacetJoin = 1.0;
/// A track seed is not laid near a point that a rail reached across this many shared edges or
/// more (RailLayer::lay_from: crowded seeds).
constexpr std::uint32_t kCrowdSeedHops = 5;

class RailLayer {
 public:
  /// `track_width(radius)`: the track width at a medial radius, when tracks are laid (it bounds
  /// the landing merges, kCoincideTrack); empty when only source rails are.
  RailLayer(const Part& part, const std::vector<MedialAxis>& axes, CutGraph& graph,
            std::function<double(double)> track_width = {})
      : part_(part),
        axes_(axes),
        g_(graph),
        track_width_(std::move(track_width)),
        index_(part),
        registry_(part, kSamePointRel * part.size),
        max_hops_(static_cast<std::uint32_t>(kMaxHopsPerPatch * part.patches.size() + kMaxHopsExtra)) {}

  /// Registers the touching points of every branch point as sources and lays their rails.
  void lay_sources() {
    for (std::size_t p = 0; p < axes_.size(); ++p) {
      const PatchId pid(p);
      for (const Source& source : sources_in_boundary_order(axes_[p])) {
        const MaVertexId v = source.v;
        const BoundaryPoint& bp = source.bp;
        if (is_suppressed(part_.patches[p].frame.to_3d(bp.position))) continue;
        if (join_source(pid, v, bp)) continue;
        const GCutId g = gcut_of(pid, bp, nullptr);
        g_.gverts[g.index()].source = true;
        if (source_radius_.size() <= g.index()) source_radius_.resize(g.index() + 1, kNoRadius);
        source_radius_[g.index()] = axes_[p].vertex(v).radius;
        set_root(g, g);
        if (const auto corner = corner_in(pid, g)) {
          // A branch point touching a reflex corner: the rail is one ray of the corner's fan
          // (Fig. 13), laid here; the corner's other images end there.
          const LoopPoint at{corner->loop, corner->index, 0.0};
          const std::optional<CutVertId> known = cut_of(g, pid);
          const CutVertId c = known ? *known : make_cut(g, pid, at);
          const MaCutId mc = make_macut(pid, vertex_point(axes_[p], v));
          g_.segments.push_back({c, mc});
          links_.push_back({g.value, node_of(mc), pid, 0.0});
        }
        queue_.push_back(g);
      }
    }
    run();
  }

  /// A patch's branch points' touching points, in the order of their places along the
  /// patch's loops (loop, then segment index + parameter), ties by the branch point's radius
  /// (both on a grid of kSourceGrid), then as the axis lists them. The axis's numbering
  /// follows the Voronoi diagram's, which differs between poses of a part; the rails are laid
  /// breadth first from these sources, and where a rail lands beside an earlier one (joined
  /// sources, leans, loop closures) the order decided which was first (docs/cutgraph.md).
  struct Source {
    std::uint32_t loop;
    long long at;      // segment index + parameter along the loop, on the grid
    long long radius;  // the branch point's over the part's size, on the grid
    MaVertexId v;
    BoundaryPoint bp;
  };
  std::vector<Source> sources_in_boundary_order(const MedialAxis& ma) const {
    std::vector<Source> sources;
    for (MaVertexId v : ma.branch_points()) {
      const double r = ma.vertex(v).radius;
      for (const BoundaryPoint& bp : ma.touching_points(v)) {
        const double u = static_cast<double>(bp.site.index) +
                         (bp.site.kind == BoundarySite::Kind::Corner ? 0.0 : bp.s);
        sources.push_back({bp.site.loop, std::llround(u / kSourceGrid),
                           std::llround(r / (kSourceGrid * part_.size)), v, bp});
      }
    }
    std::stable_sort(sources.begin(), sources.end(), [](const Source& a, const Source& b) {
      return std::tie(a.loop, a.at, a.radius) < std::tie(b.loop, b.at, b.radius);
    });
    return sources;
  }

  /// Source points at these places are not laid: their rails were deleted (narrow corridors).
  void suppress(std::vector<Vec3> points) { suppressed_ = std::move(points); }

  /// Lays the rail through a boundary point of patch p (a track rail), and all it leads to;
  /// with `crowd_fraction` > 0, not when the seed is crowded (below).
  void lay_from(PatchId p, const BoundaryPoint& bp, double crowd_fraction = 0.0) {
    if (bp.site.kind != BoundarySite::Kind::Corner) {
      // A seed between a leaning rail's target and its landing: that rail is this seed's
      // (laying it would cross the leaning one).
      const EdgeId e = index_.edge_at(p, bp.site.loop, bp.site.index);
      const double t = index_.edge_param(p, bp.site.loop, bp.site.index, bp.s);
      if (inside_lean(e, t).valid()) return;
      // A crowded seed (docs/cutgraph.md, "Crowded rails"): within crowd_fraction x the track
      // width of a point that a rail reached across kCrowdSeedHops shared edges or more (a
      // track drifting round a band of thin triangles, lap after lap), its rail would run
      // beside that one.
      if (crowd_fraction > 0.0 && track_width_) {
        double gap = 0.0;
        const GCutId near = registry_.nearest(e, t, &gap);
        if (near.valid() && gap > registry_tolerance() && hops_of(near) >= kCrowdSeedHops) {
          // On the widths' grid: a gap within rounding of the reach decides alike in every pose.
          const std::optional<MaPoint> m = axes_[p.index()].project(bp);
          if (m && width_quantum(part_, gap) <
                       width_quantum(part_, crowd_fraction * track_width_(m->radius))) {
            ++g_.crowded_seeds;
            return;
          }
        }
      }
    }
    const GCutId g = gcut_of(p, bp, nullptr);
    if (!root_of(g).valid()) set_root(g, g);
    queue_.push_back(g);
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

  /// Where G-CUT-VERT g lies on patch p's boundary: its image on segment `seg` of `loop` if it
  /// has one there (an edge may bound a patch twice, along a seam), else its first on p.
  LoopPoint image_in(GCutId g, PatchId p, std::uint32_t loop, std::uint32_t seg) const {
    std::optional<LoopPoint> first;
    for (const auto& [q, at] : images(g)) {
      if (q != p) continue;
      if (at.loop == loop && at.segment == seg) return at;
      if (!first) first = at;
    }
    return *first;
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
    const BoundaryPoint bp = c.on_segment();
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
    const BoundaryPoint target = ma.touching_point(*m, ma.far_side(*m, bp));
    double gap = 0.0;
    // A rail that has crossed more shared edges than a closed chain could need without closing
    // (a spiral round the draft walls of a tray, whose landings never meet their start) ends
    // on the landing edge's nearest existing point instead of making another.
    const std::uint32_t hop = hops_of(c.g) + 1;
    const GCutId root = root_of(c.g);
    GCutId g2;
    if (target.site.kind != BoundarySite::Kind::Corner) {
      const EdgeId te = index_.edge_at(p, target.site.loop, target.site.index);
      const double tt = index_.edge_param(p, target.site.loop, target.site.index, target.s);
      // A target between a leaning rail's own target and its landing would cross it: it lands
      // there too.
      g2 = inside_lean(te, tt);
      if (g2.valid()) {
        gap = std::abs(param_on(g2, te) - tt) * edge_length(te);
        ++g_.rail_merges;
      }
      if (!g2.valid() && hop > max_hops_) {
        g2 = registry_.nearest(te, tt, &gap);
        if (g2.valid()) ++g_.spiral_closures;  // its gap is not a closure error
      }
      // Closures and merges only where the chain goes on (a shared edge): on a free edge it
      // ends, and narrow corridors there are removed as usual.
      const bool shared = is_shared(te);
      if (!g2.valid() && shared && root.valid()) {
        double d = 0.0;
        const GCutId own = registry_.nearest_if(
            te, tt, [&](GCutId x) { return root_of(x) == root; }, &d);
        if (own.valid() && d > registry_tolerance() && d <= kLoopCloseRel * m->radius) {
          // Land on the existing point nearest the target on the way to that crossing (the
          // crossing, unless another chain's rail lands between): the leaning rail crosses none.
          const double to = param_on(own, te);
          g2 = registry_.nearest_if(
              te, tt,
              [&](GCutId x) {
                const double u = param_on(x, te);
                return (u - tt) * (u - to) <= 0.0;
              },
              &gap);
          ++g_.loop_closures;  // nor is this one
        }
      }
      if (!g2.valid() && shared) {
        g2 = coincident(te, tt, m->radius, [](GCutId) { return true; }, &gap);
        if (g2.valid()) ++g_.rail_merges;
      }
      if (g2.valid()) add_lean(te, tt, g2);
    }
    const bool leans = g2.valid();
    if (!leans) {
      g2 = gcut_of(p, target, &gap);
      g_.max_landing_gap = std::max(g_.max_landing_gap, gap);
    }
    if (g2.index() >= hops_.size()) hops_.resize(g2.index() + 1, hop);
    if (!root_of(g2).valid()) set_root(g2, root);
    std::optional<CutVertId> landed = cut_of(g2, p);
    if (!landed) {
      LoopPoint at{target.site.loop, target.site.index,
                   target.site.kind == BoundarySite::Kind::Corner ? 0.0 : target.s};
      if (leans) at = image_in(g2, p, target.site.loop, target.site.index);
      landed = make_cut(g2, p, at);
    }
    g_.segments.push_back({*landed, mc, leans});
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
    const double tol = registry_tolerance();
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

  /// The G-CUT-VERT whose rail chain reached g (itself for sources and seeds).
  GCutId root_of(GCutId g) const { return g.index() < roots_.size() ? roots_[g.index()] : GCutId(); }
  void set_root(GCutId g, GCutId root) {
    if (g.index() >= roots_.size()) roots_.resize(g.index() + 1);
    roots_[g.index()] = root;
  }
  /// The point a leaning rail landed on whose span on edge e holds parameter t, if any.
  GCutId inside_lean(EdgeId e, double t) const {
    const auto it = leans_.find(e.value);
    if (it == leans_.end()) return {};
    // Ends included, within the point tolerance: a target at a leaning rail's own target (a
    // rail through the same MA point) decides the same in every pose.
    const double tol = registry_tolerance() / edge_length(e);
    for (const Lean& l : it->second) {
      if (t >= l.lo - tol && t <= l.hi + tol) return l.point;
    }
    return {};
  }

  double edge_length(EdgeId e) const {
    const BrepEdge& edge = part_.edges[e.index()];
    return distance(part_.vertices[edge.a.index()].position,
                    part_.vertices[edge.b.index()].position);
  }

  /// The parameter of G-CUT-VERT g along edge e (one of its edges).
  double param_on(GCutId g, EdgeId e) const {
    const GCutVert& gv = g_.gverts[g.index()];
    if (gv.vertex) return part_.edges[e.index()].a == *gv.vertex ? 0.0 : 1.0;
    return gv.t;
  }
  double registry_tolerance() const { return kSamePointRel * part_.size; }

  /// Joined sources (docs/cutgraph.md, "Coincident rails"): a touching point of branch point v
  /// of patch p on a shared edge, within the coincide limit of the touching point of an earlier
  /// patch's branch point on that edge (or, both branch points of small facets, within
  /// kSmallFacetJoin x the track width), is not a source of its own: the rail from v leans to
  /// that point, and the two branch points are joined by one rail chain. (On a shell of
  /// irregular triangles each shared edge holds both facets' incircle touching points a few
  /// hundredths of an element apart; each pair made two chains side by side and a sliver
  /// between them.) Sources are registered patch by patch before any rail is laid, so the
  /// earlier patch is the lower index, the same in every pose. True when joined.
  bool join_source(PatchId p, MaVertexId v, const BoundaryPoint& bp) {
    if (bp.site.kind == BoundarySite::Kind::Corner) return false;
    const EdgeId e = index_.edge_at(p, bp.site.loop, bp.site.index);
    if (!is_shared(e)) return false;
    const double t = index_.edge_param(p, bp.site.loop, bp.site.index, bp.s);
    const MedialAxis& ma = axes_[p.index()];
    const double r = ma.vertex(v).radius;
    double d = 0.0;
    const GCutId near = registry_.nearest_if(
        e, t, [&](GCutId x) { return !g_.gverts[x.index()].vertex && !cut_of(x, p); }, &d);
    if (!near.valid() || d <= registry_tolerance()) return false;
    // The coincide limit; small facets on both sides (kSmallFacetRel) kSmallFacetJoin x the
    // track width.
    const auto small = [&](double radius) {
      return track_width_ && radius < kSmallFacetRel * track_width_(radius);
    };
    const double reach = small(r) && near.index() < source_radius_.size() &&
                                 small(source_radius_[near.index()])
                             ? std::max(coincide_limit(r), kSmallFacetJoin * track_width_(r))
                             : coincide_limit(r);
    if (d > reach) return false;
    const CutVertId c = make_cut(near, p, image_in(near, p, bp.site.loop, bp.site.index));
    const MaCutId mc = make_macut(p, vertex_point(ma, v));
    g_.segments.push_back({c, mc, true});
    links_.push_back({near.value, node_of(mc), p, d});
    add_lean(e, t, near);
    ++g_.rail_merges;
    return true;
  }

  /// Axis vertex v as a point on its first edge.
  static MaPoint vertex_point(const MedialAxis& ma, MaVertexId v) {
    MaPoint m;
    m.edge = ma.incident(v).front();
    m.t = ma.edge(m.edge).a == v ? 0.0 : 1.0;
    m.position = ma.vertex(v).position;
    m.radius = ma.vertex(v).radius;
    return m;
  }

  bool is_shared(EdgeId e) const { return part_.edges[e.index()].patches.size() >= 2; }

  /// The coincide rule, for landings and joined sources: the nearest accepted point inside
  /// edge e (not at a vertex) to parameter t, if it lies beyond the point tolerance and within
  /// the coincide limit for medial radius r (its distance in *d); else invalid.
  GCutId coincident(EdgeId e, double t, double r, const std::function<bool(GCutId)>& accept,
                    double* d) const {
    const GCutId near = registry_.nearest_if(
        e, t, [&](GCutId x) { return !g_.gverts[x.index()].vertex && accept(x); }, d);
    if (near.valid() && *d > registry_tolerance() && *d <= coincide_limit(r)) return near;
    return {};
  }

  /// Records that a rail aimed at parameter t of edge e landed on point g instead.
  void add_lean(EdgeId e, double t, GCutId g) {
    const double x = param_on(g, e);
    leans_[e.value].push_back({std::min(x, t), std::max(x, t), g});
  }

  /// How close to another chain's point a rail landing at medial radius r lands on it.
  double coincide_limit(double r) const {
    const double limit = kCoincideRel * r;
    return track_width_ ? std::min(limit, kCoincideTrack * track_width_(r)) : limit;
  }

  bool is_suppressed(Vec3 x) const {
    const double tol = registry_tolerance();
    return std::any_of(suppressed_.begin(), suppressed_.end(),
                       [&](Vec3 q) { return distance(q, x) <= tol; });
  }

  const Part& part_;
  const std::vector<MedialAxis>& axes_;
  CutGraph& g_;
  std::function<double(double)> track_width_;
  BoundaryIndex index_;
  GCutRegistry registry_;
  std::uint32_t max_hops_;
  /// Per source G-CUT-VERT: the radius of its branch point (kNoRadius for other points).
  static constexpr double kNoRadius = std::numeric_limits<double>::infinity();
  std::vector<double> source_radius_;
  std::vector<std::uint32_t> hops_;  ///< per G-CUT-VERT: see hops_of
  std::vector<GCutId> roots_;        ///< per G-CUT-VERT: see root_of
  /// Per edge: the span between a leaning rail's target and the point it landed on.
  struct Lean {
    double lo = 0.0;
    double hi = 0.0;
    GCutId point;
  };
  std::map<std::uint32_t, std::vector<Lean>> leans_;
  std::deque<GCutId> queue_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, CutVertId> cut_at_;
  std::map<std::pair<std::uint32_t, std::uint32_t>, MaCutId> branch_at_;
  std::vector<Link> links_;
  std::vector<Vec3> suppressed_;
};

}  // namespace laytracks::cutgraph_detail
