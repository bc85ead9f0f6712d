// Bends of thin strips squared (docs/mesher.md, "Bends of thin strips"). In a strip a few
// quads wide, the rails of a bend come from the branch point on its corner's diagonal: the
// bend is split on the diagonal from the reflex corner to the convex one (a mitre), and the
// quads along it are trapezoids, tapered at any length under twice the strip's width. Cut
// instead from the reflex corner straight across the strip (along the inward normals of its
// two walls), the bend is a square with rows of rectangles on either side.
//
// The pass cuts the mesh into cells at *rung chains*: paths of one to kBendRowsMax edges
// straight across the strip, from boundary to boundary through inner nodes of four quads (in
// a strip of k rows, the lines of edges across it). A cell with a reflex B-Rep vertex between
// its walls is meshed again as pieces between cuts from that vertex: a k x m grid where a
// piece has two cuts (or rung chains) and two straight walls, the face templates elsewhere (a
// bend's block, two cuts and two walls to the convex corner, both ways, the better kept).
// A cut that meets a rung chain, or lands beside its end, first joins the cell across it. The
// cell's rung chains and B-Rep vertices stay; the nodes on its straight walls are spaced
// again. Kept when, both relaxed, fewer quads are beyond Table III's thresholds and the worst
// corner is no lower, or as many are and the worst corner is higher by kBendWorstGain.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <vector>

#include "fill.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/check.hpp"
#include "laytracks/mesher/quality.hpp"
#include "patch_quads.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

using Quad = std::array<std::uint32_t, 4>;

/// A rung chain has at most this many edges: a strip at most this many quads across.
constexpr std::uint32_t kBendRowsMax = 3;
/// A rung chain, and a cut from a reflex corner, is at most this x h long.
constexpr double kBendCutMax = 2.5;
/// A cell of more quads is no strip's (a strip's cells end at rung chains about every h):
/// not meshed again, and no time spent on its boundary.
constexpr std::size_t kBendCellQuads = 256;
/// Rounds of joining the cells across the rung chains that cuts meet.
constexpr int kBendJoins = 3;
/// A reflex corner is cut when its walls turn by more than this (degrees): below it the two
/// cuts land a sliver apart.
constexpr double kBendTurnMin = 30.0;
/// A cut lands on a wall less than this (degrees) from parallel to the wall it leaves...
constexpr double kBendParallel = 30.0;
/// ... which is at least this x the cut long (a corner relief's step is not cut across).
constexpr double kBendWallMin = 0.5;
/// A cut lands on a kept node of the wall it reaches (a B-Rep vertex, a seam node) within this
/// x its length of the point straight across; within it of a rung chain's end, the cell across
/// the chain joins the cut's.
constexpr double kBendSnap = 0.25;
/// A piece that is not a grid (two cuts, two straight walls) spans at most this x h: a cell
/// that opens into a wide region is not a strip.
constexpr double kBendPieceSpan = 3.0;
/// ... and has at most this many nodes (a bend's square with a relief in it has 10; a needle's
/// walls at the spacing of its tip's chords would have thousands).
constexpr std::size_t kBendPieceNodes = 24;
/// A remesh with as many quads beyond Table III's thresholds is kept when its worst corner is
/// higher by this (a plus-shaped crossing of two strips: its centre split on a diagonal, 0.707,
/// against a grid, 0.99).
constexpr double kBendWorstGain = 0.1;
/// Lengths over a spacing within this of a half, and lengths within this ratio of a bound,
/// count as on it, alike in every pose (a grid-cell outline meets them exactly).
constexpr double kBendTieRel = 1e-9;

constexpr std::size_t kNoIndex = static_cast<std::size_t>(-1);

std::uint64_t edge_key(std::size_t a, std::size_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

/// Edges for a straight wall of length `len` at spacing `h`: rounded, halves down, at least
/// one.
std::uint32_t edges_for(double len, double h) {
  const double x = len / h;
  const double f = std::floor(x);
  const double r = x - f <= 0.5 + kBendTieRel ? f : f + 1.0;
  return static_cast<std::uint32_t>(std::max(1.0, r));
}

struct Union {
  std::vector<std::uint32_t> up;
  explicit Union(std::size_t n) : up(n) { std::iota(up.begin(), up.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (up[x] != x) x = up[x] = up[up[x]];
    return x;
  }
  /// The smaller root stays: each cell's root is its least element, whatever the order.
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) up[std::max(a, b)] = std::min(a, b);
  }
};

/// How an edge of a cell's boundary cycle lies.
enum class Side : std::uint8_t { Rung, FreeWall, SeamWall };

/// A node of a cell's remesh: a mesh node (id) or a new one (kNew), at pos (patch frame) and p3.
struct Node {
  static constexpr std::uint32_t kNew = 0xffffffffu;
  std::uint32_t id = kNew;
  Vec2 pos;
  Vec3 p3;
  bool free = false;  ///< off the cell's boundary: relaxed before the remesh is judged
};

struct Remesh {
  std::vector<Node> nodes;
  std::vector<Quad> quads;  ///< over `nodes`
  int beyond = 0;           ///< quads beyond Table III's thresholds, relaxed
  double worst = 0.0;       ///< their worst corner, relaxed
};

class BendCells {
 public:
  BendCells(const Part& part, const QuadMesh& mesh, double h, int sweeps)
      : part_(part),
        mesh_(mesh),
        h_(h),
        sweeps_(sweeps),
        pinned_(pinned_nodes(mesh)),
        shared_(shared_nodes(mesh)),
        vertex_(vertex_nodes(part, mesh)),
        around_(quads_at_mesh_nodes(mesh)),
        tol_(MeshTolerances::kOnBrep * part.size),
        edges_(edges_by_lower_node(mesh, [](std::size_t) { return true; })) {}

  /// What run() found: the elements to drop, those to add, and the new nodes (ids from the
  /// mesh's node count on).
  struct Changes {
    std::vector<bool> drop;
    std::vector<MeshElement> added;
    std::vector<Vec3> nodes;
    std::size_t cells = 0;
  };

