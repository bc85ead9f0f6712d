// Algorithm II of the paper: rails laid breadth first from the Source G-CUT-VERTs, across
// patches through shared edges; then, in uniform mode, the track rails of every corridor.
// The rules chosen where the paper is silent are in docs/cutgraph.md.
#include "laytracks/cutgraph/cut_graph.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <sstream>

#include "boundary_index.hpp"
#include "corridors.hpp"
#include "narrow.hpp"
#include "rail_layer.hpp"

namespace laytracks {

using cutgraph_detail::BoundaryIndex;
using cutgraph_detail::corner_turn;
using cutgraph_detail::GCutRegistry;

const char* to_string(RailEnd end) {
  switch (end) {
    case RailEnd::Loop:
      return "loop";
    case RailEnd::FreeEdge:
      return "free-edge";
    case RailEnd::ConcaveVertex:
      return "concave-vertex";
    case RailEnd::BranchPoint:
      return "branch-point";
    case RailEnd::Junction:
      return "junction";
    case RailEnd::ConvexVertex:
      return "convex-vertex";
    case RailEnd::RoundCorner:
      return "round-corner";
    case RailEnd::Lost:
      return "lost";
  }
  return "lost";
}

namespace cutgraph_detail {

/// Splits the rail network into chains: maximal paths through points where exactly two rail
/// pieces meet; what is left are loops.
void extract_chains(const Part& part,
                    const BoundaryIndex& index,
                    const RailLayer& layer,
                    CutGraph& g) {
  std::map<std::uint32_t, std::vector<std::size_t>> at;  // node -> link indices
  const auto& links = layer.links();
  for (std::size_t i = 0; i < links.size(); ++i) {
    at[links[i].from].push_back(i);
    at[links[i].to].push_back(i);
  }
  const auto end_kind = [&](std::uint32_t node) {
    if (node & kMaNodeFlag) {
      return g.macuts[node & ~kMaNodeFlag].branch ? RailEnd::BranchPoint : RailEnd::RoundCorner;
    }
    const std::size_t degree = at[node].size();
    const GCutVert& gv = g.gverts[node];
    if (gv.vertex) {
      // Rails end at a corner, however many meet there (the fan of a concave vertex).
      bool free = true;
      for (const auto& c : index.corners_of(*gv.vertex)) {
        const int turn = corner_turn(part, c.patch, c.loop, c.index);
        if (turn < 0) return RailEnd::ConcaveVertex;
        if (turn > 0) return RailEnd::ConvexVertex;
        const Loop& loop = part.patches[c.patch.index()].loops[c.loop];
        const std::size_t n = loop.edges.size();
        for (EdgeId e : {loop.edges[c.index], loop.edges[(c.index + n - 1) % n]}) {
          free = free && part.edges[e.index()].patches.size() == 1;
        }
      }
      // A smooth or straight corner is an ordinary boundary point.
      if (degree >= 3) return RailEnd::Junction;
      return degree == 1 && free ? RailEnd::FreeEdge : RailEnd::Lost;
    }
    if (degree >= 3) return RailEnd::Junction;
    if (degree == 1 && part.edges[gv.edge.index()].patches.size() == 1) return RailEnd::FreeEdge;
    return RailEnd::Lost;
  };
  // Where chains stop: MA nodes, corners, and points where other than two rails meet.
  const auto stops = [&](std::uint32_t node) {
    if ((node & kMaNodeFlag) || at[node].size() != 2) return true;
    const RailEnd e = end_kind(node);
    return e == RailEnd::ConcaveVertex || e == RailEnd::ConvexVertex;
  };
  std::vector<bool> used(links.size(), false);
  const auto walk = [&](std::uint32_t start, std::size_t first) {
    RailChain chain;
    chain.start = end_kind(start);
    std::uint32_t node = start;
    std::size_t li = first;
    std::vector<PatchId> patches;
    while (true) {
      used[li] = true;
      const auto& l = links[li];
      patches.push_back(l.patch);
      chain.closure_gap = std::max(chain.closure_gap, l.gap);
      if (!(node & kMaNodeFlag)) chain.through.push_back(GCutId(node));
      node = l.from == node ? l.to : l.from;
      if (node == start && !stops(node)) {
        chain.start = chain.end = RailEnd::Loop;
        break;
      }
      if (stops(node)) {
        if (!(node & kMaNodeFlag)) chain.through.push_back(GCutId(node));
        chain.end = end_kind(node);
        break;
      }
      const auto& next = at[node];
      li = used[next[0]] ? next[1] : next[0];
      if (used[li]) {
        chain.end = RailEnd::Loop;
        break;
      }
    }
    std::sort(patches.begin(), patches.end());
    patches.erase(std::unique(patches.begin(), patches.end()), patches.end());
    chain.patches = patches;
    chain.source = std::any_of(chain.through.begin(), chain.through.end(),
                               [&](GCutId id) { return g.gverts[id.index()].source; });
    if (chain.end != RailEnd::Loop) chain.closure_gap = 0.0;
    g.chains.push_back(std::move(chain));
  };
  for (const auto& [node, list] : at) {
    if (stops(node)) {
      for (std::size_t li : list) {
        if (!used[li]) walk(node, li);
      }
    }
  }
  for (std::size_t li = 0; li < links.size(); ++li) {
    if (!used[li]) walk(links[li].from, li);  // what is left: loops
  }
}

}  // namespace cutgraph_detail

CutGraph build_cut_graph(const Part& part,
                         const std::vector<MedialAxis>& axes,
                         const CutGraphOptions& options) {
  CutGraph graph;
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    const Patch& patch = part.patches[p];
    std::vector<std::int32_t>& round = graph.round_arcs.emplace_back(part.arcs.size(), -1);
    for (std::size_t l = 0; l < patch.loops.size() && !patch.polygon.circle.empty(); ++l)
      for (std::size_t i = 0; i < patch.loops[l].edges.size(); ++i) {
        const std::int32_t k = patch.polygon.circle[l][i];
        const std::int64_t arc = part.edges[patch.loops[l].edges[i].index()].arc;
        if (k >= 0 && arc >= 0 && axes[p].is_round(static_cast<std::size_t>(k)))
          round[static_cast<std::size_t>(arc)] = k;
      }
  }
  std::vector<Vec3> suppressed;
  const TrackWidthLaw* law = options.adaptive;
  const bool tracks = options.track_width > 0.0 || law;
  // The track width at a medial radius (adaptive: the width a track would have there with
  // Delta theta_in alone); none when no tracks are laid.
  std::function<double(double)> track_width;
  if (tracks)
    track_width = [&](double radius) { return law ? law->width_for(radius, 1.0) : options.track_width; };
  cutgraph_detail::OppositeCache cache;
  // The source rails: as the narrow corridors' last round laid them (the deletions made, the
  // same rails and corridors that laying them again gives), else laid here.
  cutgraph_detail::LaidSources laid;
  if (tracks && options.narrow_fraction > 0.0) {
    cutgraph_detail::remove_narrow_corridors(
        part, axes, track_width, options.narrow_fraction, options.narrow_one_per_round,
        options.drop_crowded_rails, suppressed, graph.deleted, graph.narrow_kept,
        graph.narrow_rounds, graph.crowded_rails, cache, &laid);
  }
  if (!laid.graph) laid = cutgraph_detail::lay_sources(part, axes, track_width, suppressed, cache);
  CutGraph& g = *laid.graph;
  cutgraph_detail::RailLayer& layer = *laid.layer;
  g.round_arcs = std::move(graph.round_arcs);
  g.deleted = std::move(graph.deleted);
  g.narrow_kept = graph.narrow_kept;
  g.narrow_rounds = graph.narrow_rounds;
  g.crowded_rails = graph.crowded_rails;
  // The corridors of the graph as it is: searched again only after rails were laid (each
  // search maps every CUT-SEG across the axis; the tracks' seeds and the count share one).
  const auto corridors_now = [&] { return cutgraph_detail::find_corridors(part, axes, g, &cache); };
  cutgraph_detail::Corridors corridors = std::move(laid.corridors);
  g.corridor_count = corridors.count;
  if (tracks && options.lay_tracks) {
    const cutgraph_detail::TrackSpacing spacing{options.track_width, law};
    // Crowded seeds are not laid (docs/cutgraph.md, "Crowded rails").
    const double crowd = options.drop_crowded_rails ? options.narrow_fraction : 0.0;
    for (const auto& seed : cutgraph_detail::track_seeds(part, corridors, spacing))
      layer.lay_from(seed.patch, seed.point, crowd);
    corridors = corridors_now();
    // Sides the longest CUT-SEG's rails did not reach get tracks of their own (docs/cutgraph.md).
    for (int round = 0; round < 3; ++round) {
      const auto gaps = cutgraph_detail::gap_seeds(part, corridors, spacing);
      if (gaps.empty()) break;
      for (const auto& seed : gaps) layer.lay_from(seed.patch, seed.point, crowd);
      corridors = corridors_now();
    }
  }
  g.track_count = corridors.count;
  cutgraph_detail::extract_chains(part, cutgraph_detail::BoundaryIndex(part), layer, g);
  graph = std::move(g);
  for (const RailChain& c : graph.chains) {
    if (c.start == RailEnd::Lost || c.end == RailEnd::Lost) {
      graph.problems.push_back("a rail chain through " + std::to_string(c.through.size()) +
                               " boundary points ends where the geometry allows no end");
    }
  }
  return graph;
}

}  // namespace laytracks
