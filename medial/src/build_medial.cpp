// From the segment Voronoi diagram to the medial axis of a polygon:
//   voronoi -> refine vertices -> keep interior edges -> merge coincident vertices
//   -> prune the branches of smooth corners -> compact -> self-check.
// The rules are written down in docs/medial.md.
#include <algorithm>
#include <limits>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>

#include "laytracks/brep/error.hpp"
#include "laytracks/brep/union_find.hpp"
#include "laytracks/medial/medial_axis.hpp"
#include "sites.hpp"
#include "voronoi.hpp"

namespace laytracks {
namespace {

using medial_detail::is_endpoint_of;
using medial_detail::kMergeRel;
using medial_detail::VoronoiDiagram;

/// Convex corners turning by more than this (radians) must end a branch of the axis
/// (Extractor::unreached_corners); below it a corner's branch is too thin to insist on.
constexpr double kCheckedTurn = 1e-3;

/// Convex corners turning by less than this (radians) are straight to rounding: a vertex on a
/// straight edge of a patch in 3D turns by +-1e-15 or so in the patch's plane, and by the sign
/// of that rounding grows a branch of the axis (along the normal there) or not. Such a branch
/// is pruned as if the diagram had none (prune_smooth_branches). A corner convex by 4e-11
/// (test_backends) still ends its branch.
constexpr double kStraightTurn = 1e-12;

/// ... or by less than this many times the rounding of its corners' coordinates over its
/// shorter side (MedialOptions::coordinate_scale): a coastline's corner 71 units from the
/// origin between sides of 0.0029 and 0.0147 turned by 7e-14 as given and by 1.9e-12 in the
/// part scaled by 1e-3, and grew a branch there (cgal_norway_85: 1,029 quads against 1,038).
/// That rounding is 5.5e-12 here; a corner that is meant turns by far more (test_backends' by
/// 4e-11 between sides of 0.5, where the rounding is 4e-16).
constexpr double kStraightNoise = 64.0;

/// After pruning smooth branches, interior leaf edges shorter than this x the chord tolerance
/// are discretisation artefacts (where a polygonised arc meets a straight edge) and go too.
constexpr double kStubChordFactor = 4.0;

/// The working graph between extraction and the final MedialAxis.
struct Graph {
  std::vector<MaVertex> vertices;
  std::vector<MaEdge> edges;
  std::vector<bool> edge_alive;
  std::vector<std::vector<std::uint32_t>> incident;  // alive or not
  std::vector<std::uint32_t> original_degree;

  std::uint32_t degree(std::uint32_t v) const {
    std::uint32_t d = 0;
    for (std::uint32_t e : incident[v]) d += edge_alive[e] ? 1u : 0u;
    return d;
  }
  std::uint32_t only_edge(std::uint32_t v) const {
    for (std::uint32_t e : incident[v]) {
      if (edge_alive[e]) return e;
    }
    return 0;
  }
  std::uint32_t other(std::uint32_t e, std::uint32_t v) const {
    const auto a = static_cast<std::uint32_t>(edges[e].a.index());
    const auto b = static_cast<std::uint32_t>(edges[e].b.index());
    return a == v ? b : a;
  }
};

class Extractor {
 public:
  Extractor(const Polygon2& polygon, const MedialOptions& options)
      : poly_(polygon), options_(options) {
    Box2 box;
    for (const auto& loop : poly_.loops) {
      for (Vec2 p : loop) box.add(p);
    }
    size_ = box.diagonal();
    centre_ = lerp(box.lo, box.hi, 0.5);
    // Smooth corners: tangent-continuous ones, and convex ones turning by less than flat_turn.
    smooth_ = poly_.smooth;
    smooth_.resize(poly_.loops.size());
    for (std::size_t l = 0; l < poly_.loops.size(); ++l) {
      const auto& loop = poly_.loops[l];
      const std::size_t n = loop.size();
      smooth_[l].resize(n, false);
      for (std::size_t i = 0; i < n && options_.flat_turn > 0.0; ++i) {
        const double turn = corner_turn(l, i);
        if (turn > 0.0 && turn < options_.flat_turn) smooth_[l][i] = true;
      }
    }
  }