  Changes run() {
    find_rung_chains();
    const std::size_t ne = mesh_.elements.size();
    // Cells: quads joined across interior edges of their patch that are on no rung chain.
    Union cells(ne);
    for_each_edge([&](std::uint32_t a, std::uint32_t b, const Uses& u) {
      if (inner(u) && rung_.count(edge_key(a, b)) == 0) cells.join(u.q[0], u.q[1]);
    });
    // Cells with a B-Rep vertex that is on no rung chain are candidates.
    std::vector<std::vector<std::uint32_t>> cell_quads;
    const auto gather = [&] {
      cell_quads.assign(ne, {});
      for (std::uint32_t q = 0; q < ne; ++q)
        if (mesh_.elements[q].is_quad()) cell_quads[cells.find(q)].push_back(q);
      for (std::vector<std::uint32_t>& quads : cell_quads) {
        bool any = false;
        for (std::uint32_t q : quads)
          for (std::uint32_t v : mesh_.elements[q].nodes) any = any || (vertex_[v] && !on_rung_[v]);
        if (!any) quads.clear();
      }
    };
    gather();
    // A cut that meets a rung chain, or lands beside one's end, joins the cell across the
    // chain to its own; again with the joined cells, up to kBendJoins rounds. Only then is
    // any cell meshed again: the cells are the same whatever their order.
    for (int round = 0; round < kBendJoins; ++round) {
      bool joined = false;
      for (std::uint32_t c = 0; c < ne; ++c) {
        if (cell_quads[c].empty()) continue;
        std::vector<std::uint32_t> across;
        remesh_cell(cell_quads[c], &across);
        for (std::uint32_t q : across) {
          if (cells.find(q) == cells.find(c)) continue;
          cells.join(q, c);
          joined = true;
        }
      }
      if (!joined) break;
      gather();
    }
    Changes ch;
    ch.drop.assign(ne, false);
    for (std::uint32_t c = 0; c < ne; ++c) {
      if (cell_quads[c].empty()) continue;
      const std::optional<Remesh> r = remesh_cell(cell_quads[c], nullptr);
      if (!r) continue;
      for (std::uint32_t q : cell_quads[c]) ch.drop[q] = true;
      std::vector<std::uint32_t> id(r->nodes.size());
      for (std::size_t i = 0; i < r->nodes.size(); ++i) {
        if (r->nodes[i].id != Node::kNew) {
          id[i] = r->nodes[i].id;
        } else {
          id[i] = static_cast<std::uint32_t>(mesh_.nodes.size() + ch.nodes.size());
          ch.nodes.push_back(r->nodes[i].p3);
        }
      }
      const MeshElement& first = mesh_.elements[cell_quads[c].front()];
      for (const Quad& x : r->quads) {
        MeshElement e = first;
        e.nodes = Quad{id[x[0]], id[x[1]], id[x[2]], id[x[3]]};
        ch.added.push_back(e);
      }
      ++ch.cells;
    }
    return ch;
  }

 private:
  /// The elements at an edge: the first two, and how many.
  struct Uses {
    std::array<std::uint32_t, 2> q{};
    std::uint32_t count = 0;
    bool has(std::uint32_t e) const { return (count > 0 && q[0] == e) || (count > 1 && q[1] == e); }
  };
  Uses uses(std::uint32_t a, std::uint32_t b) const {
    if (a > b) std::swap(a, b);
    Uses u;
    for (std::uint32_t k = edges_.start[a]; k < edges_.start[a + 1]; ++k)
      if (edges_.uses[k].first == b) {
        if (u.count < 2) u.q[u.count] = edges_.uses[k].second;
        ++u.count;
      }
    return u;
  }
  /// An interior edge of one patch: two quads of it.
  bool inner(const Uses& u) const {
    return u.count == 2 && mesh_.elements[u.q[0]].patch == mesh_.elements[u.q[1]].patch;
  }
  /// fn(a, b, uses) for every edge of the mesh, a < b, in node order.
  template <typename Fn>
  void for_each_edge(Fn&& fn) const {
    for (std::uint32_t a = 0; a + 1 < edges_.start.size(); ++a)
      for (std::uint32_t k = edges_.start[a]; k < edges_.start[a + 1];) {
        const std::uint32_t b = edges_.uses[k].first;
        Uses u;
        for (; k < edges_.start[a + 1] && edges_.uses[k].first == b; ++k) {
          if (u.count < 2) u.q[u.count] = edges_.uses[k].second;
          ++u.count;
        }
        fn(a, b, u);
      }
  }

  /// Rung chains: from a boundary node, along an interior edge of one patch, on through inner
  /// nodes of four quads by the edge opposite the one it came by, to a boundary node, in at
  /// most kBendRowsMax edges and kBendCutMax x h.
  void find_rung_chains() {
    on_rung_.assign(mesh_.nodes.size(), false);
    for_each_edge([&](std::uint32_t lo, std::uint32_t hi, const Uses& qs) {
      if (!inner(qs)) return;
      for (const bool flip : {false, true}) {
        std::uint32_t a = lo, b = hi;
        if (flip) std::swap(a, b);
        if (!pinned_[a]) continue;
        std::vector<std::uint32_t> chain{a, b};
        double len = distance(mesh_.nodes[a], mesh_.nodes[b]);
        bool ok = true;
        while (ok && !pinned_[chain.back()]) {
          const std::uint32_t x = chain.back(), from = chain[chain.size() - 2];
          if (chain.size() > kBendRowsMax || around_[x].size() != 4) {
            ok = false;
            break;
          }
          // The edge at x in neither quad of the edge it came by.
          const Uses in = uses(from, x);
          std::uint32_t to = Node::kNew;
          for (std::uint32_t q : around_[x]) {
            if (in.has(q)) continue;
            const Quad& e = mesh_.elements[q].nodes;
            std::size_t i = 0;
            while (e[i] != x) ++i;
            for (const std::uint32_t y : {e[(i + 1) % 4], e[(i + 3) % 4]}) {
              const Uses u = uses(x, y);
              if (inner(u) && !in.has(u.q[0]) && !in.has(u.q[1]) &&
                  mesh_.elements[u.q[0]].patch == mesh_.elements[qs.q[0]].patch)
                to = y;
            }
          }
          if (to == Node::kNew) {
            ok = false;
            break;
          }
          len += distance(mesh_.nodes[x], mesh_.nodes[to]);
          chain.push_back(to);
        }
        // Not from a B-Rep vertex: the cuts start there (a mitre's diagonal is no rung).
        if (!ok || vertex_[chain.front()] || vertex_[chain.back()] ||
            chain.size() - 1 > kBendRowsMax || len > kBendCutMax * h_ * (1.0 + kBendTieRel))
          continue;
        for (std::size_t k = 0; k + 1 < chain.size(); ++k)
          rung_.emplace(edge_key(chain[k], chain[k + 1]), chain.size() - 1);
        for (std::uint32_t v : chain) on_rung_[v] = true;
      }
    });
  }

