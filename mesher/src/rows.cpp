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
/// Boundary nodes that go with the chain lie on a straight boundary: the sine of the angle
/// between their two boundary edges at most this.
constexpr double kStraightSine = 1e-9;

/// Aspect ratio as quality.md defines it (measure_quad), of a quad in the patch's plane.
double quad_aspect(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const auto up = [](Vec2 v) { return Vec3{v.x, v.y, 0.0}; };
  return measure_quad({up(a), up(b), up(c), up(d)}, {0.0, 0.0, 1.0}).aspect_ratio;
}

class PatchRows {
 public:
  PatchRows(PatchQuads& pq, const std::vector<bool>& removable)
      : pq_(pq), removable_(removable), around_(pq.pos.size()) {
    for (std::uint32_t q = 0; q < pq_.quads.size(); ++q)
      for (std::uint32_t v : pq_.quads[q]) around_[v].push_back(q);
  }

  /// Merges every chain it can; returns the count, the quads that went (`gone`) and the
  /// merged quads.
  std::size_t run(std::vector<bool>& gone, std::vector<Quad>& merged) {
    gone.assign(pq_.quads.size(), false);
    std::vector<bool> dropped(pq_.pos.size(), false);
    std::size_t chains = 0;
    for (std::uint32_t v = 0; v < pq_.pos.size(); ++v) {
      if (dropped[v]) continue;
      const auto pair = chain_pair(v);
      if (!pair) continue;
      std::vector<std::uint32_t> chain;
      bool closed = false;
      if (!trace(v, *pair, chain, closed)) continue;
      std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
      std::vector<Quad> made;
      if (!merge(chain, closed, gone, pairs, made)) continue;
      for (const auto& [a, b] : pairs) gone[a] = gone[b] = true;
      for (std::uint32_t c : chain) dropped[c] = true;
      merged.insert(merged.end(), made.begin(), made.end());
      ++chains;
    }
    return chains;
  }

 private:
  /// The neighbours of v along edges, when v is interior with four quads.
  std::vector<std::uint32_t> neighbours(std::uint32_t v) const {
    std::vector<std::uint32_t> n;
    for (std::uint32_t q : around_[v]) {
      const Quad& x = pq_.quads[q];
      for (std::size_t k = 0; k < 4; ++k)
        if (x[k] == v) {
          n.push_back(x[(k + 1) % 4]);
          n.push_back(x[(k + 3) % 4]);
        }
    }
    std::sort(n.begin(), n.end());
    n.erase(std::unique(n.begin(), n.end()), n.end());
    return n;
  }

  bool share_quad(std::uint32_t v, std::uint32_t a, std::uint32_t b) const {
    for (std::uint32_t q : around_[v]) {
      const Quad& x = pq_.quads[q];
      const auto has = [&](std::uint32_t n) { return std::find(x.begin(), x.end(), n) != x.end(); };
      if (has(a) && has(b)) return true;
    }
    return false;
  }

  /// The neighbour of interior node v (four quads) opposite `from`: where a chain through v
  /// goes on; kNone when v is no such node.
  std::uint32_t opposite(std::uint32_t v, std::uint32_t from) const {
    if (pq_.fixed[v] || around_[v].size() != 4) return kNone;
    const std::vector<std::uint32_t> n = neighbours(v);
    if (n.size() != 4 || std::find(n.begin(), n.end(), from) == n.end()) return kNone;
    std::uint32_t out = kNone;
    for (std::uint32_t a : n)
      if (a != from && !share_quad(v, a, from)) {
        if (out != kNone) return kNone;
        out = a;
      }
    return out;
  }

