// Corner kites folded (docs/mesher.md, "Corner kites"). At a convex corner of the boundary the
// medial axis has a branch to the corner, and the rails from its branch point land on the two
// sides of the corner; the face between them and the corner is one quad, a kite. At a corner
// of 90 degrees it is a square, but at an obtuse one (a 45-degree bend of a strip, a chamfer)
// its corner at the branch point is the supplement of the boundary's, 45 degrees at a corner
// of 135: scaled Jacobian 0.707 and taper 0.31. Without the kite's two side nodes the two
// quads beside it take the corner instead, each half of it. At a reflex corner the same
// pattern is two quads that split the corner in two, with rail feet just beside it (a strip's
// right-angle bend: two quads of 135 degrees at the corner, 0.707): without the side nodes
// the two become one quad and the corner is split in three.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fill.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/quality.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

/// A fold is kept when the worst corner of the two quads it leaves beats the worst of the
/// three it replaces by this (measured before any smoothing, on the templates' nodes, which
/// agree between poses to 1e-12: the same folds in every pose).
constexpr double kKiteGain = 0.02;
/// A side node is no farther from the corner than this x from its other boundary neighbour:
/// the boundary edge the fold makes is at most 2.5 x the one beyond. Without the bound a fold
/// of a piece ten times the edge beyond (a reflex corner of a generated bracket) left a long
/// quad that the smoothing could not mend (worst 0.755 -> 0.721).
constexpr double kKiteSidePiece = 1.5;

using Quad = std::array<std::uint32_t, 4>;

/// What both folds read of the mesh's nodes, once per pass.
struct FoldNodes {
  FoldNodes(const Part& part, const QuadMesh& m)
      : mesh(m),
        pinned(pinned_nodes(m)),
        shared(shared_nodes(m)),
        vertex(vertex_nodes(part, m)),
        around(quads_at_mesh_nodes(m)) {}
  /// A side node, which a fold may drop: on one patch's boundary (pinned, not shared), no
  /// B-Rep vertex, in two quads.
  bool side(std::uint32_t v) const {
    return pinned[v] && !shared[v] && !vertex[v] && around[v].size() == 2;
  }
  /// Element q's nodes turned to start at node v.
  Quad from(std::uint32_t q, std::uint32_t v) const {
    const Quad& x = mesh.elements[q].nodes;
    std::size_t i = 0;
    while (x[i] != v) ++i;
    return Quad{x[i], x[(i + 1) % 4], x[(i + 2) % 4], x[(i + 3) % 4]};
  }
  const QuadMesh& mesh;
  const std::vector<bool> pinned, shared, vertex;
  const std::vector<std::vector<std::uint32_t>> around;
};

/// Whether a side node at f lies on one line between its boundary neighbours `toward` (the
/// corner it is dropped for) and `beyond`, no farther from `toward` than kKiteSidePiece x
/// from `beyond`: the two boundary pieces can become one edge.
bool straight_side(Vec2 f, Vec2 toward, Vec2 beyond) {
  const Vec2 u = beyond - f, w = toward - f;
  return std::abs(cross(u, w)) <= kStraightBoundarySine * norm(u) * norm(w) && dot(u, w) < 0.0 &&
         norm(w) <= kKiteSidePiece * norm(u);
}

}  // namespace