  /// Problems of `ma` (this extractor's axis): the convex corners, not smooth and turning by
  /// more than kCheckedTurn, that no axis vertex sits on. Each such corner ends a branch, the
  /// bisector of its two sides, and pruning takes only smooth corners' branches. (Boost's
  /// diagram of a staircase outline given in its own plane, a step's corner cocircular with
  /// the next run's middle vertex and the step's reflex corner, lost that corner's branch:
  /// connected, a tree, every vertex at its radius, so every other check passed; turned in 3D,
  /// and with CGAL, the branch was there. Fuzz seed 38039, extreme_067.)
  std::vector<std::string> unreached_corners(const MedialAxis& ma) const {
    std::vector<std::vector<bool>> reached(poly_.loops.size());
    for (std::size_t l = 0; l < poly_.loops.size(); ++l)
      reached[l].assign(poly_.loops[l].size(), false);
    for (const MaVertex& v : ma.vertices())
      if (v.corner && v.corner->loop < reached.size() &&
          v.corner->index < reached[v.corner->loop].size())
        reached[v.corner->loop][v.corner->index] = true;
    std::vector<std::string> problems;
    for (std::size_t l = 0; l < poly_.loops.size(); ++l) {
      for (std::size_t i = 0; i < poly_.loops[l].size(); ++i) {
        if (reached[l][i] || smooth_[l][i] || !(corner_turn(l, i) > kCheckedTurn)) continue;
        problems.push_back("convex corner " + std::to_string(i) + " of loop " + std::to_string(l) +
                           " ends no branch of the axis");
      }
    }
    return problems;
  }

  /// The angle the boundary turns by at corner i of loop l (radians, > 0 at a convex corner).
  double corner_turn(std::size_t l, std::size_t i) const {
    const auto& loop = poly_.loops[l];
    const std::size_t n = loop.size();
    const Vec2 in = loop[i] - loop[(i + n - 1) % n], out = loop[(i + 1) % n] - loop[i];
    return std::atan2(cross(in, out), dot(in, out));
  }

  MedialAxis run() {
    VoronoiDiagram vd = medial_detail::segment_voronoi(poly_, options_.backend);
    refine(vd);
    const std::vector<std::uint32_t> kept = interior_edges(vd);
    Graph g = merge(vd, kept);
    prune_smooth_branches(g);
    prune_stubs(g);
    return compact(g);
  }

 private:
  void refine(VoronoiDiagram& vd) const {
    for (auto& v : vd.vertices) {
      v.position = medial_detail::refine_vertex(poly_, v.sites, v.position, centre_, size_);
    }
  }

  /// Indices of the Voronoi edges that belong to the medial axis.
  static std::vector<std::uint32_t> interior_edges(const VoronoiDiagram& vd) {
    std::vector<std::uint32_t> kept;
    for (std::uint32_t i = 0; i < vd.edges.size(); ++i) {
      if (vd.edges[i].medial) kept.push_back(i);
    }
    return kept;
  }