  /// For an interior node of valence four: its two opposite neighbours along the chain (the
  /// pair whose edges are kRowThinRatio x longer than the other pair's), if any.
  std::optional<std::pair<std::uint32_t, std::uint32_t>> chain_pair(std::uint32_t v) const {
    if (pq_.fixed[v] || around_[v].size() != 4) return std::nullopt;
    const std::vector<std::uint32_t> n = neighbours(v);
    if (n.size() != 4) return std::nullopt;
    const std::uint32_t across = opposite(v, n[0]);
    if (across == kNone) return std::nullopt;
    std::vector<std::uint32_t> rest;
    for (std::uint32_t a : n)
      if (a != n[0] && a != across) rest.push_back(a);
    const std::pair<std::uint32_t, std::uint32_t> pairs[2] = {{n[0], across}, {rest[0], rest[1]}};
    const auto len = [&](std::uint32_t a) { return distance(pq_.pos[v], pq_.pos[a]); };
    for (int k = 0; k < 2; ++k) {
      const auto& c = pairs[k];
      const auto& r = pairs[1 - k];
      const double rung = std::max(len(r.first), len(r.second));
      if (std::min(len(c.first), len(c.second)) >= kRowThinRatio * rung) return c;
    }
    return std::nullopt;
  }

  /// A boundary node that may go with a chain's end: removable, in two quads of this patch
  /// (the pair across the chain's last edge), on a straight stretch of boundary.
  bool end_goes(std::uint32_t e, std::uint32_t from) const {
    if (!removable_[e] || around_[e].size() != 2) return false;
    std::vector<std::uint32_t> others;
    for (std::uint32_t q : around_[e]) {
      const Quad& x = pq_.quads[q];
      for (std::size_t k = 0; k < 4; ++k)
        if (x[k] == e) {
          for (std::uint32_t o : {x[(k + 1) % 4], x[(k + 3) % 4]})
            if (o != from) others.push_back(o);
        }
    }
    if (others.size() != 2) return false;
    const Vec2 a = pq_.pos[others[0]] - pq_.pos[e], b = pq_.pos[others[1]] - pq_.pos[e];
    const double s = cross(a, b);
    return dot(a, b) < 0.0 && s * s <= kStraightSine * kStraightSine * dot(a, a) * dot(b, b);
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
        if (half[side].size() > pq_.pos.size()) return false;
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
    // as the chain edge to the boundary).
    const std::size_t first = closed ? 0 : 2, last = closed ? chain.size() : chain.size() - 2;
    for (std::size_t i = first; i < last; ++i)
      if (!chain_pair(chain[i])) return false;
    return true;
  }

  /// The quad of q's nodes after removing the chain edge (a, b) it holds: its other two
  /// nodes, in its counter-clockwise order after b.
  bool merge(const std::vector<std::uint32_t>& chain, bool closed, const std::vector<bool>& gone,
             std::vector<std::pair<std::uint32_t, std::uint32_t>>& pairs,
             std::vector<Quad>& made) const {
    const std::size_t m = chain.size();
    const std::size_t edges = closed ? m : m - 1;
    if (edges == 0) return false;
    double worst_old = 0.0, worst_new = 0.0;
    for (std::size_t i = 0; i < edges; ++i) {
      const std::uint32_t a = chain[i], b = chain[(i + 1) % m];
      // The two quads holding edge (a, b): one has it as a -> b, the other as b -> a.
      std::uint32_t up = kNone, down = kNone;
      for (std::uint32_t q : around_[a]) {
        const Quad& x = pq_.quads[q];
        for (std::size_t k = 0; k < 4; ++k) {
          if (x[k] == a && x[(k + 1) % 4] == b) up = q;
          if (x[k] == b && x[(k + 1) % 4] == a) down = q;
        }
      }
      if (up == kNone || down == kNone || gone[up] || gone[down]) return false;
      // up: a, b, p, q (counter-clockwise); down: b, a, r, s.
      const auto after = [&](std::uint32_t q, std::uint32_t from) {
        const Quad& x = pq_.quads[q];
        std::size_t k = 0;
        while (x[k] != from) ++k;
        return std::make_pair(x[(k + 2) % 4], x[(k + 3) % 4]);
      };
      const auto [p, q] = after(up, a);
      const auto [r, s] = after(down, b);
      const Quad nq{p, q, r, s};
      const auto jacobian = [&](const Quad& x) {
        return min_scaled_jacobian(pq_.pos[x[0]], pq_.pos[x[1]], pq_.pos[x[2]], pq_.pos[x[3]]);
      };
      const auto aspect = [&](const Quad& x) {
        return quad_aspect(pq_.pos[x[0]], pq_.pos[x[1]], pq_.pos[x[2]], pq_.pos[x[3]]);
      };
      const Quad& u = pq_.quads[up];
      const Quad& d = pq_.quads[down];
      const double j_new = jacobian(nq), j_old = std::min(jacobian(u), jacobian(d));
      const double a_new = aspect(nq), a_u = aspect(u), a_d = aspect(d);
      // No merged quad worse than its pair in its worst corner, and each squarer than its pair
      // or square enough; the chain as a whole squarer.
      if (j_new < j_old - kRowJacobianSlack) return false;
      if (!(a_new < std::min(a_u, a_d) || a_new <= kRowAspectOk)) return false;
      worst_old = std::max({worst_old, a_u, a_d});
      worst_new = std::max(worst_new, a_new);
      pairs.emplace_back(up, down);
      made.push_back(nq);
    }
    return worst_new < worst_old;
  }