  /// The length of the straight B-Rep edge of patch p from its vertex at `from` through the
  /// node at `toward` (0 when there is none: an arc's).
  double wall_length(std::size_t p, Vec3 from, Vec3 toward) const {
    for (const Loop& loop : part_.patches[p].loops)
      for (EdgeId e : loop.edges) {
        const BrepEdge& be = part_.edges[e.index()];
        if (be.arc >= 0) continue;
        Vec3 s = part_.vertices[be.a.index()].position, t = part_.vertices[be.b.index()].position;
        if (distance(t, from) <= tol_) std::swap(s, t);
        if (distance(s, from) > tol_) continue;
        const Vec3 d = t - s;
        const double len2 = dot(d, d);
        const double u = len2 > 0.0 ? std::clamp(dot(toward - s, d) / len2, 0.0, 1.0) : 0.0;
        if (distance(toward, s + u * d) <= tol_) return std::sqrt(len2);
      }
    return 0.0;
  }

  /// Whether the segment a-b (3D) lies on a straight (not arc) B-Rep edge of patch p: new
  /// nodes may go on it.
  bool on_straight_edge(std::size_t p, Vec3 a, Vec3 b) const {
    for (const Loop& loop : part_.patches[p].loops)
      for (EdgeId e : loop.edges) {
        const BrepEdge& be = part_.edges[e.index()];
        if (be.arc >= 0) continue;
        const Vec3 s = part_.vertices[be.a.index()].position;
        const Vec3 d = part_.vertices[be.b.index()].position - s;
        const double len2 = dot(d, d);
        const auto off = [&](Vec3 x) {
          const double u = len2 > 0.0 ? std::clamp(dot(x - s, d) / len2, 0.0, 1.0) : 0.0;
          return distance(x, s + u * d);
        };
        if (off(a) <= tol_ && off(b) <= tol_) return true;
      }
    return false;
  }

  class Cell;
  /// The cell's quads meshed again, when that is kept. With `across`, only the quads beyond
  /// the rung chains its cuts meet (or land beside the end of) are put there, and nothing is
  /// meshed.
  std::optional<Remesh> remesh_cell(const std::vector<std::uint32_t>& quads,
                                    std::vector<std::uint32_t>* across) const;

  const Part& part_;
  const QuadMesh& mesh_;
  const double h_;
  const int sweeps_;
  const std::vector<bool> pinned_, shared_, vertex_;
  const std::vector<std::vector<std::uint32_t>> around_;
  const double tol_;
  const EdgesByNode edges_;
  /// Edges on rung chains, with their chain's edge count; nodes on them.
  std::unordered_map<std::uint64_t, std::size_t> rung_;
  std::vector<bool> on_rung_;
};

/// One cell meshed again (BendCells::remesh_cell), step by step: its boundary cycle, the cuts
/// from its reflex corners, the chords they become and the ring with their feet, the pieces
/// between the chords, the quads of each piece, and the judgement. A step that cannot go on
/// returns why (for LAYTRACKS_DEBUG_BENDS); nullptr is on.
class BendCells::Cell {
 public:
  /// With `blocks`, a bend's block (two chains from its reflex corner, two walls to its convex
  /// one) is a rows x rows grid; without, it goes to the templates like any other piece.
  Cell(const BendCells& b, const std::vector<std::uint32_t>& quads, bool blocks)
      : b_(b),
        quads_(quads),
        blocks_(blocks),
        patch_(b.mesh_.elements[quads.front()].patch.index()),
        frame_(b.part_.patches[patch_].frame) {}

  std::optional<Remesh> remesh(std::vector<std::uint32_t>* across) {
    static const bool debug = std::getenv("LAYTRACKS_DEBUG_BENDS") != nullptr;
    const char* why = quads_.size() > kBendCellQuads ? "large" : boundary();
    if (why == nullptr) {
      find_cuts(across);
      if (across != nullptr) return std::nullopt;
      why = cuts_.empty() ? "no cut" : lay_chords();
    }
    if (why == nullptr) why = split();
    for (std::size_t k = 0; why == nullptr && k < pieces_.size(); ++k) why = mesh_piece(pieces_[k]);
    if (why != nullptr) {
      if (debug)
        std::fprintf(stderr, "bends: cell of %zu quads at node %u: %s\n", quads_.size(),
                     b_.mesh_.elements[quads_.front()].nodes[0], why);
      return std::nullopt;
    }
    const bool keep = judge();
    if (debug)
      std::fprintf(stderr,
                   "bends: cell of %zu quads at node %u (%zu round, %zu cuts, %zu pieces, %zu "
                   "rows): %zu quads, beyond %d -> %d, worst %.3f -> %.3f%s\n",
                   quads_.size(), b_.mesh_.elements[quads_.front()].nodes[0], n_, chords_.size(),
                   pieces_.size(), rows_, r_.quads.size(), was_beyond_, now_beyond_, was_, now_,
                   keep ? " kept" : "");
    if (!keep) return std::nullopt;
    // Only the nodes the quads use.
    std::vector<std::size_t> renum(r_.nodes.size(), kNoIndex);
    Remesh used;
    for (Quad& x : r_.quads)
      for (std::uint32_t& v : x) {
        if (renum[v] == kNoIndex) {
          renum[v] = used.nodes.size();
          used.nodes.push_back(r_.nodes[v]);
        }
        v = static_cast<std::uint32_t>(renum[v]);
      }
    used.quads = std::move(r_.quads);
    used.beyond = now_beyond_;
    used.worst = now_;
    return used;
  }

 private:
  std::size_t next(std::size_t i) const { return (i + 1) % n_; }
  std::size_t prev(std::size_t i) const { return (i + n_ - 1) % n_; }

