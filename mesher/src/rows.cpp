// Thin rows merged (docs/mesher.md, "Thin rows"): every rail runs from the boundary to the
// medial axis, so a corridor is at least two quads across, and a strip narrower than an
// element gets two rows of quads of aspect about 2 h / w. Where a chain of edges along the
// middle of such a strip runs from boundary to boundary (or round a ring) through interior
// nodes of valence four, with the quads on both sides thin across it, the two rows are one:
// the chain's nodes go and each pair of quads across it becomes one quad.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "laytracks/mesher/build_quads.hpp"
#include "fill.hpp"
#include "laytracks/mesher/check.hpp"
#include "laytracks/mesher/quality.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

using Quad = std::array<std::uint32_t, 4>;
constexpr std::uint32_t kNone = 0xffffffffu;

/// A chain edge is at least this x as long as the rungs across it at both its nodes.
constexpr double kRowThinRatio = 2.0;
/// A merged quad is no worse than its pair's worst corner, to this (rounding: a rectangle's
/// corners are 1 to within 1e-15 in one pose and not in another). 0.05 allowed merges that
/// the smoothing then made worse (cgal_wiggly_03_cgal at 2x: 0.143 -> 0.070).
constexpr double kRowJacobianSlack = 1e-9;
/// A merged quad less square than its pair is still taken up to this aspect ratio (the end of
/// a strip: two near-squares become one rectangle of 2).
constexpr double kRowAspectOk = 3.0;
/// Lengths and aspect ratios within this factor of a threshold, or of each other, count as
/// equal: a grid-cell part has exact ratios of 2 and 3 in one pose that rounding puts either
/// side of the threshold in another (rect_063 of the session-30 fuzzing: 104 quads, and 100
/// scaled by 1e-3).
constexpr double kRowTieRel = 1e-9;

/// Aspect ratio as quality.md defines it (measure_quad), of a quad in the patch's plane.
double quad_aspect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const auto up = [](Vec2 v) { return Vec3{v.x, v.y, 0.0}; };
  return measure_quad({up(a), up(b), up(c), up(d)}, {0.0, 0.0, 1.0}).aspect_ratio;
}

/// The quads of the whole mesh, for chains that may cross seams: a chain goes through an
/// interior node of a patch, or through a node on a seam between two patches (no B-Rep
/// vertex) with two quads of each round it; each pair of quads it merges is in one patch,
/// and is measured in that patch's frame.
class MeshRows {
 public:
  MeshRows(const Part& part, const QuadMesh& mesh, std::vector<bool> through,
           const std::vector<bool>& removable)
      : part_(part), mesh_(mesh), through_(std::move(through)), removable_(removable),
        around_(quads_at_mesh_nodes(mesh)) {
    // Only where its four quads close round it, each edge at it in two of them, and (on a
    // seam) two of them in each patch.
    for (std::uint32_t v = 0; v < mesh_.nodes.size(); ++v) {
      if (!through_[v]) continue;
      if (around_[v].size() != 4) {
        through_[v] = false;
        continue;
      }
      const std::vector<std::uint32_t> ends = edge_ends(v);
      std::vector<std::uint32_t> patches;
      for (std::uint32_t q : around_[v]) patches.push_back(mesh_.elements[q].patch.value);
      std::sort(patches.begin(), patches.end());
      bool closed = ends.size() == 8;
      for (std::size_t i = 0; closed && i < 8; i += 2)
        closed = ends[i] == ends[i + 1] && (i == 0 || ends[i] != ends[i - 1]);
      const bool one_patch = patches[0] == patches[3];
      const bool split = one_patch || (patches[0] == patches[1] && patches[2] == patches[3]);
      through_[v] = closed && split && (one_patch || straight_seam(v));
    }
  }

  /// Merges every chain it can; returns the count, the quads that went (`gone`) and the
  /// merged quads.
  std::size_t run(std::vector<bool>& gone, std::vector<MeshElement>& merged) {
    gone.assign(mesh_.elements.size(), false);
    std::vector<bool> dropped(mesh_.nodes.size(), false);
    std::size_t chains = 0;
    for (std::uint32_t v = 0; v < mesh_.nodes.size(); ++v) {
      if (dropped[v]) continue;
      const auto pair = chain_pair(v);
      if (!pair) continue;
      std::vector<std::uint32_t> chain;
      bool closed = false;
      if (!trace(v, *pair, chain, closed)) continue;
      std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
      std::vector<MeshElement> made;
      if (!merge(chain, closed, gone, pairs, made)) continue;
      for (const auto& [a, b] : pairs) gone[a] = gone[b] = true;
      for (std::uint32_t c : chain) dropped[c] = true;
      merged.insert(merged.end(), made.begin(), made.end());
      ++chains;
    }
    return chains;
  }

