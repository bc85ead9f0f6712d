// Removing narrow corridors by deleting rails (paper 4.2.1-4.2.3); the medial axis is never
// edited. The rules chosen are in docs/cutgraph.md.
#include "narrow.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "corridors.hpp"
#include "laytracks/brep/union_find.hpp"
#include "rail_layer.hpp"

namespace laytracks::cutgraph_detail {
namespace {

/// The state of one round: the source rails laid with some deleted, and their corridors.
struct Round {
  CutGraph graph;
  std::vector<CorridorPiece> pieces;
  std::vector<RailLayer::Link> links;
};

Round lay_round(const Part& part,
                const std::vector<MedialAxis>& axes,
                const std::function<double(double)>& track_width,
                const std::vector<Vec3>& suppressed,
                OppositeCache& cache) {
  Round r;
  RailLayer layer(part, axes, r.graph, track_width);
  layer.suppress(suppressed);
  layer.lay_sources();
  r.links = layer.links();
  r.pieces = corridor_pieces_impl(part, axes, r.graph, &cache);
  return r;
}

/// True when G-CUT-VERT g sits at a corner that is not smooth (rails end there).
bool at_corner(const Part& part, const BoundaryIndex& index, const GCutVert& g) {
  if (!g.vertex) return false;
  for (const auto& c : index.corners_of(*g.vertex)) {
    if (corner_turn(part, c.patch, c.loop, c.index) != 0) return true;
  }
  return false;
}

}  // namespace

void remove_narrow_corridors(const Part& part,
                             const std::vector<MedialAxis>& axes,
                             const std::function<double(double)>& track_width,
                             double narrow_fraction,
                             bool one_per_round,
                             std::vector<Vec3>& suppressed,
                             std::vector<DeletedRail>& deleted,
                             std::size_t& kept,
                             std::size_t& rounds,
                             OppositeCache& cache) {
  const BoundaryIndex index(part);
  // Patches that share an edge.
  std::vector<std::vector<std::uint32_t>> neighbours(part.patches.size());
  for (const BrepEdge& e : part.edges)
    for (PatchId a : e.patches)
      for (PatchId b : e.patches)
        if (a != b) neighbours[a.index()].push_back(b.value);
  // Each round deletes rails (connected sets of source rails), then lays again: the narrowest
  // corridors first, so that a group of adjacent narrow corridors merges until the width
  // holds. A round deletes for every narrow corridor, narrowest first, whose deletion is far
  // from that of each narrower corridor of the round (deleted or waiting) in one of two ways:
  // by patches (its region, the patches of its pieces and of the rails it would delete, meets
  // neither the other's region nor a patch beside it), or by corridors (none of the corridors
  // it merges is one the other merges or one beside those, sharing a rail set with them).
  // Deletions that far apart change none of each other's corridors, so the rounds delete what
  // one deletion per round would (tested against `one_per_round`), in far fewer rounds: an
  // icosphere of 1280 triangles needs the first (17 rounds; 135 by corridors alone), a torus
  // of 24 x 12 quads, whose rails run round it, the second (2 rounds; 48 by patches alone). Bounded by the number of source points.
  for (std::size_t round = 0; round < 100000; ++round) {
    const Round r = lay_round(part, axes, track_width, suppressed, cache);
    const CutGraph& g = r.graph;
    // Rails joined through boundary points (not through MA nodes or corners) form one set.
    UnionFind uf(g.gverts.size());
    for (const auto& l : r.links) {
      if ((l.from & kMaNodeFlag) || (l.to & kMaNodeFlag)) continue;
      if (at_corner(part, index, g.gverts[l.from]) || at_corner(part, index, g.gverts[l.to]))
        continue;
      uf.unite(l.from, l.to);
    }
    // Break points of the CUT-SEGs: the G-CUT-VERT there, if any.
    std::map<LoopKey, GCutId> cut_at;
    const auto key = [&](PatchId p, std::uint32_t loop, double u) {
      return loop_key(part, p, loop, u);
    };
    for (const CutVert& c : g.cuts) cut_at[key(c.patch, c.at.loop, c.at.u())] = c.g;
    // Corridors: width (longest CUT-SEG) and bounding break points.
    std::map<std::size_t, double> width;
    std::map<std::size_t, double> radius;  // the longest rail bounding the corridor
    std::map<std::size_t, std::set<std::uint32_t>> bounds;
    std::set<std::size_t> small_feature;
    for (const CorridorPiece& c : r.pieces) {
      width[c.corridor] = std::max(width[c.corridor], c.length);
      const auto& poly = part.patches[c.patch.index()].polygon.loops[c.loop];
      const auto at = [&](double u) {
        const auto i = static_cast<std::size_t>(std::floor(u)) % poly.size();
        return lerp(poly[i], poly[(i + 1) % poly.size()], u - std::floor(u));
      };
      radius[c.corridor] = std::max({radius[c.corridor], distance(at(c.u0), c.ma0),
                                     distance(at(c.u1), c.ma1)});
      for (double u : {c.u0, c.u1}) {
        const auto it = cut_at.find(key(c.patch, c.loop, u));
        if (it == cut_at.end()) {
          // A corner: a convex one makes the corridor a small feature, which stays.
          const auto n = part.patches[c.patch.index()].polygon.loops[c.loop].size();
          const auto corner =
              static_cast<std::uint32_t>(std::llround(u) % static_cast<long long>(n));
          if (corner_turn(part, c.patch, c.loop, corner) > 0) small_feature.insert(c.corridor);
          continue;
        }
        bounds[c.corridor].insert(it->second.value);
      }
    }
    // Source points per rail set, and how many source rails end at each concave corner.
    std::map<std::size_t, std::vector<std::uint32_t>> sources_of;
    std::map<std::uint32_t, std::size_t> rays_at_vertex;
    for (std::uint32_t i = 0; i < g.gverts.size(); ++i) {
      if (!g.gverts[i].source) continue;
      sources_of[uf.find(i)].push_back(i);
      if (g.gverts[i].vertex) ++rays_at_vertex[g.gverts[i].vertex->value];
    }
    // Where each G-CUT-VERT first appears along the boundary (patch, loop, u).
    std::vector<LoopKey> place(g.gverts.size(), std::make_tuple(UINT32_MAX, UINT32_MAX, LLONG_MAX));
    for (const CutVert& c : g.cuts) {
      place[c.g.index()] = std::min(place[c.g.index()], key(c.patch, c.at.loop, c.at.u()));
    }
    // The branch point each rail set meets (its first), for rails through branch points.
    std::map<std::size_t, std::uint32_t> branch_of;
    for (const auto& l : r.links) {
      if (!(l.to & kMaNodeFlag) || (l.from & kMaNodeFlag)) continue;
      if (!g.macuts[l.to & ~kMaNodeFlag].branch) continue;
      branch_of.emplace(uf.find(l.from), l.to);
    }
    // Widths within rounding of each other, or of the threshold, must decide the same in every
    // pose: compare them on a grid of 1e-9 x the part's size.
    const double grain = 1e-9 * part.size;
    const auto quantum = [&](double x) { return std::llround(x / grain); };
    std::vector<std::pair<long long, std::size_t>> order;
    for (const auto& [corridor, w] : width) {
      if (quantum(w) < quantum(narrow_fraction * track_width(radius[corridor])))
        order.push_back({quantum(w), corridor});
    }
    std::sort(order.begin(), order.end());
    std::vector<std::pair<double, std::size_t>> narrow;
    for (const auto& [q, corridor] : order) narrow.push_back({width[corridor], corridor});
    // Patches per corridor and per rail set; the corridors each rail set bounds.
    std::map<std::size_t, std::set<std::uint32_t>> corridor_patches;
    for (const CorridorPiece& c : r.pieces) corridor_patches[c.corridor].insert(c.patch.value);
    std::map<std::size_t, std::set<std::uint32_t>> set_patches;
    for (const auto& l : r.links)
      for (std::uint32_t end : {l.from, l.to})
        if (!(end & kMaNodeFlag)) set_patches[uf.find(end)].insert(l.patch.value);
    std::map<std::size_t, std::set<std::size_t>> corridors_of_set;
    for (const auto& [corridor, gs] : bounds)
      for (std::uint32_t b : gs) corridors_of_set[uf.find(b)].insert(corridor);
    const auto sets_of = [&](std::size_t corridor) {
      std::set<std::size_t> sets;
      const auto it = bounds.find(corridor);
      if (it != bounds.end())
        for (std::uint32_t b : it->second) sets.insert(uf.find(b));
      return sets;
    };
    // What each deletion of the round (made, or waiting for the next round) claims.
    struct Claim {
      std::vector<bool> patches;    // its region and the patches beside it
      std::set<std::size_t> near;   // the corridors it merges and those beside them
    };
    std::vector<Claim> claims;
    bool removed = false;
    kept = 0;
    for (const auto& [w, corridor] : narrow) {
      if (small_feature.count(corridor)) {
        ++kept;
        continue;
      }
      // The rails across the corridor: the rail sets bounding it, those that meet at one branch
      // point taken together (a rail through a branch point, Table I cases 3 and 4). Delete
      // the unit with the fewest sources that does not take the last rail from a concave
      // vertex.
      std::map<std::uint32_t, std::vector<std::size_t>> units;  // key: MA node or set
      for (std::uint32_t b : bounds[corridor]) {
        const std::size_t set = uf.find(b);
        if (!sources_of.count(set)) continue;
        const auto node = branch_of.find(set);
        const std::uint32_t unit =
            node != branch_of.end() ? node->second : static_cast<std::uint32_t>(set);
        auto& u = units[unit];
        if (std::find(u.begin(), u.end(), set) == u.end()) u.push_back(set);
      }
      // Ties go to the unit whose first source comes first along the boundary: a key that does
      // not depend on how the axis happened to be numbered, so the choice is the same in every
      // pose.
      std::vector<std::uint32_t> best;
      std::vector<std::size_t> best_sets;
      LoopKey best_key{};
      for (const auto& [unit, sets] : units) {
        std::vector<std::uint32_t> srcs;
        for (std::size_t set : sets) {
          srcs.insert(srcs.end(), sources_of[set].begin(), sources_of[set].end());
        }
        const bool last_at_concave = std::any_of(srcs.begin(), srcs.end(), [&](std::uint32_t src) {
          return g.gverts[src].vertex && rays_at_vertex[g.gverts[src].vertex->value] <= 1;
        });
        if (last_at_concave) continue;
        auto unit_key = std::make_tuple(UINT32_MAX, UINT32_MAX, LLONG_MAX);
        for (std::uint32_t src : srcs) unit_key = std::min(unit_key, place[src]);
        if (best.empty() || srcs.size() < best.size() ||
            (srcs.size() == best.size() && unit_key < best_key)) {
          best = srcs;
          best_sets = sets;
          best_key = unit_key;
        }
      }
      if (best.empty()) {
        ++kept;
        continue;
      }
      // Its region: the patches of its CUT-SEGs and of the rails it deletes.
      std::set<std::uint32_t> region = corridor_patches[corridor];
      for (std::uint32_t src : best) {
        const auto it = set_patches.find(uf.find(src));
        if (it != set_patches.end()) region.insert(it->second.begin(), it->second.end());
      }
      // The corridors it merges: this one and those across the deleted rails.
      std::set<std::size_t> touched{corridor};
      for (std::size_t set : best_sets)
        touched.insert(corridors_of_set[set].begin(), corridors_of_set[set].end());
      // Far enough from every claim of the round by patches or by corridors.
      const bool waits = (one_per_round && removed) ||
                         std::any_of(claims.begin(), claims.end(), [&](const Claim& c) {
                           const bool by_patches = std::any_of(
                               region.begin(), region.end(), [&](std::uint32_t p) { return c.patches[p]; });
                           const bool by_corridors = std::any_of(
                               touched.begin(), touched.end(), [&](std::size_t k) { return c.near.count(k) > 0; });
                           return by_patches && by_corridors;
                         });
      Claim claim{std::vector<bool>(part.patches.size(), false), touched};
      for (std::uint32_t p : region) {
        claim.patches[p] = true;
        for (std::uint32_t q : neighbours[p]) claim.patches[q] = true;
      }
      for (std::size_t c : touched)
        for (std::size_t set : sets_of(c))
          claim.near.insert(corridors_of_set[set].begin(), corridors_of_set[set].end());
      claims.push_back(std::move(claim));
      if (waits) continue;  // a narrower corridor of the round is near: the next round
      for (std::uint32_t src : best) {
        const GCutVert& gv = g.gverts[src];
        suppressed.push_back(gv.position);
        DeletedRail d;
        d.at = gv.position;
        d.corridor_width = w;
        for (const CutVert& c : g.cuts) {
          if (c.g.value == src) d.patch = c.patch;
        }
        for (const RailSegment& seg : g.segments) {
          if (g.cuts[seg.cut.index()].g.value == src && g.macuts[seg.ma.index()].branch) {
            d.through_branch_point = true;
          }
        }
        deleted.push_back(d);
      }
      for (std::uint32_t src : best)
        if (g.gverts[src].vertex) --rays_at_vertex[g.gverts[src].vertex->value];
      removed = true;
    }
    if (!removed) return;
    ++rounds;
  }
}

}  // namespace laytracks::cutgraph_detail