  /// The cell's boundary: the edges of its quads that no other quad of it uses, chained
  /// counter-clockwise from its least node (the same start in every pose); how each lies, the
  /// rung chains' edge count, and the nodes kept (B-Rep vertices, seam nodes, rung chains'
  /// nodes, wall nodes where the wall turns).
  const char* boundary() {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> out_edges, all;
    std::vector<std::uint64_t> keys;
    for (std::uint32_t q : quads_) {
      const Quad& x = b_.mesh_.elements[q].nodes;
      for (std::size_t k = 0; k < 4; ++k) {
        all.emplace_back(x[k], x[(k + 1) % 4]);
        keys.push_back(edge_key(x[k], x[(k + 1) % 4]));
      }
    }
    std::vector<std::uint64_t> sorted = keys;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < all.size(); ++i) {
      const auto range = std::equal_range(sorted.begin(), sorted.end(), keys[i]);
      if (range.second - range.first == 1) out_edges.push_back(all[i]);
    }
    std::sort(out_edges.begin(), out_edges.end());
    for (std::size_t i = 1; i < out_edges.size(); ++i)
      if (out_edges[i].first == out_edges[i - 1].first) return "pinched";
    cyc_ = {out_edges.front().first};
    for (;;) {
      const auto it =
          std::lower_bound(out_edges.begin(), out_edges.end(), std::make_pair(cyc_.back(), 0u));
      if (it == out_edges.end() || it->first != cyc_.back()) return "open";
      if (it->second == cyc_.front()) break;
      cyc_.push_back(it->second);
      if (cyc_.size() > out_edges.size()) return "loops";
    }
    if (cyc_.size() != out_edges.size()) return "holes";
    n_ = cyc_.size();
    side_.resize(n_);
    pos_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      pos_[i] = frame_.to_2d(b_.mesh_.nodes[cyc_[i]]);
      const Uses qs = b_.uses(cyc_[i], cyc_[next(i)]);
      if (qs.count == 1) {
        side_[i] = Side::FreeWall;
      } else if (b_.inner(qs)) {
        side_[i] = Side::Rung;
        const auto it = b_.rung_.find(edge_key(cyc_[i], cyc_[next(i)]));
        if (it == b_.rung_.end()) return "inner edge";
        if (rows_ != 0 && rows_ != it->second) return "rows differ";
        rows_ = it->second;
      } else {
        side_[i] = Side::SeamWall;
      }
    }
    if (rows_ == 0) return "no rung chain";
    keep_.assign(n_, false);
    for (std::size_t i = 0; i < n_; ++i) {
      const std::uint32_t v = cyc_[i];
      const Vec2 u = pos_[next(i)] - pos_[i], w = pos_[i] - pos_[prev(i)];
      const bool turns =
          std::abs(cross(u, w)) > kStraightBoundarySine * norm(u) * norm(w) || dot(u, w) <= 0.0;
      keep_[i] = b_.vertex_[v] || b_.shared_[v] || side_[i] == Side::Rung ||
                 side_[prev(i)] == Side::Rung || turns;
    }
    return nullptr;
  }

  /// The quads across cycle edge e (a rung chain's), for `across`.
  void join_across(std::size_t e, std::vector<std::uint32_t>* across) const {
    if (across == nullptr) return;
    const Uses u = b_.uses(cyc_[e], cyc_[next(e)]);
    for (std::uint32_t k = 0; k < std::min(u.count, 2u); ++k)
      if (std::find(quads_.begin(), quads_.end(), u.q[k]) == quads_.end())
        across->push_back(u.q[k]);
  }

  /// Cuts from reflex B-Rep vertices with free walls on both sides, along each wall's inward
  /// normal, to the first edge of the cycle they meet: a free wall on a straight B-Rep edge (or
  /// a kept node near the point across), within kBendCutMax x h. A cut that meets a rung chain
  /// or lands beside its end puts the quads across it in `across` instead.
  void find_cuts(std::vector<std::uint32_t>* across) {
    const double h = b_.h_;
    for (std::size_t i = 0; i < n_; ++i) {
      if (!b_.vertex_[cyc_[i]] || side_[i] != Side::FreeWall || side_[prev(i)] != Side::FreeWall ||
          b_.on_rung_[cyc_[i]])
        continue;
      const Vec2 din = pos_[i] - pos_[prev(i)], dout = pos_[next(i)] - pos_[i];
      const double turn = std::atan2(cross(din, dout), dot(din, dout)) * 180.0 / kPi;
      // Reflex by more than kBendTurnMin (a turn of exactly that, a regular 12-gon's, is none:
      // its rounding is either side of it by pose).
      if (!(turn < -kBendTurnMin * (1.0 + kBendTieRel))) continue;
      for (const Vec2 d : {din, dout}) {
        const Vec2 normal = Vec2{-d.y, d.x} * (1.0 / norm(d));  // inward: the cell on the left
        // The first edge the ray meets. Alike in every pose: edges within kBendTieRel of
        // parallel to it are not met, an edge met within kBendTieRel of an end is met, and of
        // two met at one distance (to kBendTieRel: at the node between them) the first in the
        // cycle's order is taken.
        double best = std::numeric_limits<double>::infinity();
        std::size_t hit = kNoIndex;
        double hit_s = 0.0;
        for (std::size_t j = 0; j < n_; ++j) {
          if (j == i || next(j) == i) continue;
          const Vec2 e = pos_[next(j)] - pos_[j];
          const double den = cross(normal, e);
          if (std::abs(den) <= kBendTieRel * norm(e)) continue;
          const Vec2 ap = pos_[j] - pos_[i];
          const double t = cross(ap, e) / den;
          const double s = cross(ap, normal) / den;
          if (s < -kBendTieRel || s > 1.0 + kBendTieRel || !(t > kBendTieRel * h)) continue;
          if (t < best * (1.0 - kBendTieRel)) {
            best = t;
            hit = j;
            hit_s = std::clamp(s, 0.0, 1.0);
          }
        }
        if (hit == kNoIndex || best > kBendCutMax * h * (1.0 + kBendTieRel)) continue;
        // Across a strip: onto a wall (not a rung chain) within kBendParallel of parallel to
        // the wall it leaves, which is at least kBendWallMin x the cut long (not a relief's
        // step).
        if (side_[hit] == Side::Rung) {
          join_across(hit, across);
          continue;
        }
        const Vec2 e = pos_[next(hit)] - pos_[hit];
        if (std::abs(cross(d, e)) >=
                std::sin(kBendParallel * kPi / 180.0) * (1.0 - kBendTieRel) * norm(d) * norm(e) ||
            dot(d, e) >= 0.0)
          continue;
        const std::size_t along = d == din ? prev(i) : next(i);
        if (b_.wall_length(patch_, b_.mesh_.nodes[cyc_[i]], b_.mesh_.nodes[cyc_[along]]) <
            kBendWallMin * best * (1.0 - kBendTieRel))
          continue;
        Cut cut{i, hit, hit_s, kNoIndex, pos_[i] + best * normal};
        const double reach = kBendSnap * best * (1.0 + kBendTieRel);
        // Near a rung chain's end (any node of the cycle within reach of the point across)
        // the cell across the chain joins this one (a cut beside a rung would leave a sliver,
        // or a piece of three sides); else the nearest kept node within reach takes the cut
        // (the first in the cycle's order at one distance), or it lands on a free wall of a
        // straight B-Rep edge.
        bool near_rung = false;
        double nearest = reach;
        for (std::size_t k = 0; k < n_; ++k) {
          const double dk = distance(pos_[k], cut.at);
          if (dk > reach || k == i) continue;
          if (!b_.vertex_[cyc_[k]])
            for (const std::size_t edge : {k, prev(k)})
              if (side_[edge] == Side::Rung) {
                near_rung = true;
                join_across(edge, across);
              }
          if (keep_[k] && b_.pinned_[cyc_[k]] &&
              (cut.to_node == kNoIndex || dk < nearest * (1.0 - kBendTieRel))) {
            cut.to_node = k;
            nearest = dk;
          }
        }
        if (near_rung) continue;
        if (cut.to_node == kNoIndex) {
          if (side_[hit] != Side::FreeWall ||
              !b_.on_straight_edge(patch_, b_.mesh_.nodes[cyc_[hit]],
                                   b_.mesh_.nodes[cyc_[next(hit)]]))
            continue;
        } else if (cut.to_node == i || cut.to_node == next(i) || cut.to_node == prev(i)) {
          continue;
        }
        cuts_.push_back(cut);
      }
    }
  }

  /// The remesh's nodes (the cycle's, then each cut's inner nodes and foot), the chords (the
  /// nodes of each cut, `rows_` edges; of two that cross the later goes, as does one that
  /// crosses the cycle), the ring (the cycle
  /// with the feet), and the fixed edges (rung chains' and chords', by chain).
  const char* lay_chords() {
    for (std::size_t i = 0; i < n_; ++i)
      r_.nodes.push_back(Node{cyc_[i], pos_[i], b_.mesh_.nodes[cyc_[i]]});
    std::vector<std::vector<std::pair<double, std::size_t>>> feet(n_);  // new feet by edge
    for (const Cut& cut : cuts_) {
      const Vec2 to_pos = cut.to_node == kNoIndex ? cut.at : pos_[cut.to_node];
      const std::size_t to = cut.to_node;
      bool clash = false;
      for (const std::vector<std::size_t>& c : chords_) {
        const std::size_t a = c.front(), e = c.back();
        if ((a == cut.from && e == to) || (e == cut.from && a == to)) clash = true;
        if (a == cut.from || e == cut.from || (to != kNoIndex && (a == to || e == to))) continue;
        if (segments_meet(r_.nodes[a].pos, r_.nodes[e].pos, pos_[cut.from], to_pos)) clash = true;
      }
      // A cut taken by a kept node leans off its ray: it must still cross no edge of the cycle
      // (but those at its ends, and the one its foot lands on).
      for (std::size_t j = 0; j < n_ && !clash; ++j) {
        if (j == cut.from || next(j) == cut.from) continue;
        // An edge through the cut's foot (its own, or one beside it when the foot is at a
        // node) only touches it there.
        const Vec2 a = pos_[j], e = pos_[next(j)] - pos_[j];
        const double u = std::clamp(dot(to_pos - a, e) / dot(e, e), 0.0, 1.0);
        if (distance(to_pos, a + u * e) <= kBendTieRel * distance(pos_[cut.from], to_pos)) continue;
        clash = segments_meet(a, pos_[next(j)], pos_[cut.from], to_pos);
      }
      if (clash) continue;
      std::vector<std::size_t> chord{cut.from};
      for (std::size_t k = 1; k < rows_; ++k) {
        const double s = static_cast<double>(k) / static_cast<double>(rows_);
        chord.push_back(r_.nodes.size());
        const Vec2 p = pos_[cut.from] + s * (to_pos - pos_[cut.from]);
        r_.nodes.push_back(Node{Node::kNew, p, frame_.to_3d(p), true});
      }
      if (to == kNoIndex) {
        const Vec3 a = b_.mesh_.nodes[cyc_[cut.edge]], e = b_.mesh_.nodes[cyc_[next(cut.edge)]];
        chord.push_back(r_.nodes.size());
        feet[cut.edge].emplace_back(cut.s, r_.nodes.size());
        r_.nodes.push_back(Node{Node::kNew, cut.at, a + cut.s * (e - a)});
      } else {
        chord.push_back(to);
      }
      // Inner chord nodes in 3D on the line between its ends.
      const Vec3 a3 = r_.nodes[chord.front()].p3, b3 = r_.nodes[chord.back()].p3;
      for (std::size_t k = 1; k + 1 < chord.size(); ++k)
        r_.nodes[chord[k]].p3 =
            a3 + (static_cast<double>(k) / static_cast<double>(rows_)) * (b3 - a3);
      chords_.push_back(std::move(chord));
    }
    side_of_.assign(r_.nodes.size(), Side::Rung);
    for (std::size_t i = 0; i < n_; ++i) {
      ring_.push_back(i);
      side_of_[i] = side_[i];
      std::sort(feet[i].begin(), feet[i].end());
      for (std::size_t k = 0; k < feet[i].size(); ++k) {
        if (k > 0 && feet[i][k].first - feet[i][k - 1].first <= kBendTieRel) return "feet meet";
        ring_.push_back(feet[i][k].second);
        side_of_[feet[i][k].second] = side_[i];
      }
    }
    kept_.assign(r_.nodes.size(), true);  // the chords' nodes are kept
    for (std::size_t i = 0; i < n_; ++i) kept_[i] = keep_[i];
    std::size_t chain = 0;
    for (std::size_t k = 0; k < ring_.size(); ++k) {
      const std::size_t a = ring_[k], e = ring_[(k + 1) % ring_.size()];
      if (side_of_[a] != Side::Rung) continue;
      // A new chain where the previous ring edge is not a rung edge of the same run.
      if (side_of_[ring_[(k + ring_.size() - 1) % ring_.size()]] != Side::Rung) ++chain;
      fixed_edge_[edge_key(a, e)] = chain;
    }
    // A run of rung edges of more than `rows_` edges is two chains end to end.
    std::unordered_map<std::size_t, std::size_t> count;
    for (const auto& [key, c] : fixed_edge_) ++count[c];
    for (const auto& [c, edges] : count)
      if (edges != rows_) return "rung chains end to end";
    for (const std::vector<std::size_t>& c : chords_) {
      ++chain;
      for (std::size_t k = 0; k + 1 < c.size(); ++k) fixed_edge_[edge_key(c[k], c[k + 1])] = chain;
    }
    return nullptr;
  }

  /// The pieces: the ring split along every chord.
  const char* split() {
    struct Todo {
      std::vector<std::size_t> poly;
      std::vector<std::size_t> chords;  // indices into chords_
    };
    std::vector<Todo> todo{{ring_, {}}};
    for (std::size_t c = 0; c < chords_.size(); ++c) todo.back().chords.push_back(c);
    while (!todo.empty()) {
      Todo t = std::move(todo.back());
      todo.pop_back();
      if (t.chords.empty()) {
        pieces_.push_back(std::move(t.poly));
        continue;
      }
      const std::vector<std::size_t>& c = chords_[t.chords.front()];
      const auto place = [&](std::size_t v) {
        return static_cast<std::size_t>(std::find(t.poly.begin(), t.poly.end(), v) -
                                        t.poly.begin());
      };
      const std::size_t ia = place(c.front()), ib = place(c.back());
      if (ia == t.poly.size() || ib == t.poly.size()) return "chord off its piece";
      Todo t1, t2;
      for (std::size_t k = ia;; k = (k + 1) % t.poly.size()) {
        t1.poly.push_back(t.poly[k]);
        if (k == ib) break;
      }
      for (std::size_t k = c.size() - 2; k >= 1; --k) t1.poly.push_back(c[k]);  // back along it
      for (std::size_t k = ib;; k = (k + 1) % t.poly.size()) {
        t2.poly.push_back(t.poly[k]);
        if (k == ia) break;
      }
      for (std::size_t k = 1; k + 1 < c.size(); ++k) t2.poly.push_back(c[k]);
      for (std::size_t k = 1; k < t.chords.size(); ++k) {
        const std::vector<std::size_t>& d = chords_[t.chords[k]];
        const bool in1 = std::find(t1.poly.begin(), t1.poly.end(), d.front()) != t1.poly.end() &&
                         std::find(t1.poly.begin(), t1.poly.end(), d.back()) != t1.poly.end();
        (in1 ? t1 : t2).chords.push_back(t.chords[k]);
      }
      todo.push_back(std::move(t1));
      todo.push_back(std::move(t2));
    }
    return nullptr;
  }

  /// A piece's side: a rung chain or a chord (fixed edges of one chain), a straight free wall
  /// between kept nodes (its inner nodes go and its edges are counted again), or one other
  /// edge (a seam's, an arc's: fixed).
  struct Link {
    std::vector<std::size_t> nodes;  // from its first node to its last, in the piece
    bool wall = false;               // spaced again
    std::size_t chain = kNoIndex;
    double len = 0.0;
    std::uint32_t edges = 0;
  };

  std::size_t chain_of(std::size_t a, std::size_t e) const {
    const auto f = fixed_edge_.find(edge_key(a, e));
    return f == fixed_edge_.end() ? kNoIndex : f->second;
  }

  /// The piece's sides, from a kept node where one begins; none when a wall bends.
  std::optional<std::vector<Link>> links_of(const std::vector<std::size_t>& piece) const {
    const std::size_t pn = piece.size();
    const auto at = [&](std::size_t k) { return piece[k % pn]; };
    std::size_t start = kNoIndex;
    for (std::size_t k = 0; k < pn && start == kNoIndex; ++k) {
      const std::size_t cin = chain_of(at(k + pn - 1), at(k)), cout = chain_of(at(k), at(k + 1));
      if (kept_[at(k)] && (cin != cout || cin == kNoIndex)) start = k;
    }
    if (start == kNoIndex) return std::nullopt;
    std::vector<Link> links;
    for (std::size_t k = 0; k < pn;) {
      const std::size_t a = at(start + k);
      Link l;
      l.nodes.push_back(a);
      l.chain = chain_of(a, at(start + k + 1));
      if (l.chain != kNoIndex) {
        while (k < pn && chain_of(at(start + k), at(start + k + 1)) == l.chain) {
          ++k;
          l.nodes.push_back(at(start + k));
        }
      } else {
        do {
          ++k;
          l.nodes.push_back(at(start + k));
        } while (k < pn && !kept_[at(start + k)]);
        if (side_of_[a] == Side::FreeWall &&
            b_.on_straight_edge(patch_, r_.nodes[l.nodes.front()].p3,
                                r_.nodes[l.nodes.back()].p3)) {
          l.wall = true;
        } else if (l.nodes.size() != 2) {
          return std::nullopt;
        }
      }
      for (std::size_t j = 0; j + 1 < l.nodes.size(); ++j)
        l.len += distance(r_.nodes[l.nodes[j]].pos, r_.nodes[l.nodes[j + 1]].pos);
      l.edges = static_cast<std::uint32_t>(l.nodes.size() - 1);
      links.push_back(std::move(l));
    }
    return links;
  }

  /// The quads of one piece: a grid (two chains of `rows_` edges across, two straight walls
  /// between them: both walls round(L / h) edges, a Coons patch inside), or the templates
  /// (walls at the spacing of the piece's chains, at most h; one more edge on the wall of the
  /// longest edges when the count is odd).
  const char* mesh_piece(const std::vector<std::size_t>& piece) {
    const double h = b_.h_;
    std::optional<std::vector<Link>> found = links_of(piece);
    if (!found) return "bent wall";
    std::vector<Link>& links = *found;
    const bool grid = links.size() == 4 && links[0].wall == links[2].wall &&
                      links[1].wall == links[3].wall && links[0].wall != links[1].wall &&
                      links[links[0].wall ? 1 : 0].chain != kNoIndex &&
                      links[links[0].wall ? 3 : 2].chain != kNoIndex;
    // A bend's block: two chains of `rows_` edges from the reflex corner, two straight walls
    // meeting at the convex corner (chain, chain, wall, wall in some turn of the cycle): a
    // rows x rows grid, whatever the walls' lengths (a sharp bend's kite).
    std::size_t block = kNoIndex;  // the link after which the two walls come
    if (blocks_ && links.size() == 4)
      for (std::size_t j = 0; j < 4 && !grid; ++j)
        if (links[j].chain != kNoIndex && links[(j + 1) % 4].chain != kNoIndex &&
            links[(j + 2) % 4].wall && links[(j + 3) % 4].wall && links[j].edges == rows_ &&
            links[(j + 1) % 4].edges == rows_)
          block = (j + 1) % 4;
    if (grid) {
      const std::size_t w = links[0].wall ? 0 : 1;
      const std::uint32_t m = edges_for(0.5 * (links[w].len + links[w + 2].len), h);
      links[w].edges = links[w + 2].edges = m;
    } else if (block != kNoIndex) {
      links[(block + 1) % 4].edges = links[(block + 2) % 4].edges =
          static_cast<std::uint32_t>(rows_);
    } else {
      double chain_len = 0.0;
      std::size_t count = 0;
      for (const Link& l : links)
        if (l.chain != kNoIndex) {
          chain_len += l.len;
          count += l.edges;
        }
      const double spacing = count > 0 ? std::min(h, chain_len / static_cast<double>(count)) : h;
      double span = 0.0;
      for (const Link& a : links)
        for (const Link& e : links)
          span = std::max(span,
                          distance(r_.nodes[a.nodes.front()].pos, r_.nodes[e.nodes.front()].pos));
      if (span > kBendPieceSpan * h * (1.0 + kBendTieRel)) return "wide piece";
      std::uint32_t edges = 0;
      for (Link& l : links) {
        if (l.wall) l.edges = edges_for(l.len, spacing);
        edges += l.edges;
      }
      if (edges % 2 != 0) {
        Link* longest = nullptr;
        for (Link& l : links)
          if (l.wall && (longest == nullptr ||
                         l.len / l.edges > longest->len / longest->edges * (1.0 + kBendTieRel)))
            longest = &l;
        if (longest == nullptr) return "odd piece";
        ++longest->edges;
      }
    }
    // The piece's new sides: each link's nodes, the walls' spaced evenly.
    std::vector<std::vector<std::size_t>> sides;
    for (const Link& l : links) {
      std::vector<std::size_t> s;
      if (!l.wall) {
        s = l.nodes;
      } else {
        const Node a = r_.nodes[l.nodes.front()], e = r_.nodes[l.nodes.back()];
        s.push_back(l.nodes.front());
        for (std::uint32_t k = 1; k < l.edges; ++k) {
          const double t = static_cast<double>(k) / l.edges;
          s.push_back(r_.nodes.size());
          r_.nodes.push_back(
              Node{Node::kNew, a.pos + t * (e.pos - a.pos), a.p3 + t * (e.p3 - a.p3)});
        }
        s.push_back(l.nodes.back());
      }
      sides.push_back(std::move(s));
    }
    if (grid) return coons_grid(sides, links[0].wall ? 0 : 1);
    if (block != kNoIndex) return coons_grid(sides, block);
    return templates(sides);
  }

  /// A Coons grid on four sides, `w` the first wall: G(i, 0) along it, G(m, j) up the chain
  /// after it, G(i, k) along the other wall backwards, G(0, j) down the chain before it.
  const char* coons_grid(const std::vector<std::vector<std::size_t>>& sides, std::size_t w) {
    const std::vector<std::size_t>& bottom = sides[w];
    const std::vector<std::size_t>& right = sides[(w + 1) % 4];
    const std::vector<std::size_t>& top = sides[(w + 2) % 4];
    const std::vector<std::size_t>& left = sides[(w + 3) % 4];
    const std::size_t m = bottom.size() - 1, k = right.size() - 1;
    if (top.size() != m + 1 || left.size() != k + 1) return "grid sides differ";
    std::vector<std::size_t> g((m + 1) * (k + 1));
    const auto at = [&](std::size_t i, std::size_t j) -> std::size_t& {
      return g[j * (m + 1) + i];
    };
    for (std::size_t i = 0; i <= m; ++i) {
      at(i, 0) = bottom[i];
      at(i, k) = top[m - i];
    }
    for (std::size_t j = 0; j <= k; ++j) {
      at(m, j) = right[j];
      at(0, j) = left[k - j];
    }
    for (std::size_t j = 1; j < k; ++j)
      for (std::size_t i = 1; i < m; ++i) {
        const double s = static_cast<double>(i) / static_cast<double>(m),
                     t = static_cast<double>(j) / static_cast<double>(k);
        const auto coons = [&](auto get) {
          return (1 - t) * get(at(i, 0)) + t * get(at(i, k)) + (1 - s) * get(at(0, j)) +
                 s * get(at(m, j)) -
                 ((1 - s) * (1 - t) * get(at(0, 0)) + s * (1 - t) * get(at(m, 0)) +
                  (1 - s) * t * get(at(0, k)) + s * t * get(at(m, k)));
        };
        const Vec2 p = coons([&](std::size_t v) { return r_.nodes[v].pos; });
        const Vec3 p3 = coons([&](std::size_t v) { return r_.nodes[v].p3; });
        at(i, j) = r_.nodes.size();
        r_.nodes.push_back(Node{Node::kNew, p, p3, true});
      }
    for (std::size_t j = 0; j < k; ++j)
      for (std::size_t i = 0; i < m; ++i)
        r_.quads.push_back(Quad{static_cast<std::uint32_t>(at(i, j)),
                                static_cast<std::uint32_t>(at(i + 1, j)),
                                static_cast<std::uint32_t>(at(i + 1, j + 1)),
                                static_cast<std::uint32_t>(at(i, j + 1))});
    return nullptr;
  }

  /// Any other piece: the re-fill's templates (fill_cavity), in the piece's own frame.
  const char* templates(const std::vector<std::vector<std::size_t>>& sides) {
    std::vector<std::size_t> cycle;
    for (const std::vector<std::size_t>& s : sides)
      cycle.insert(cycle.end(), s.begin(), s.end() - 1);
    if (cycle.size() % 2 != 0) return "odd cycle";
    if (cycle.size() > kBendPieceNodes) return "piece of many nodes";
    std::vector<Vec2> poly;
    for (std::size_t v : cycle) poly.push_back(r_.nodes[v].pos);
    const LocalFrame cf(poly);
    FaceInput face;
    for (const Vec2 p : poly) face.cycle.push_back(cf.to_local(p));
    face.free_nodes.assign(poly.size(), false);
    FaceSide all;
    all.kind = FaceSide::Kind::Boundary;
    all.edges = static_cast<std::uint32_t>(poly.size());
    face.sides.push_back(all);
    const std::optional<FaceMesh> fm = fill_cavity(face);
    if (!fm) return "no fill";
    std::vector<std::size_t> id = cycle;
    for (const Vec2 q : fm->interior) {
      id.push_back(r_.nodes.size());
      const Vec2 p = cf.to_patch(q);
      r_.nodes.push_back(Node{Node::kNew, p, frame_.to_3d(p), true});
    }
    for (const auto& x : fm->quads)
      r_.quads.push_back(
          Quad{static_cast<std::uint32_t>(id[x[0]]), static_cast<std::uint32_t>(id[x[1]]),
               static_cast<std::uint32_t>(id[x[2]]), static_cast<std::uint32_t>(id[x[3]])});
    return nullptr;
  }

  /// The old quads and the new, each relaxed inside the cell's cycle (in the cycle's own
  /// frame: the same problem in every pose): kept when fewer quads are beyond Table III's
  /// thresholds and the worst corner is no lower, or as many and the worst corner higher by
  /// kBendWorstGain. The new free nodes take their relaxed places.
  bool judge() {
    const LocalFrame cf(pos_);
    const auto relax_and_judge = [&](std::vector<Vec2>& at, const std::vector<bool>& fixed,
                                     const std::vector<Quad>& qs, int& beyond, double& worst) {
      if (b_.sweeps_ > 0) final_sweeps(at, fixed, qs, b_.sweeps_, kFinalEscapeTarget);
      beyond = 0;
      worst = std::numeric_limits<double>::infinity();
      for (const Quad& x : qs) {
        beyond +=
            beyond_table_iii(measure_planar_quad(at[x[0]], at[x[1]], at[x[2]], at[x[3]])) ? 1 : 0;
        worst = std::min(worst, min_scaled_jacobian(at[x[0]], at[x[1]], at[x[2]], at[x[3]]));
      }
    };
    {
      // The old: the cycle's nodes fixed, the cell's inner nodes free.
      std::vector<std::uint32_t> ids(cyc_.begin(), cyc_.end());
      std::unordered_map<std::uint32_t, std::uint32_t> local;
      for (std::uint32_t i = 0; i < n_; ++i) local[cyc_[i]] = i;
      std::vector<Quad> qs;
      for (std::uint32_t q : quads_) {
        Quad x = b_.mesh_.elements[q].nodes;
        for (std::uint32_t& v : x) {
          const auto it = local.emplace(v, static_cast<std::uint32_t>(ids.size()));
          if (it.second) ids.push_back(v);
          v = it.first->second;
        }
        qs.push_back(x);
      }
      std::vector<Vec2> at;
      for (std::uint32_t v : ids) at.push_back(cf.to_local(frame_.to_2d(b_.mesh_.nodes[v])));
      std::vector<bool> fixed(ids.size(), false);
      std::fill(fixed.begin(), fixed.begin() + static_cast<std::ptrdiff_t>(n_), true);
      relax_and_judge(at, fixed, qs, was_beyond_, was_);
    }
    std::vector<Vec2> at;
    std::vector<bool> fixed;
    for (const Node& v : r_.nodes) {
      at.push_back(cf.to_local(v.pos));
      fixed.push_back(!v.free);
    }
    relax_and_judge(at, fixed, r_.quads, now_beyond_, now_);
    for (std::size_t k = 0; k < r_.nodes.size(); ++k)
      if (r_.nodes[k].free) {
        r_.nodes[k].pos = cf.to_patch(at[k]);
        r_.nodes[k].p3 = frame_.to_3d(r_.nodes[k].pos);
      }
    return (now_beyond_ < was_beyond_ && settled(now_) >= settled(was_)) ||
           (now_beyond_ == was_beyond_ && settled(now_) >= settled(was_) + kBendWorstGain);
  }

  struct Cut {
    std::size_t from;
    std::size_t edge;                ///< cycle edge it lands on (edge i: node i to i + 1)
    double s;                        ///< along that edge
    std::size_t to_node = kNoIndex;  ///< a kept node it lands on instead
    Vec2 at;
  };

  const BendCells& b_;
  const std::vector<std::uint32_t>& quads_;
  const bool blocks_;
  const std::size_t patch_;
  const Frame& frame_;
  // The boundary (boundary()).
  std::vector<std::uint32_t> cyc_;
  std::size_t n_ = 0;
  std::vector<Side> side_;
  std::vector<Vec2> pos_;
  std::size_t rows_ = 0;  ///< the rung chains' edge count (all alike)
  std::vector<bool> keep_;
  // The cuts, chords, ring and pieces.
  std::vector<Cut> cuts_;
  Remesh r_;
  std::vector<std::vector<std::size_t>> chords_;
  std::vector<std::size_t> ring_;
  std::vector<Side> side_of_;  ///< of the ring edge from each node
  std::vector<bool> kept_;
  std::unordered_map<std::uint64_t, std::size_t> fixed_edge_;
  std::vector<std::vector<std::size_t>> pieces_;
  // The judgement.
  int was_beyond_ = 0, now_beyond_ = 0;
  double was_ = 0.0, now_ = 0.0;
};