  Graph merge(const VoronoiDiagram& vd, const std::vector<std::uint32_t>& kept) const {
    // Merge along every short Voronoi edge, medial or not: a zero-length edge at a straight
    // corner (turn 0) is not medial, yet it joins two medial edges.
    UnionFind uf(vd.vertices.size());
    const double tol = kMergeRel * size_;
    for (const auto& e : vd.edges) {
      if (distance(vd.vertices[e.a].position, vd.vertices[e.b].position) <= tol) uf.unite(e.a, e.b);
    }
    // New ids for the representatives used by a non-degenerate kept edge, in first-use order.
    std::vector<std::uint32_t> new_id(vd.vertices.size(), UINT32_MAX);
    Graph g;
    auto vertex_of = [&](std::uint32_t v) {
      const auto r = static_cast<std::uint32_t>(uf.find(v));
      if (new_id[r] == UINT32_MAX) {
        new_id[r] = static_cast<std::uint32_t>(g.vertices.size());
        g.vertices.emplace_back();
      }
      return new_id[r];
    };
    for (std::uint32_t i : kept) {
      const auto& e = vd.edges[i];
      if (uf.find(e.a) == uf.find(e.b)) continue;
      const std::uint32_t a = vertex_of(e.a);
      const std::uint32_t b = vertex_of(e.b);
      MaEdge me;
      me.a = MaVertexId(a);
      me.b = MaVertexId(b);
      me.left = e.left;
      me.right = e.right;
      const bool lc = e.left.kind == BoundarySite::Kind::Corner;
      const bool rc = e.right.kind == BoundarySite::Kind::Corner;
      me.kind = (lc != rc) ? MaEdgeKind::Parabola : MaEdgeKind::Line;
      g.edges.push_back(me);
    }
    // Vertex data: the best-placed member of each group, the union of the sites.
    std::vector<double> best(g.vertices.size(), INFINITY);
    std::vector<std::vector<BoundarySite>> sites(g.vertices.size());
    for (std::uint32_t v = 0; v < vd.vertices.size(); ++v) {
      const auto r = static_cast<std::uint32_t>(uf.find(v));
      if (new_id[r] == UINT32_MAX) continue;
      const std::uint32_t id = new_id[r];
      const auto& vv = vd.vertices[v];
      for (const auto& s : vv.sites) sites[id].push_back(s);
      const double spread = medial_detail::distance_spread(poly_, vv.sites, vv.position);
      if (spread < best[id]) {
        best[id] = spread;
        g.vertices[id].position = vv.position;
      }
    }
    for (std::uint32_t id = 0; id < g.vertices.size(); ++id) {
      auto& s = sites[id];
      std::sort(s.begin(), s.end());
      s.erase(std::unique(s.begin(), s.end()), s.end());
      MaVertex& mv = g.vertices[id];
      mv.sites = s;
      double r = INFINITY;
      for (const auto& site : s)
        r = std::min(r, medial_detail::site_distance(poly_, site, mv.position));
      mv.radius = r;
      for (const auto& site : s) {
        if (site.kind == BoundarySite::Kind::Corner && vd.turn[site.loop][site.index] > 0 &&
            distance(mv.position, poly_.loops[site.loop][site.index]) <= kMergeRel * size_) {
          mv.corner = site;
          mv.position = poly_.loops[site.loop][site.index];
          mv.radius = 0.0;
          mv.sites = {site};
        }
      }
    }
    g.edge_alive.assign(g.edges.size(), true);
    g.incident.assign(g.vertices.size(), {});
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      g.incident[g.edges[e].a.index()].push_back(e);
      g.incident[g.edges[e].b.index()].push_back(e);
    }
    g.original_degree.resize(g.vertices.size());
    for (std::uint32_t v = 0; v < g.vertices.size(); ++v) g.original_degree[v] = g.degree(v);
    return g;
  }

  bool is_smooth_corner(const MaVertex& v) const {
    if (!v.corner) return false;
    const auto& sm = smooth_;
    return v.corner->loop < sm.size() && v.corner->index < sm[v.corner->loop].size() &&
           sm[v.corner->loop][v.corner->index];
  }