  PatchQuads& pq_;
  const std::vector<bool>& removable_;
  std::vector<std::vector<std::uint32_t>> around_;
};

}  // namespace

std::size_t merge_thin_rows(const Part& part, QuadMesh& mesh) {
  const std::vector<bool> pinned = pinned_nodes(mesh);
  // A boundary node may go when only one patch uses it and it is no B-Rep vertex.
  std::vector<std::uint32_t> patch_of(mesh.nodes.size(), kNone);
  std::vector<bool> shared(mesh.nodes.size(), false);
  for (const MeshElement& e : mesh.elements)
    for (std::uint32_t v : e.nodes) {
      if (patch_of[v] == kNone) patch_of[v] = e.patch.value;
      else if (patch_of[v] != e.patch.value) shared[v] = true;
    }
  const double tol = MeshTolerances::kOnBrep * part.size;  // at a vertex, as the check says
  std::vector<bool> vertex(mesh.nodes.size(), false);
  {
    // Nodes at B-Rep vertices, by sorted x.
    std::vector<std::pair<double, std::uint32_t>> by_x;
    for (std::uint32_t v = 0; v < mesh.nodes.size(); ++v) by_x.emplace_back(mesh.nodes[v].x, v);
    std::sort(by_x.begin(), by_x.end());
    for (const auto& pv : part.vertices) {
      auto it = std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(pv.position.x - tol, 0u));
      for (; it != by_x.end() && it->first <= pv.position.x + tol; ++it)
        if (distance(mesh.nodes[it->second], pv.position) <= tol) vertex[it->second] = true;
    }
  }
  const std::vector<std::vector<std::uint32_t>> by_patch = elements_by_patch(part, mesh);
  std::vector<bool> drop_element(mesh.elements.size(), false);
  std::vector<MeshElement> added;
  std::size_t chains = 0;
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    if (by_patch[p].empty()) continue;
    PatchQuads pq = patch_quads(part, mesh, p, by_patch[p], pinned);
    std::vector<bool> removable(pq.pos.size(), false);
    for (std::size_t i = 0; i < pq.pos.size(); ++i) {
      const std::uint32_t g = pq.global[i];
      removable[i] = pq.fixed[i] && !shared[g] && !vertex[g];
    }
    PatchRows rows(pq, removable);
    std::vector<bool> gone;
    std::vector<Quad> merged;
    const std::size_t n = rows.run(gone, merged);
    if (n == 0) continue;
    chains += n;
    const std::uint32_t shell = mesh.elements[pq.elements.front()].shell;
    for (std::size_t q = 0; q < gone.size(); ++q)
      if (gone[q]) drop_element[pq.elements[q]] = true;
    for (const Quad& q : merged) added.push_back(element_of(pq, q, p, shell));
  }
  if (chains == 0) return 0;
  replace_elements(mesh, drop_element, added);
  return chains;
}

}  // namespace laytracks