std::optional<Remesh> BendCells::remesh_cell(const std::vector<std::uint32_t>& quads,
                                             std::vector<std::uint32_t>* across) const {
  // A bend's block as a grid and as the templates fill it: the better kept (fewer quads beyond
  // Table III's thresholds, then the higher worst corner; the templates' on a tie). A sharp
  // bend's kite is better as a grid, a bend with a chamfer or a long leg beside it sometimes
  // not.
  if (across != nullptr) return Cell(*this, quads, false).remesh(across);
  std::optional<Remesh> plain = Cell(*this, quads, false).remesh(nullptr);
  std::optional<Remesh> blocks = Cell(*this, quads, true).remesh(nullptr);
  if (!blocks) return plain;
  if (!plain || blocks->beyond < plain->beyond ||
      (blocks->beyond == plain->beyond && settled(blocks->worst) > settled(plain->worst)))
    return blocks;
  return plain;
}

}  // namespace

std::size_t square_thin_bends(const Part& part, QuadMesh& mesh, double size, int sweeps) {
  if (!(size > 0.0)) return 0;
  BendCells::Changes ch = BendCells(part, mesh, size, sweeps).run();
  if (ch.cells == 0) return 0;
  mesh.nodes.insert(mesh.nodes.end(), ch.nodes.begin(), ch.nodes.end());
  replace_elements(mesh, ch.drop, ch.added);
  return ch.cells;
}

}  // namespace laytracks
