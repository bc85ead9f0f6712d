// Boundary nodes slid apart (docs/mesher.md, "Sliding boundary nodes"). A rail's foot may land
// a hundredth of an element from an arc point or another foot (a hole's arc: 0.013 h on
// plate_with_hole), or from a vertex of a polygonal outline: the quad on that piece has an
// edge 70 times shorter than its others, taper 0.07, edge ratio 70; or a foot may sit where
// its quads are tapered (half an element from a bend of a narrow strip: taper 0.65), which
// the smoothing, moving interior nodes only, cannot mend. Such a foot slides along its
// boundary (the line through its two boundary neighbours, or its arc) to where the worst of
// its quads is best; since session 40 a node on a seam between patches too (the tracks of a
// faceted shell cross its facets' edges as strips a quarter of an element wide). After the
// smoothing (and then smoothed round, as the late flips are): judged on the smoothed quads; nodes
// and quads are not added or removed, so the counts are the re-fill's, the same in every pose.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "fill.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

/// A boundary node on an arc slides when its shorter boundary edge is below this x its longer
/// one; on a straight edge, below kSlideTinyLine x. Pieces of a tenth slid on straight edges
/// lowered worst corners after the smoothing (the adaptive bracket 0.451 -> 0.397); those of a
/// twentieth are the polygonal outlines' slivers (cgal_complex_1: edge ratio 94 -> 33,
/// cgal_sample_0: 85 -> 12), and no worst corner fell.
constexpr double kSlideTiny = 0.2;
constexpr double kSlideTinyLine = 0.05;
/// Where it may go: this many positions, evenly along its boundary between its two neighbours
/// (fractions 1/(n+1) .. n/(n+1) of the way).
constexpr int kSlideSteps = 15;
/// A node (on a line or an arc) also slides when one of its quads has a taper of this or less
/// (quality.md's bad taper): a rail's foot beside a bend of a narrow strip, or round a hole.
constexpr double kSlideTaper = 0.8;
/// A slide is kept when it raises the worst min(scaled Jacobian, taper) of the node's quads by
/// this.
constexpr double kSlideGain = 0.05;
/// ... and lowers their worst scaled Jacobian only when it stays above this. Without a floor
/// cover_bosses kept two slivers of edge ratio 70 (the slide gave 0.62 from 0.71); with none
/// at all, worst corners fell on more of the test sets.
constexpr double kSlideJacobianFloor = 0.6;
/// A node is on an arc when its distance from the arc's circle is at most this x the part's
/// size (and its angle within the arc's span, to this in radians).
constexpr double kSlideOnArc = 1e-7;

}  // namespace

