// Corner kites folded (docs/mesher.md, "Corner kites"). At a convex corner of the boundary the
// medial axis has a branch to the corner, and the rails from its branch point land on the two
// sides of the corner; the face between them and the corner is one quad, a kite. At a corner
// of 90 degrees it is a square, but at an obtuse one (a 45-degree bend of a strip, a chamfer)
// its corner at the branch point is the supplement of the boundary's, 45 degrees at a corner
// of 135: scaled Jacobian 0.707 and taper 0.31. Without the kite's two side nodes the two
// quads beside it take the corner instead, each half of it.
#include <algorithm>
#include <cmath>
#include <vector>

#include "fill.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/check.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

/// A fold is kept when the worst corner of the two quads it leaves beats the worst of the
/// three it replaces by this (measured before any smoothing, on the templates' nodes, which
/// agree between poses to 1e-12: the same folds in every pose).
constexpr double kKiteGain = 0.02;
/// The side nodes that go lie on straight boundary: the sine of the angle between their two
/// boundary edges at most this.
constexpr double kKiteStraightSine = 1e-9;

}  // namespace

std::size_t fold_corner_kites(const Part& part, QuadMesh& mesh) {
  const std::vector<bool> pinned = pinned_nodes(mesh);
  const std::vector<bool> shared = shared_nodes(mesh);
  const std::vector<bool> vertex = vertex_nodes(part, mesh);
  std::vector<std::vector<std::uint32_t>> around(mesh.nodes.size());
  for (std::uint32_t q = 0; q < mesh.elements.size(); ++q)
    if (mesh.elements[q].is_quad())
      for (std::uint32_t v : mesh.elements[q].nodes) around[v].push_back(q);
  std::vector<bool> drop(mesh.elements.size(), false);
  std::vector<MeshElement> added;
  std::size_t folds = 0;
  // A side node that may go: on a patch's boundary (pinned, not shared), no B-Rep vertex, in
  // two quads.
  const auto side = [&](std::uint32_t v) {
    return pinned[v] && !shared[v] && !vertex[v] && around[v].size() == 2;
  };
  for (std::uint32_t c = 0; c < mesh.nodes.size(); ++c) {
    // The corner: a B-Rep vertex that one quad of the mesh meets.
    if (!vertex[c] || around[c].size() != 1) continue;
    const std::uint32_t k = around[c][0];
    if (drop[k]) continue;
    const MeshElement& kite = mesh.elements[k];
    std::size_t at = 0;
    while (kite.nodes[at] != c) ++at;
    const std::uint32_t f1 = kite.nodes[(at + 1) % 4], b = kite.nodes[(at + 2) % 4],
                        f2 = kite.nodes[(at + 3) % 4];
    if (!side(f1) || !side(f2)) continue;
    const std::uint32_t q1 = around[f1][0] == k ? around[f1][1] : around[f1][0];
    const std::uint32_t q2 = around[f2][0] == k ? around[f2][1] : around[f2][0];
    if (q1 == q2 || drop[q1] || drop[q2]) continue;
    const MeshElement& e1 = mesh.elements[q1];
    const MeshElement& e2 = mesh.elements[q2];
    if (e1.patch != kite.patch || e2.patch != kite.patch) continue;
    const Frame& frame = part.patches[kite.patch.index()].frame;
    const auto at2 = [&](std::uint32_t v) { return frame.to_2d(mesh.nodes[v]); };
    // Each side node between the corner and its other boundary neighbour, on one line.
    const auto straight = [&](std::uint32_t f, const MeshElement& e) {
      std::size_t i = 0;
      while (e.nodes[i] != f) ++i;
      // In e, f's boundary neighbour is the one that is not b.
      const std::uint32_t next = e.nodes[(i + 1) % 4], prev = e.nodes[(i + 3) % 4];
      if (next != b && prev != b) return false;
      const std::uint32_t n = next == b ? prev : next;
      const Vec2 u = at2(n) - at2(f), w = at2(c) - at2(f);
      return std::abs(cross(u, w)) <= kKiteStraightSine * norm(u) * norm(w) && dot(u, w) < 0.0;
    };
    if (!straight(f1, e1) || !straight(f2, e2)) continue;
    // The quads as they are and as they would be (the side node replaced by the corner), in the
    // patch frame; the frame may turn them clockwise, so they are read with the kite's sense.
    const Vec2 pc = at2(c), p1 = at2(f1), p2 = at2(f2), pb = at2(b);
    const double sense = cross(p1 - pc, pb - pc) + cross(pb - pc, p2 - pc) > 0.0 ? 1.0 : -1.0;
    const auto corners = [&](const std::array<std::uint32_t, 4>& x) {
      std::array<Vec2, 4> p;
      for (std::size_t i = 0; i < 4; ++i) p[i] = Vec2{at2(x[i]).x, sense * at2(x[i]).y};
      return p;
    };
    const auto jacobian = [&](const std::array<std::uint32_t, 4>& x) {
      const auto p = corners(x);
      return min_scaled_jacobian(p[0], p[1], p[2], p[3]);
    };
    const auto replaced = [&](std::array<std::uint32_t, 4> x, std::uint32_t f) {
      std::replace(x.begin(), x.end(), f, c);
      return x;
    };
    const std::array<std::uint32_t, 4> n1 = replaced(e1.nodes, f1), n2 = replaced(e2.nodes, f2);
    const double was = std::min({jacobian(kite.nodes), jacobian(e1.nodes), jacobian(e2.nodes)});
    const double now = std::min(jacobian(n1), jacobian(n2));
    if (!(settled(now) >= settled(was) + kKiteGain)) continue;
    drop[k] = drop[q1] = drop[q2] = true;
    MeshElement m1 = e1, m2 = e2;
    m1.nodes = n1;
    m2.nodes = n2;
    added.push_back(m1);
    added.push_back(m2);
    ++folds;
  }
  if (folds > 0) replace_elements(mesh, drop, added);
  return folds;
}

}  // namespace laytracks
