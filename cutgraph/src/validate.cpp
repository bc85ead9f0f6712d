// The validator of the cut graph (docs/cutgraph.md): what must hold once the rails are laid.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "boundary_index.hpp"
#include "corridors.hpp"
#include "laytracks/cutgraph/boost_view.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks {
namespace {

std::string fmt(Vec3 p) {
  std::ostringstream s;
  s.precision(6);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

/// Orientation of c relative to a -> b, with a relative dead band for collinear points.
int side(Vec2 a, Vec2 b, Vec2 c, double eps) {
  const double d = cross(b - a, c - a);
  return d > eps ? 1 : d < -eps ? -1 : 0;
}

/// True when the closed segments ab and cd cross at a point that is not a shared end point.
bool cross_inside(Vec2 a, Vec2 b, Vec2 c, Vec2 d, double eps) {
  if (a == c || a == d || b == c || b == d) return false;
  const int s1 = side(a, b, c, eps);
  const int s2 = side(a, b, d, eps);
  const int s3 = side(c, d, a, eps);
  const int s4 = side(c, d, b, eps);
  return s1 * s2 < 0 && s3 * s4 < 0;
}

}  // namespace

std::vector<std::string> validate_cut_graph(const Part& part,
                                            const std::vector<MedialAxis>& axes,
                                            const CutGraph& graph) {
  std::vector<std::string> problems = graph.problems;
  const double tol = 1e-7 * part.size;
  // Every G-CUT-VERT on an edge has an image in every patch of the edge, at the same 3D point.
  std::map<std::uint32_t, std::vector<CutVertId>> images;
  for (std::size_t i = 0; i < graph.cuts.size(); ++i)
    images[graph.cuts[i].g.value].push_back(CutVertId(i));
  for (std::size_t gi = 0; gi < graph.gverts.size(); ++gi) {
    const GCutVert& g = graph.gverts[gi];
    const auto& list = images[static_cast<std::uint32_t>(gi)];
    if (!g.vertex && list.size() != part.edges[g.edge.index()].patches.size()) {
      problems.push_back("the rail point at " + fmt(g.position) + " has " +
                         std::to_string(list.size()) + " images but its edge has " +
                         std::to_string(part.edges[g.edge.index()].patches.size()) + " patches");
    }
    for (CutVertId c : list) {
      const CutVert& cv = graph.cuts[c.index()];
      const Vec3 x = part.patches[cv.patch.index()].frame.to_3d(cv.position);
      if (distance(x, g.position) > tol) {
        problems.push_back("the image of the rail point at " + fmt(g.position) + " on " +
                           part.patch_label(cv.patch) + " is " +
                           std::to_string(distance(x, g.position)) + " away from it");
      }
    }
  }
  // Every MA-CUT-VERT lies on its MA edge, and each rail segment is as long as the radius there.
  for (const RailSegment& s : graph.segments) {
    const CutVert& c = graph.cuts[s.cut.index()];
    const MaCutVert& m = graph.macuts[s.ma.index()];
    const MedialAxis& ma = axes[m.patch.index()];
    const MaPoint on = m.point.edge.valid() ? ma.point_on_edge(m.point.edge, m.point.t)
                                            : MaPoint{{}, 0.0, ma.vertices().front().position, 0.0};
    if (m.point.t < -1e-12 || m.point.t > 1.0 + 1e-12 ||
        distance(on.position, m.point.position) > tol) {
      problems.push_back("an MA-CUT-VERT on " + part.patch_label(m.patch) +
                         " lies off its MA edge");
    }
    // Rails into the centre of a polygonised arc are longer than its radius by the sagitta.
    // A rail closing a loop on an existing point leans (RailLayer): not along the mapping.
    // A rail to or from a spread zone, or into the vertex a pruned corner maps to
    // (MedialAxis::project), leans too, but never into the disk.
    const double length = distance(c.position, m.point.position);
    const bool spread = m.point.off_normal || ma.in_spread_zone(c.on_segment());
    if (spread ? length < m.point.radius - tol
               : !s.leans && std::fabs(length - m.point.radius) > tol + part.chord_tol) {
      problems.push_back("a rail segment on " + part.patch_label(c.patch) +
                         " is not as long as the radius at its MA point");
    }
  }
  // No two rails cross inside a patch (sweep over x).
  std::vector<std::vector<std::pair<Vec2, Vec2>>> rails(part.patches.size());
  for (const RailSegment& s : graph.segments) {
    const CutVert& c = graph.cuts[s.cut.index()];
    rails[c.patch.index()].push_back({c.position, graph.macuts[s.ma.index()].point.position});
  }
  for (std::size_t p = 0; p < rails.size(); ++p) {
    auto& r = rails[p];
    std::sort(r.begin(), r.end(), [](const auto& x, const auto& y) {
      return std::min(x.first.x, x.second.x) < std::min(y.first.x, y.second.x);
    });
    const double eps = 1e-12 * part.size * part.size;
    std::size_t crossings = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const double hi = std::max(r[i].first.x, r[i].second.x);
      for (std::size_t j = i + 1; j < r.size() && std::min(r[j].first.x, r[j].second.x) <= hi;
           ++j) {
        if (cross_inside(r[i].first, r[i].second, r[j].first, r[j].second, eps)) ++crossings;
      }
    }
    if (crossings > 0) {
      problems.push_back(std::to_string(crossings) + " pairs of rails cross inside " +
                         part.patch_label(PatchId(p)));
    }
  }
  // The CUT-GRAPH is bipartite: rail segments join boundary points to MA points only.
  if (!is_bipartite_by_kind(to_boost_graph(graph))) {
    problems.push_back("the CUT-GRAPH is not bipartite");
  }
  // Every corridor piece is bounded by two rails or corners, the boundary and the axis.
  std::map<cutgraph_detail::LoopKey, bool> railed;
  const auto key = [&](PatchId p, std::uint32_t loop, double u) {
    return cutgraph_detail::loop_key(part, p, loop, u);
  };
  for (const RailSegment& s : graph.segments) {
    const CutVert& c = graph.cuts[s.cut.index()];
    railed[key(c.patch, c.at.loop, c.at.u())] = true;
  }
  for (const CutVert& c : graph.cuts) {
    // A CUT-VERT at a corner ends its rail there (fan or zero length).
    const double n =
        static_cast<double>(part.patches[c.patch.index()].polygon.loops[c.at.loop].size());
    if (c.at.s == 0.0 &&
        cutgraph_detail::corner_turn(part, c.patch, c.at.loop, c.at.segment) != 0) {
      railed[key(c.patch, c.at.loop, std::fmod(c.at.u(), n))] = true;
    }
  }
  for (const CorridorPiece& piece : cutgraph_detail::corridor_pieces_impl(part, axes, graph)) {
    const auto n = part.patches[piece.patch.index()].polygon.loops[piece.loop].size();
    if (piece.u1 - piece.u0 >= static_cast<double>(n)) continue;  // a whole loop: a ring
    for (double u : {piece.u0, piece.u1}) {
      const double frac = u - std::floor(u);
      const bool corner = frac == 0.0;
      if (corner && cutgraph_detail::corner_turn(
                        part, piece.patch, piece.loop,
                        static_cast<std::uint32_t>(static_cast<std::size_t>(u) % n)) != 0) {
        continue;
      }
      if (!railed.count(key(piece.patch, piece.loop, u))) {
        problems.push_back("a corridor piece on " + part.patch_label(piece.patch) +
                           " ends at a boundary point without a rail");
        break;
      }
    }
  }
  return problems;
}

}  // namespace laytracks