 private:
  const Quad& quad(std::uint32_t q) const { return mesh_.elements[q].nodes; }

  /// Whether seam node v's two neighbours along the seam (those of edges in quads of both
  /// patches) lie on a straight line through it: a node of an arc's chords may not go, or the
  /// seam would leave the arc (a plate split by an arc seam is two coplanar patches).
  bool straight_seam(std::uint32_t v) const {
    std::vector<std::uint32_t> along;
    for (std::uint32_t o : neighbours(v)) {
      // The two quads at edge (v, o), in two patches for a seam edge.
      std::vector<std::uint32_t> patches;
      for (std::uint32_t q : around_[v])
        if (std::find(quad(q).begin(), quad(q).end(), o) != quad(q).end())
          patches.push_back(mesh_.elements[q].patch.value);
      if (patches.size() == 2 && patches[0] != patches[1]) along.push_back(o);
    }
    if (along.size() != 2) return false;
    const Vec3 a = mesh_.nodes[along[0]] - mesh_.nodes[v];
    const Vec3 b = mesh_.nodes[along[1]] - mesh_.nodes[v];
    const Vec3 c = cross(a, b);
    constexpr double k2 = kStraightBoundarySine * kStraightBoundarySine;
    return dot(a, b) < 0.0 && dot(c, c) <= k2 * dot(a, a) * dot(b, b);
  }

  /// Node v of quad q in q's patch frame.
  Vec2 at(std::uint32_t q, std::uint32_t v) const {
    return part_.patches[mesh_.elements[q].patch.index()].frame.to_2d(mesh_.nodes[v]);
  }

  double length(std::uint32_t a, std::uint32_t b) const {
    return distance(mesh_.nodes[a], mesh_.nodes[b]);
  }

  /// The other ends of the edges at v, once per quad that holds the edge, sorted.
  std::vector<std::uint32_t> edge_ends(std::uint32_t v) const {
    std::vector<std::uint32_t> n;
    for (std::uint32_t q : around_[v]) {
      const Quad& x = quad(q);
      for (std::size_t k = 0; k < 4; ++k)
        if (x[k] == v) {
          n.push_back(x[(k + 1) % 4]);
          n.push_back(x[(k + 3) % 4]);
        }
    }
    std::sort(n.begin(), n.end());
    return n;
  }

  /// The neighbours of v along edges.
  std::vector<std::uint32_t> neighbours(std::uint32_t v) const {
    std::vector<std::uint32_t> n = edge_ends(v);
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  }