std::size_t fold_corner_kites(const Part& part, QuadMesh& mesh) {
  const FoldNodes nodes(part, mesh);
  const std::vector<bool>& vertex = nodes.vertex;
  const std::vector<std::vector<std::uint32_t>>& around = nodes.around;
  const auto side = [&](std::uint32_t v) { return nodes.side(v); };
  std::vector<bool> drop(mesh.elements.size(), false);
  std::vector<MeshElement> added;
  std::size_t folds = 0;
  for (std::uint32_t c = 0; c < mesh.nodes.size(); ++c) {
    // The corner: a B-Rep vertex that one quad meets (a convex corner's kite) or two quads
    // sharing an edge from it (a reflex corner split in two).
    if (!vertex[c] || around[c].empty() || around[c].size() > 2) continue;
    const std::vector<std::uint32_t>& at_c = around[c];
    if (std::any_of(at_c.begin(), at_c.end(), [&](std::uint32_t q) { return drop[q]; })) continue;
    // Each corner quad from c, counter-clockwise: (c, next, opposite, prev).
    const auto from_c = [&](std::uint32_t q) { return nodes.from(q, c); };
    const Quad a1 = from_c(at_c.front()), a2 = from_c(at_c.back());
    // The side nodes: c's boundary neighbours, f1 last in its quad, f2 first; the inner node
    // g beside each, across which the quad beyond it lies. Two corner quads share c's edge to
    // d (a1's first, a2's last node), the kite's corner has none.
    std::uint32_t f1 = a1[3], g1 = a1[2], f2 = a2[1], g2 = a2[2], d = MeshElement::kNoNode;
    if (at_c.size() == 2) {
      if (a1[1] == a2[3]) {
        d = a1[1];
      } else if (a2[1] == a1[3]) {  // the other way round: a2 is the first counter-clockwise
        d = a2[1];
        f1 = a2[3];
        g1 = a2[2];
        f2 = a1[1];
        g2 = a1[2];
      } else {
        continue;
      }
    }
    if (!side(f1) || !side(f2)) continue;
    const auto beyond = [&](std::uint32_t f) {
      return std::find(at_c.begin(), at_c.end(), around[f][0]) == at_c.end() ? around[f][0]
                                                                              : around[f][1];
    };
    const std::uint32_t q1 = beyond(f1), q2 = beyond(f2);
    if (q1 == q2 || drop[q1] || drop[q2] ||
        std::find(at_c.begin(), at_c.end(), q1) != at_c.end() ||
        std::find(at_c.begin(), at_c.end(), q2) != at_c.end())
      continue;
    const MeshElement& corner = mesh.elements[at_c.front()];
    const MeshElement& e1 = mesh.elements[q1];
    const MeshElement& e2 = mesh.elements[q2];
    if (e1.patch != corner.patch || e2.patch != corner.patch ||
        mesh.elements[at_c.back()].patch != corner.patch)
      continue;
    const Frame& frame = part.patches[corner.patch.index()].frame;
    const auto at2 = [&](std::uint32_t v) { return frame.to_2d(mesh.nodes[v]); };
    // Each side node between the corner and its other boundary neighbour, on one line, no
    // farther from the corner than kKiteSidePiece x from that neighbour; the quad beyond has
    // the edge from it to g.
    const auto straight = [&](std::uint32_t f, std::uint32_t g, const MeshElement& e) {
      std::size_t i = 0;
      while (e.nodes[i] != f) ++i;
      const std::uint32_t next = e.nodes[(i + 1) % 4], prev = e.nodes[(i + 3) % 4];
      if (next != g && prev != g) return false;
      const std::uint32_t n = next == g ? prev : next;
      return straight_side(at2(f), at2(c), at2(n));
    };
    if (!straight(f1, g1, e1) || !straight(f2, g2, e2)) continue;
    // The quads as they are and as they would be, in the patch frame (where every element
    // runs counter-clockwise: the frame's normal is the patch's).
    const auto jacobian = [&](const Quad& x) {
      return min_scaled_jacobian(at2(x[0]), at2(x[1]), at2(x[2]), at2(x[3]));
    };
    const auto replaced = [&](Quad x, std::uint32_t f) {
      std::replace(x.begin(), x.end(), f, c);
      return x;
    };
    std::vector<MeshElement> made{e1, e2};
    made[0].nodes = replaced(e1.nodes, f1);
    made[1].nodes = replaced(e2.nodes, f2);
    if (d != MeshElement::kNoNode) {  // the two corner quads without their side nodes: one quad
      MeshElement m = corner;
      m.nodes = Quad{c, g2, d, g1};
      made.push_back(m);
    }
    double was = std::min(jacobian(e1.nodes), jacobian(e2.nodes));
    for (std::uint32_t q : at_c) was = std::min(was, jacobian(mesh.elements[q].nodes));
    double now = std::numeric_limits<double>::infinity();
    for (const MeshElement& m : made) now = std::min(now, jacobian(m.nodes));
    if (!(settled(now) >= settled(was) + kKiteGain)) continue;
    for (std::uint32_t q : at_c) drop[q] = true;
    drop[q1] = drop[q2] = true;
    added.insert(added.end(), made.begin(), made.end());
    ++folds;
  }
  if (folds > 0) replace_elements(mesh, drop, added);
  return folds;
}