  /// Whether v is a convex corner turning by less than kStraightTurn, or than kStraightNoise x
  /// the rounding of its coordinates over its shorter side.
  bool is_straight_corner(const MaVertex& v) const {
    if (!v.corner || v.corner->loop >= poly_.loops.size() ||
        v.corner->index >= poly_.loops[v.corner->loop].size())
      return false;
    const std::size_t l = v.corner->loop, i = v.corner->index;
    const auto& loop = poly_.loops[l];
    const std::size_t n = loop.size();
    const Vec2 a = loop[(i + n - 1) % n], b = loop[i], c = loop[(i + 1) % n];
    const double shorter = std::min(distance(a, b), distance(b, c));
    double scale = options_.coordinate_scale;
    for (const Vec2 p : {a, b, c}) scale = std::max({scale, std::fabs(p.x), std::fabs(p.y)});
    const double noise = kStraightNoise * std::numeric_limits<double>::epsilon() * scale / shorter;
    const double turn = corner_turn(l, i);
    return turn > 0.0 && turn < std::max(kStraightTurn, noise);
  }

  /// Removes every chain that runs from a leaf at a smooth corner to the first vertex that was
  /// a junction of the Voronoi-derived axis. A chain that reaches another leaf is kept (it is
  /// all there is of that component). The chains of straight corners (is_straight_corner) go
  /// first, and the junction each ends at counts one branch fewer, as in the diagram of the
  /// same outline turned, where the corner turns the other way by rounding and has no branch:
  /// a smooth corner's chain then runs on through it (fuzz seed 51051's bent_039, a fold's
  /// patch whose straight vertex turned by +1e-15 as given: a stub of the axis was left where
  /// the two chains met, 1,665 quads as given and 1,661 turned).
  void prune_smooth_branches(Graph& g) const {
    for (const bool straight : {true, false})
      for (std::uint32_t leaf = 0; leaf < g.vertices.size(); ++leaf) {
        if (g.degree(leaf) != 1) continue;
        if (straight ? !is_straight_corner(g.vertices[leaf]) : !is_smooth_corner(g.vertices[leaf]))
          continue;
        prune_chain(g, leaf, straight);
      }
  }

  /// prune_smooth_branches' work for one leaf; with `forget`, the junction the chain ends at
  /// loses the chain from its count of branches.
  void prune_chain(Graph& g, std::uint32_t leaf, bool forget) const {
    std::vector<std::uint32_t> chain;  // edges
    std::uint32_t v = leaf;
    std::uint32_t prev_edge = UINT32_MAX;
    bool reaches_junction = false;
    while (true) {
      std::uint32_t next_edge = UINT32_MAX;
      for (std::uint32_t e : g.incident[v]) {
        if (g.edge_alive[e] && e != prev_edge) {
          next_edge = e;
          break;
        }
      }
      if (next_edge == UINT32_MAX) break;
      chain.push_back(next_edge);
      v = g.other(next_edge, v);
      prev_edge = next_edge;
      if (g.original_degree[v] != 2) {
        reaches_junction = g.original_degree[v] >= 3;
        break;
      }
    }
    if (!reaches_junction) return;
    for (std::uint32_t e : chain) g.edge_alive[e] = false;
    if (forget) --g.original_degree[v];
  }

  /// Removes short interior leaf edges left where smooth branches were pruned.
  void prune_stubs(Graph& g) const {
    if (options_.chord_tol <= 0.0) return;
    const double max_len = kStubChordFactor * options_.chord_tol;
    bool changed = true;
    while (changed) {
      changed = false;
      for (std::uint32_t v = 0; v < g.vertices.size(); ++v) {
        if (g.vertices[v].corner || g.degree(v) != 1) continue;
        const std::uint32_t e = g.only_edge(v);
        const std::uint32_t w = g.other(e, v);
        if (g.degree(w) < 2) continue;  // the last edge of its component stays
        if (distance(g.vertices[v].position, g.vertices[w].position) > max_len) continue;
        g.edge_alive[e] = false;
        changed = true;
      }
    }
  }