  bool share_quad(std::uint32_t v, std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t q : around_[v]) {
      const Quad& x = quad(q);
      const auto has = [&](std::uint32_t n) { return std::find(x.begin(), x.end(), n) != x.end(); };
      if (has(a) && has(b)) return true;
    }
    return false;
  }

  /// The neighbour of a node a chain may pass (`through_`: four quads round it) opposite
  /// `from`: where a chain through v goes on; kNone when v is no such node.
  std::uint32_t opposite(std::uint32_t v, std::uint32_t from) const {
    if (!through_[v]) return kNone;
    const std::vector<std::uint32_t> n = neighbours(v);
    if (std::find(n.begin(), n.end(), from) == n.end()) return kNone;
    std::uint32_t out = kNone;
    for (std::uint32_t a : n)
      if (a != from && !share_quad(v, a, from)) {
        if (out != kNone) return kNone;
        out = a;
      }
    return out;
  }

  /// For a node a chain may pass: its two opposite neighbours along the chain (the pair whose
  /// edges are kRowThinRatio x longer than the other pair's), if any.
  std::optional<std::pair<std::uint32_t, std::uint32_t>> chain_pair(std::uint32_t v) const {
    if (!through_[v]) return std::nullopt;
    const std::vector<std::uint32_t> n = neighbours(v);  // four: its quads close round it
    const std::uint32_t across = opposite(v, n[0]);
    if (across == kNone) return std::nullopt;
    std::vector<std::uint32_t> rest;
    for (std::uint32_t a : n)
      if (a != n[0] && a != across) rest.push_back(a);
    const std::pair<std::uint32_t, std::uint32_t> pairs[2] = {{n[0], across}, {rest[0], rest[1]}};
    const auto len = [&](std::uint32_t a) { return length(v, a); };
    for (int k = 0; k < 2; ++k) {
      const auto& c = pairs[k];
      const auto& r = pairs[1 - k];
      const double rung = std::max(len(r.first), len(r.second));
      if (std::min(len(c.first), len(c.second)) >= kRowThinRatio * rung * (1.0 - kRowTieRel))
        return c;
    }
    return std::nullopt;
  }

  /// A boundary node that may go with a chain's end: removable, in two quads (of one patch:
  /// the pair across the chain's last edge), on a straight stretch of boundary.
  bool end_goes(std::uint32_t e, std::uint32_t from) const {
    if (!removable_[e] || around_[e].size() != 2) return false;
    std::vector<std::uint32_t> others;
    for (std::uint32_t q : around_[e]) {
      const Quad& x = quad(q);
      for (std::size_t k = 0; k < 4; ++k)
        if (x[k] == e) {
          for (std::uint32_t o : {x[(k + 1) % 4], x[(k + 3) % 4]})
            if (o != from) others.push_back(o);
        }
    }
    if (others.size() != 2) return false;
    const std::uint32_t q = around_[e].front();
    const Vec2 pe = at(q, e);
    const Vec2 a = at(q, others[0]) - pe, b = at(q, others[1]) - pe;
    const double s = cross(a, b);
    constexpr double k2 = kStraightBoundarySine * kStraightBoundarySine;
    return dot(a, b) < 0.0 && s * s <= k2 * dot(a, a) * dot(b, b);
  }

  /// The chain through v, both ways, ends included (boundary nodes that go with it), or round
  /// a ring (`closed`). False when an end does not allow the merge.
  bool trace(std::uint32_t v, std::pair<std::uint32_t, std::uint32_t> pair,
             std::vector<std::uint32_t>& chain, bool& closed) const {
    std::vector<std::uint32_t> half[2];
    closed = false;
    for (int side = 0; side < 2; ++side) {
      std::uint32_t prev = v, cur = side == 0 ? pair.first : pair.second;
      while (true) {
        if (cur == v) {
          closed = true;
          break;
        }
        const std::uint32_t next = opposite(cur, prev);
        if (next == kNone) {
          if (!end_goes(cur, prev)) return false;
          half[side].push_back(cur);
          break;
        }
        half[side].push_back(cur);
        if (half[side].size() > mesh_.nodes.size()) return false;
        prev = cur;
        cur = next;
      }
      if (closed) break;
    }
    chain.assign(half[0].rbegin(), half[0].rend());
    chain.push_back(v);
    if (!closed) chain.insert(chain.end(), half[1].begin(), half[1].end());
    std::vector<std::uint32_t> sorted = chain;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
    // A thin strip all along: every interior node thin across (its chain edges kRowThinRatio x
    // its rungs), but for the one next to each end (a strip's end: the rung there is as long
    // as the chain edge to the boundary), and those whose rungs are kRowThinRatio x shorter
    // than the chain's median edge (where the chain's edges shorten, at a strip's end inside
    // it: the corner of a box's thin walls).
    const std::size_t m = chain.size();
    const std::size_t edges = closed ? m : m - 1;
    std::vector<double> along;
    for (std::size_t i = 0; i < edges; ++i) along.push_back(length(chain[i], chain[(i + 1) % m]));
    const auto middle = along.begin() + static_cast<std::ptrdiff_t>(edges / 2);
    std::nth_element(along.begin(), middle, along.end());
    const double median = *middle;
    const std::size_t first = closed ? 0 : 2, last = closed ? m : m - 2;
    for (std::size_t i = first; i < last; ++i) {
      if (chain_pair(chain[i])) continue;
      const std::uint32_t prev = chain[(i + m - 1) % m], next = chain[(i + 1) % m];
      double rung = 0.0;
      for (std::uint32_t a : neighbours(chain[i]))
        if (a != prev && a != next) rung = std::max(rung, length(chain[i], a));
      if (rung * kRowThinRatio > median * (1.0 + kRowTieRel)) return false;
    }
    return true;
  }

  /// Each pair of quads across a chain edge (in one patch) as one quad: its four other nodes.
  /// False when a merged quad would be worse than its pair, or the chain no squarer.
  bool merge(const std::vector<std::uint32_t>& chain, bool closed, const std::vector<bool>& gone,
             std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
             std::vector<MeshElement>& made) const {
    const std::size_t m = chain.size();
    const std::size_t edges = closed ? m : m - 1;
    if (edges == 0) return false;
    double worst_old = 0.0, worst_new = 0.0;
    for (std::size_t i = 0; i < edges; ++i) {
      const std::uint32_t a = chain[i], b = chain[(i + 1) % m];
      // The two quads holding edge (a, b): one has it as a -> b, the other as b -> a.
      std::uint32_t up = kNone, down = kNone;
      for (std::uint32_t q : around_[a]) {
        const Quad& x = quad(q);
        for (std::size_t k = 0; k < 4; ++k) {
          if (x[k] == a && x[(k + 1) % 4] == b) up = q;
          if (x[k] == b && x[(k + 1) % 4] == a) down = q;
        }
      }
      if (up == kNone || down == kNone || gone[up] || gone[down]) return false;
      // A chain edge along a seam: its two quads are in two planes.
      if (mesh_.elements[up].patch != mesh_.elements[down].patch) return false;
      // up: a, b, p, q (counter-clockwise); down: b, a, r, s.
      const auto after = [&](std::uint32_t q, std::uint32_t from) {
        const Quad& x = quad(q);
        std::size_t k = 0;
        while (x[k] != from) ++k;
        return std::make_pair(x[(k + 2) % 4], x[(k + 3) % 4]);
      };
      const auto [p, q] = after(up, a);
      const auto [r, s] = after(down, b);
      const Quad nq{p, q, r, s};
      // All in up's patch frame (the pair's patch).
      const auto jacobian = [&](const Quad& x) {
        return min_scaled_jacobian(at(up, x[0]), at(up, x[1]), at(up, x[2]), at(up, x[3]));
      };
      const auto aspect = [&](const Quad& x) {
        return quad_aspect(at(up, x[0]), at(up, x[1]), at(up, x[2]), at(up, x[3]));
      };
      const Quad& u = quad(up);
      const Quad& d = quad(down);
      const double j_new = jacobian(nq), j_old = std::min(jacobian(u), jacobian(d));
      const double a_new = aspect(nq), a_u = aspect(u), a_d = aspect(d);
      // No merged quad worse than its pair in its worst corner, and each squarer than its pair
      // or square enough; the chain as a whole squarer.
      if (j_new < j_old - kRowJacobianSlack) return false;
      if (!(a_new < std::min(a_u, a_d) * (1.0 - kRowTieRel) ||
            a_new <= kRowAspectOk * (1.0 + kRowTieRel)))
        return false;
      worst_old = std::max({worst_old, a_u, a_d});
      worst_new = std::max(worst_new, a_new);
      pairs.emplace_back(up, down);
      MeshElement e = mesh_.elements[up];
      e.nodes = nq;
      made.push_back(e);
    }
    return worst_new < worst_old * (1.0 - kRowTieRel);
  }

  const Part& part_;
  const QuadMesh& mesh_;
  std::vector<bool> through_;  ///< nodes a chain may pass
  const std::vector<bool>& removable_;
  std::vector<std::vector<std::uint32_t>> around_;
};

}  // namespace

std::size_t merge_thin_rows(const Part& part, QuadMesh& mesh) {
  const std::vector<bool> pinned = pinned_nodes(mesh);
  const std::vector<bool> shared = shared_nodes(mesh);
  const std::vector<bool> vertex = vertex_nodes(part, mesh);
  // A chain passes a patch's interior node, or a node of a seam between two patches (pinned
  // because it is shared; MeshRows checks that its quads close round it, two in each patch);
  // a boundary node used by one patch, no B-Rep vertex, may go with a chain's end.
  std::vector<bool> through(mesh.nodes.size(), false), removable(mesh.nodes.size(), false);
  for (std::uint32_t v = 0; v < mesh.nodes.size(); ++v) {
    if (vertex[v]) continue;
    through[v] = !pinned[v] || shared[v];  // MeshRows keeps those of four quads round them
    removable[v] = pinned[v] && !shared[v];
  }
  MeshRows rows(part, mesh, std::move(through), removable);
  std::vector<bool> gone;
  std::vector<MeshElement> merged;
  const std::size_t chains = rows.run(gone, merged);
  if (chains == 0) return 0;
  replace_elements(mesh, gone, merged);
  return chains;
}

}  // namespace laytracks