std::size_t fold_corner_reliefs(const Part& part, QuadMesh& mesh) {
  const FoldNodes nodes(part, mesh);
  const std::vector<std::vector<std::uint32_t>>& around = nodes.around;
  std::vector<bool> drop(mesh.elements.size(), false);
  std::vector<MeshElement> added;
  std::size_t folds = 0;
  // The quad at node v other than q (v in two quads).
  const auto other = [&](std::uint32_t v, std::uint32_t q) {
    return around[v][0] == q ? around[v][1] : around[v][0];
  };
  for (std::uint32_t p = 0; p < mesh.nodes.size(); ++p) {
    // The relief's reflex vertex: two quads sharing its edge to an inner node b.
    if (!nodes.vertex[p] || around[p].size() != 2) continue;
    std::uint32_t q1 = around[p][0], q2 = around[p][1];
    Quad a1 = nodes.from(q1, p), a2 = nodes.from(q2, p);
    if (a1[1] != a2[3]) {
      std::swap(q1, q2);
      std::swap(a1, a2);
    }
    // a1 = (p, b, y1, p1), a2 = (p, p3, y2, b).
    if (a1[1] != a2[3]) continue;
    const std::uint32_t b = a1[1], y1 = a1[2], p1 = a1[3], p3 = a2[1], y2 = a2[2];
    if (nodes.pinned[b] || around[b].size() != 4 || !nodes.side(y1) || !nodes.side(y2)) continue;
    // The quads beyond y1 and y2: q3 = (y1, b, d, a) and q4 = (y2, c, d, b), sharing b's edge
    // to d.
    const std::uint32_t q3 = other(y1, q1), q4 = other(y2, q2);
    if (q3 == q4) continue;
    const Quad a3 = nodes.from(q3, y1), a4 = nodes.from(q4, y2);
    if (a3[1] != b || a4[3] != b || a3[2] != a4[2]) continue;
    const std::uint32_t d = a3[2], a = a3[3], c = a4[1];
    const std::uint32_t quads[4] = {q1, q2, q3, q4};
    if (std::any_of(quads, quads + 4, [&](std::uint32_t q) {
          return drop[q] || mesh.elements[q].patch != mesh.elements[q1].patch;
        }))
      continue;
    const MeshElement& first = mesh.elements[q1];
    const Frame& frame = part.patches[first.patch.index()].frame;
    const auto at2 = [&](std::uint32_t v) { return frame.to_2d(mesh.nodes[v]); };
    // Each wall node between its neighbours on one straight piece of boundary (then the
    // two pieces become one edge), the piece to the relief no longer than kKiteSidePiece x
    // the one beyond.
    if (!straight_side(at2(y1), at2(p1), at2(a)) || !straight_side(at2(y2), at2(p3), at2(c)))
      continue;
    const auto jacobian = [&](const Quad& x) {
      return min_scaled_jacobian(at2(x[0]), at2(x[1]), at2(x[2]), at2(x[3]));
    };
    const auto beyond = [&](const Quad& x) {
      return beyond_table_iii(measure_planar_quad(at2(x[0]), at2(x[1]), at2(x[2]), at2(x[3]))) ? 1
                                                                                           : 0;
    };
    // The four quads as two: (a, p1, p, d) and (p, p3, c, d).
    const Quad n1{a, p1, p, d}, n2{p, p3, c, d};
    double was = std::numeric_limits<double>::infinity();
    int was_beyond = 0;
    for (std::uint32_t q : quads) {
      was = std::min(was, jacobian(mesh.elements[q].nodes));
      was_beyond += beyond(mesh.elements[q].nodes);
    }
    const double now = std::min(jacobian(n1), jacobian(n2));
    const int now_beyond = beyond(n1) + beyond(n2);
    if (!(settled(now) >= settled(was)) || now_beyond >= was_beyond) continue;
    for (std::uint32_t q : quads) drop[q] = true;
    MeshElement m1 = first, m2 = first;
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