  MedialAxis compact(const Graph& g) const {
    std::vector<std::uint32_t> new_id(g.vertices.size(), UINT32_MAX);
    std::vector<MaVertex> vertices;
    std::vector<MaEdge> edges;
    auto keep_vertex = [&](std::uint32_t v) {
      if (new_id[v] == UINT32_MAX) {
        new_id[v] = static_cast<std::uint32_t>(vertices.size());
        vertices.push_back(g.vertices[v]);
      }
      return new_id[v];
    };
    for (std::uint32_t e = 0; e < g.edges.size(); ++e) {
      if (!g.edge_alive[e]) continue;
      MaEdge me = g.edges[e];
      me.a = MaVertexId(keep_vertex(static_cast<std::uint32_t>(me.a.index())));
      me.b = MaVertexId(keep_vertex(static_cast<std::uint32_t>(me.b.index())));
      edges.push_back(me);
    }
    if (vertices.empty() && !g.vertices.empty()) {
      // Every edge was pruned (a polygonised disk): the axis is its deepest point.
      std::uint32_t deepest = 0;
      for (std::uint32_t v = 1; v < g.vertices.size(); ++v) {
        if (g.vertices[v].radius > g.vertices[deepest].radius) deepest = v;
      }
      keep_vertex(deepest);
    }
    for (auto& v : vertices) v.degree = 0;
    for (const auto& e : edges) {
      ++vertices[e.a.index()].degree;
      ++vertices[e.b.index()].degree;
    }
    return MedialAxis(poly_, std::move(vertices), std::move(edges));
  }

  const Polygon2& poly_;
  MedialOptions options_;
  std::vector<std::vector<bool>> smooth_;  // per loop corner: its branch is pruned
  double size_ = 0.0;
  Vec2 centre_;
};

}  // namespace

namespace medial_detail {

VoronoiDiagram segment_voronoi(const Polygon2& polygon, VoronoiBackend backend) {
  if (backend == VoronoiBackend::Cgal) return segment_voronoi_cgal(polygon);
  std::string why;
  try {
    std::optional<VoronoiDiagram> vd = segment_voronoi_boost(polygon, &why);
    // A vertex left without a finite position (Boost's diagram of exactly parallel sides, a
    // fuzzed grid outline's one-cell tooth, whose cocircular vertex the flips gave sites with
    // no common disk) would drop its medial edges: CGAL does the polygon instead.
    const auto finite = [](const VoronoiVertex& v) {
      return std::isfinite(v.position.x) && std::isfinite(v.position.y);
    };
    if (vd && std::all_of(vd->vertices.begin(), vd->vertices.end(), finite)) return std::move(*vd);
    if (vd) why = "a Voronoi vertex without a finite position";
  } catch (const InternalError& e) {
    if (backend == VoronoiBackend::BoostOnly) throw;
    why = e.what();
  }
  if (backend == VoronoiBackend::BoostOnly) {
    throw InternalError("medial axis (Boost backend): " + why);
  }
  return segment_voronoi_cgal(polygon);
}

}  // namespace medial_detail

MedialAxis compute_medial_axis(const Polygon2& polygon, const MedialOptions& options) {
  // The axis with its problems: MedialAxis::validate's and the corners it does not reach.
  const auto extract = [&](const MedialOptions& o, std::vector<std::string>& problems) {
    Extractor extractor(polygon, o);
    MedialAxis axis = extractor.run();
    problems = axis.validate();
    for (std::string& p : extractor.unreached_corners(axis)) problems.push_back(std::move(p));
    return axis;
  };
  std::vector<std::string> problems;
  MedialAxis ma = extract(options, problems);
  if (!problems.empty() && options.backend == VoronoiBackend::Boost) {
    // Boost decided the topology on the rounded corners; CGAL decides it on the input.
    MedialOptions cgal = options;
    cgal.backend = VoronoiBackend::Cgal;
    ma = extract(cgal, problems);
  }
  if (!problems.empty()) {
    std::string msg = "medial axis failed its self-check (" + std::to_string(problems.size()) +
                      " problems); first: " + problems.front();
    throw InternalError(msg);
  }
  return ma;
}

}  // namespace laytracks