std::size_t slide_boundary_nodes(const Part& part,
                                 QuadMesh& mesh,
                                 std::vector<std::uint32_t>* moved,
                                 bool tapered_too,
                                 std::size_t* for_taper) {
  if (for_taper) *for_taper = 0;
  const std::vector<bool> pinned = pinned_nodes(mesh);
  const std::vector<bool> shared = shared_nodes(mesh);
  const std::vector<bool> vertex = vertex_nodes(part, mesh);
  const std::vector<std::vector<std::uint32_t>> around = quads_at_mesh_nodes(mesh);
  // The boundary neighbours of node f in one patch: across the edges from it that one quad
  // of that patch has (in the order its quads give them).
  const auto boundary_neighbours = [&](std::uint32_t f, PatchId patch) {
    const auto in_patch = [&](std::uint32_t q) { return mesh.elements[q].patch == patch; };
    std::vector<std::uint32_t> found;
    for (std::uint32_t q : around[f]) {
      if (!in_patch(q)) continue;
      const auto& x = mesh.elements[q].nodes;
      const std::size_t i = static_cast<std::size_t>(std::find(x.begin(), x.end(), f) - x.begin());
      for (std::uint32_t n : {x[(i + 1) % 4], x[(i + 3) % 4]}) {
        const auto uses = std::count_if(around[f].begin(), around[f].end(), [&](std::uint32_t r) {
          const auto& y = mesh.elements[r].nodes;
          return in_patch(r) && std::find(y.begin(), y.end(), n) != y.end();
        });
        if (uses == 1) found.push_back(n);
      }
    }
    return found;
  };
  std::size_t slid = 0;
  for (std::uint32_t f = 0; f < mesh.nodes.size(); ++f) {
    if (!pinned[f] || vertex[f] || around[f].empty()) continue;
    // Its boundary neighbours in each patch it is in. A seam node (shared) slides along its
    // seam only where every patch sees the same two (since session 40; before, nodes of one
    // patch only); the first patch's order decides ties between positions.
    std::vector<PatchId> patches;
    for (std::uint32_t q : around[f])
      if (std::find(patches.begin(), patches.end(), mesh.elements[q].patch) == patches.end())
        patches.push_back(mesh.elements[q].patch);
    const std::vector<std::uint32_t> ends = boundary_neighbours(f, patches.front());
    if (ends.size() != 2 || ends[0] == ends[1]) continue;
    if (std::any_of(patches.begin() + 1, patches.end(), [&](PatchId p) {
          const std::vector<std::uint32_t> here = boundary_neighbours(f, p);
          return here.size() != 2 || !std::is_permutation(here.begin(), here.end(), ends.begin());
        }))
      continue;
    if (shared[f] && patches.size() < 2) continue;  // (a seam whose other side has no quad here)
    // Its own patch's frame for its geometry; every quad is scored in its own patch's frame.
    const Frame& frame = part.patches[patches.front().index()].frame;
    const auto at2 = [&](std::uint32_t v) { return frame.to_2d(mesh.nodes[v]); };
    const Vec2 p1 = at2(ends[0]), pf = at2(f), p2 = at2(ends[1]);
    const double d1 = norm(pf - p1), d2 = norm(p2 - pf);
    // Its boundary: the line through its neighbours, or the part's arc through the three (the
    // positions it may take come from PartArc::at, as every arc node's does). A seam is read
    // in 3D (its patches' planes differ).
    const Vec2 u = pf - p1, w = p2 - pf;
    const Vec3 u3 = mesh.nodes[f] - mesh.nodes[ends[0]], w3 = mesh.nodes[ends[1]] - mesh.nodes[f];
    const bool straight = patches.size() > 1
                              ? norm(cross(u3, w3)) <= kStraightBoundarySine * norm(u3) * norm(w3)
                              : std::abs(cross(u, w)) <= kStraightBoundarySine * norm(u) * norm(w);
    const bool tiny =
        std::min(d1, d2) < (straight ? kSlideTinyLine : kSlideTiny) * std::max(d1, d2);
    if (!tiny && !tapered_too) continue;
    // The worst min(scaled Jacobian, taper) of the node's quads with the node at `at`, their
    // worst scaled Jacobian (in each quad's patch frame, where every element runs
    // counter-clockwise), and how many of them have a taper of kSlideTaper or less.
    // The quads round f in their patches' frames, f's corners to be set per position.
    struct Around {
      const Frame* frame;
      std::array<Vec2, 4> p;
      std::array<bool, 4> at_f;
    };
    std::vector<Around> quads_round;
    for (std::uint32_t q : around[f]) {
      Around a{&part.patches[mesh.elements[q].patch.index()].frame, {}, {}};
      for (std::size_t i = 0; i < 4; ++i) {
        const std::uint32_t v = mesh.elements[q].nodes[i];
        a.at_f[i] = v == f;
        if (!a.at_f[i]) a.p[i] = a.frame->to_2d(mesh.nodes[v]);
      }
      quads_round.push_back(a);
    }
    const auto score = [&](Vec3 at, double& jacobian, int& tapered_quads) {
      double worst = std::numeric_limits<double>::infinity();
      jacobian = worst;
      tapered_quads = 0;
      for (Around& a : quads_round) {
        const Vec2 here = a.frame->to_2d(at);
        for (std::size_t i = 0; i < 4; ++i)
          if (a.at_f[i]) a.p[i] = here;
        const auto& p = a.p;
        const auto [t, j] = quad_taper_jacobian(p[0], p[1], p[2], p[3]);
        jacobian = std::min(jacobian, j);
        worst = std::min({worst, j, t});
        if (t <= kSlideTaper) ++tapered_quads;
      }
      jacobian = settled(jacobian);
      return settled(worst);
    };
    double jacobian_now = 0.0;
    int tapered_now = 0;
    const double now = score(mesh.nodes[f], jacobian_now, tapered_now);
    if (!tiny && tapered_now == 0) continue;
    if (straight && dot(u, w) <= 0.0) continue;
    const Vec3 x1 = mesh.nodes[ends[0]], x2 = mesh.nodes[ends[1]];
    const PartArc* arc = nullptr;
    double u1 = 0.0, u2 = 0.0;
    if (!straight) {
      // The fraction of the arc's angle at x, if x is on the arc's circle and within its span.
      const auto fraction = [&](const PartArc& a, Vec3 x) -> std::optional<double> {
        const Vec3 r = x - a.center;
        if (std::abs(norm(r) - a.radius) > kSlideOnArc * part.size) return std::nullopt;
        double t = std::atan2(dot(r, a.e2), dot(r, a.e1));
        if (t < 0.0) t += 2.0 * kPi;
        if (t > a.span + kSlideOnArc) return std::nullopt;
        return std::min(t, a.span) / a.span;
      };
      for (const PartArc& a : part.arcs) {
        const auto uf = fraction(a, mesh.nodes[f]), ua = fraction(a, x1), ub = fraction(a, x2);
        if (uf && ua && ub && std::min(*ua, *ub) < *uf && *uf < std::max(*ua, *ub)) {
          arc = &a;
          u1 = *ua;
          u2 = *ub;
          break;
        }
      }
      if (!arc) continue;
    }
    const auto point = [&](double t) {
      return straight ? x1 + t * (x2 - x1) : arc->at(u1 + (u2 - u1) * t);
    };
    double best = now;
    std::optional<Vec3> to;
    for (int k = 1; k <= kSlideSteps; ++k) {
      const Vec3 at = point(static_cast<double>(k) / (kSlideSteps + 1));
      double jacobian = 0.0;
      int tapered_then = 0;
      const double s = score(at, jacobian, tapered_then);
      // A short edge's node: no worse a corner, or none below kSlideJacobianFloor. A node
      // slid for a taper: no worse a corner, and fewer tapered quads.
      const bool ok = tiny ? jacobian >= std::min(jacobian_now, kSlideJacobianFloor)
                           : jacobian >= jacobian_now && tapered_then < tapered_now;
      if (s > best && ok) {
        best = s;
        to = at;
      }
    }
    if (!to || !(best >= now + kSlideGain)) continue;
    mesh.nodes[f] = *to;
    if (moved) moved->push_back(f);
    if (for_taper && !tiny) ++*for_taper;
    ++slid;
  }
  return slid;
}

}  // namespace laytracks
