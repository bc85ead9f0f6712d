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

/// True when G-CUT-VERT g sits at a corner that is not smooth (rails end there).
bool at_corner(const Part& part, const BoundaryIndex& index, const GCutVert& g) {
  if (!g.vertex) return false;
  for (const auto& c : index.corners_of(*g.vertex)) {
    if (corner_turn(part, c.patch, c.loop, c.index) != 0) return true;
  }
  return false;
}

/// Whether the source points `srcs` hold the last source rail of a concave vertex
/// (`rays_at_vertex`: the source rails at each), which may not be deleted.
bool holds_last_ray(const std::vector<std::uint32_t>& srcs,
                    const CutGraph& g,
                    const std::vector<std::size_t>& rays_at_vertex) {
  return std::any_of(srcs.begin(), srcs.end(), [&](std::uint32_t src) {
    return g.gverts[src].vertex && rays_at_vertex[g.gverts[src].vertex->index()] <= 1;
  });
}

/// The place of a G-CUT-VERT not on any loop (no CUT-VERT): after every other.
constexpr LoopKey kNoPlace{UINT32_MAX, UINT32_MAX, LLONG_MAX};

/// The first of the source points `srcs` along the boundary (`place`: where each G-CUT-VERT
/// first appears): the key that orders rail sets and units the same in every pose.
LoopKey first_place(const std::vector<std::uint32_t>& srcs, const std::vector<LoopKey>& place) {
  LoopKey k = kNoPlace;
  for (std::uint32_t src : srcs) k = std::min(k, place[src]);
  return k;
}

/// Crowded rails (docs/cutgraph.md, "Crowded rails"): a source rail set that reaches at least
/// kCrowdMinPoints points inside B-Rep edges (it runs across patches) and has, at
/// kCrowdShare of them or more, a point of a rail set kept before it on the same edge closer
/// than narrow_fraction x the track width is not laid. Sets are judged in the order of their
/// first source along the boundary (`place`, the same in every pose); the sets that may not go
/// (too short, no source, the last ray of a concave vertex) are kept first. On a shell of
/// thin triangles every facet's branch point sends rails that drift across the facets beside
/// it (a wedge's two-way mapping keeps the distance from its tip, and its sides differ in
/// length), and they come to lie a fraction of a track apart over many facets, in one corridor
/// too long and too uneven for its longest CUT-SEG to find narrow.
constexpr std::size_t kCrowdMinPoints = 5;
constexpr double kCrowdShare = 0.75;

/// The source points of the crowded rail sets of the graph, in order (see above).
/// `rays_at_vertex`: the source rails at each concave vertex (a copy: the sets dropped here
/// take theirs away, and the last may not go).
std::vector<std::uint32_t> crowded_sources(
    const Part& part,
    const CutGraph& g,
    UnionFind& uf,
    const std::vector<std::vector<std::uint32_t>>& sources_of,
    std::vector<std::size_t> rays_at_vertex,
    const std::vector<LoopKey>& place,
    const std::function<double(double)>& track_width,
    double narrow_fraction) {
  const std::size_t n = g.gverts.size();
  // The radius at each G-CUT-VERT: its longest rail segment.
  std::vector<double> radius(n, 0.0);
  for (const RailSegment& seg : g.segments) {
    const CutVert& c = g.cuts[seg.cut.index()];
    double& r = radius[c.g.index()];
    r = std::max(r, distance(c.position, g.macuts[seg.ma.index()].point.position));
  }
  // Each set's points inside edges.
  std::vector<std::vector<std::uint32_t>> points(n);
  for (std::uint32_t i = 0; i < n; ++i)
    if (!g.gverts[i].vertex) points[uf.find(i)].push_back(i);
  std::vector<std::uint32_t> candidates;
  std::vector<std::vector<std::uint32_t>> kept_on_edge(part.edges.size());
  const auto keep = [&](std::uint32_t set) {
    for (std::uint32_t i : points[set]) kept_on_edge[g.gverts[i].edge.index()].push_back(i);
  };
  const auto last_at_concave = [&](std::uint32_t set) {
    return holds_last_ray(sources_of[set], g, rays_at_vertex);
  };
  for (std::uint32_t set = 0; set < n; ++set) {
    if (uf.find(set) != set) continue;
    if (sources_of[set].empty() || last_at_concave(set) || points[set].size() < kCrowdMinPoints)
      keep(set);
    else
      candidates.push_back(set);
  }
  std::vector<std::pair<LoopKey, std::uint32_t>> order;
  for (std::uint32_t set : candidates) order.emplace_back(first_place(sources_of[set], place), set);
  std::sort(order.begin(), order.end());
  // Distances on the widths' grid, as everywhere here.
  const auto quantum = [&](double x) { return width_quantum(part, x); };
  std::vector<std::uint32_t> crowded;
  for (const auto& [key, set] : order) {
    std::size_t near = 0;
    for (std::uint32_t i : points[set]) {
      const long long reach = quantum(narrow_fraction * track_width(radius[i]));
      const auto& others = kept_on_edge[g.gverts[i].edge.index()];
      near += std::any_of(others.begin(), others.end(), [&](std::uint32_t k) {
                return quantum(distance(g.gverts[i].position, g.gverts[k].position)) < reach;
              })
                  ? 1u
                  : 0u;
    }
    if (static_cast<double>(near) < kCrowdShare * static_cast<double>(points[set].size()) ||
        last_at_concave(set)) {
      keep(set);
      continue;
    }
    for (std::uint32_t src : sources_of[set]) {
      crowded.push_back(src);
      if (g.gverts[src].vertex) --rays_at_vertex[g.gverts[src].vertex->index()];
    }
  }
  return crowded;
}

}  // namespace

LaidSources::LaidSources() = default;
LaidSources::LaidSources(LaidSources&&) noexcept = default;
LaidSources& LaidSources::operator=(LaidSources&&) noexcept = default;
LaidSources::~LaidSources() = default;

LaidSources lay_sources(const Part& part,
                        const std::vector<MedialAxis>& axes,
                        const std::function<double(double)>& track_width,
                        const std::vector<Vec3>& suppressed,
                        OppositeCache& cache,
                        bool corridors) {
  LaidSources laid;
  laid.graph = std::make_unique<CutGraph>();
  laid.layer = std::make_unique<RailLayer>(part, axes, *laid.graph, track_width);
  laid.layer->suppress(suppressed);
  laid.layer->lay_sources();
  if (corridors) laid.corridors = find_corridors(part, axes, *laid.graph, &cache);
  return laid;
}

void remove_narrow_corridors(const Part& part,
                             const std::vector<MedialAxis>& axes,
                             const std::function<double(double)>& track_width,
                             double narrow_fraction,
                             bool one_per_round,
                             bool drop_crowded,
                             std::vector<Vec3>& suppressed,
                             std::vector<DeletedRail>& deleted,
                             std::size_t& kept,
                             std::size_t& rounds,
                             std::size_t& crowded,
                             OppositeCache& cache,
                             LaidSources* last) {
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
  // of 24 x 12 quads, whose rails run round it, the second (2 rounds; 48 by patches alone).
  // Bounded by the number of source points.
  for (std::size_t round = 0; round < 100000; ++round) {
    // This round's source rails (with the deletions so far) and their corridors.
    const bool crowd_round = round == 0 && drop_crowded;
    LaidSources laid = lay_sources(part, axes, track_width, suppressed, cache, !crowd_round);
    const CutGraph& g = *laid.graph;
    const std::vector<RailLayer::Link>& links = laid.layer->links();
    // Rails joined through boundary points (not through MA nodes or corners) form one set.
    UnionFind uf(g.gverts.size());
    for (const auto& l : links) {
      if ((l.from & kMaNodeFlag) || (l.to & kMaNodeFlag)) continue;
      if (at_corner(part, index, g.gverts[l.from]) || at_corner(part, index, g.gverts[l.to]))
        continue;
      uf.unite(l.from, l.to);
    }
    const auto key = [&](PatchId p, std::uint32_t loop, double u) {
      return loop_key(part, p, loop, u);
    };
    // Source points per rail set, and how many source rails end at each concave corner.
    std::vector<std::vector<std::uint32_t>> sources_of(g.gverts.size());
    std::vector<std::size_t> rays_at_vertex(part.vertices.size(), 0);
    for (std::uint32_t i = 0; i < g.gverts.size(); ++i) {
      if (!g.gverts[i].source) continue;
      sources_of[uf.find(i)].push_back(i);
      if (g.gverts[i].vertex) ++rays_at_vertex[g.gverts[i].vertex->index()];
    }
    // Where each G-CUT-VERT first appears along the boundary (patch, loop, u); the patch of its
    // last CUT-VERT.
    std::vector<LoopKey> place(g.gverts.size(), kNoPlace);
    std::vector<PatchId> patch_of(g.gverts.size());
    for (const CutVert& c : g.cuts) {
      place[c.g.index()] = std::min(place[c.g.index()], key(c.patch, c.at.loop, c.at.u()));
      patch_of[c.g.index()] = c.patch;
    }
    // Before the first round's corridors are searched: the crowded rail sets are not laid
    // (when none is, the corridors of these rails are searched now).
    if (crowd_round) {
      const std::vector<std::uint32_t> drop = crowded_sources(
          part, g, uf, sources_of, rays_at_vertex, place, track_width, narrow_fraction);
      if (!drop.empty()) {
        for (std::uint32_t src : drop) suppressed.push_back(g.gverts[src].position);
        crowded = drop.size();
        continue;
      }
      laid.corridors = find_corridors(part, axes, g, &cache);
    }
    const std::vector<CorridorPiece> pieces = corridor_pieces_of(part, g, laid.corridors);
    // Break points of the CUT-SEGs: the G-CUT-VERT there, if any (the last CUT-VERT at a
    // place names it), found by binary search.
    std::vector<std::pair<LoopKey, GCutId>> cut_at;
    cut_at.reserve(g.cuts.size());
    for (const CutVert& c : g.cuts) cut_at.emplace_back(key(c.patch, c.at.loop, c.at.u()), c.g);
    std::stable_sort(cut_at.begin(), cut_at.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    const auto cut_g = [&](const LoopKey& k) -> const GCutId* {
      const auto it = std::upper_bound(cut_at.begin(), cut_at.end(), k,
                                       [](const LoopKey& x, const auto& y) { return x < y.first; });
      if (it == cut_at.begin() || std::prev(it)->first != k) return nullptr;
      return &std::prev(it)->second;
    };
    // Corridors (dense ids): width (longest CUT-SEG) and bounding break points.
    std::size_t corridors = 0;
    for (const CorridorPiece& c : pieces) corridors = std::max(corridors, c.corridor + 1);
    std::vector<double> width(corridors, 0.0);
    std::vector<double> radius(corridors, 0.0);  // the longest rail bounding the corridor
    std::vector<std::vector<std::uint32_t>> bounds(corridors);  // ascending, no repeats
    std::vector<bool> small_feature(corridors, false);
    std::vector<std::vector<std::uint32_t>> corridor_patches(corridors);  // ascending
    for (const CorridorPiece& c : pieces) {
      width[c.corridor] = std::max(width[c.corridor], c.length);
      const auto& poly = part.patches[c.patch.index()].polygon.loops[c.loop];
      const auto at = [&](double u) {
        const auto i = static_cast<std::size_t>(std::floor(u)) % poly.size();
        return lerp(poly[i], poly[(i + 1) % poly.size()], u - std::floor(u));
      };
      radius[c.corridor] = std::max({radius[c.corridor], distance(at(c.u0), c.ma0),
                                     distance(at(c.u1), c.ma1)});
      corridor_patches[c.corridor].push_back(c.patch.value);
      for (double u : {c.u0, c.u1}) {
        const GCutId* gc = cut_g(key(c.patch, c.loop, u));
        if (!gc) {
          // A corner: a convex one makes the corridor a small feature, which stays.
          const auto n = part.patches[c.patch.index()].polygon.loops[c.loop].size();
          const auto corner =
              static_cast<std::uint32_t>(std::llround(u) % static_cast<long long>(n));
          if (corner_turn(part, c.patch, c.loop, corner) > 0) small_feature[c.corridor] = true;
          continue;
        }
        bounds[c.corridor].push_back(gc->value);
      }
    }
    const auto sort_unique = [](auto& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    for (auto& b : bounds) sort_unique(b);
    for (auto& cp : corridor_patches) sort_unique(cp);
    // The G-CUT-VERTs whose rails run through a branch point.
    std::vector<bool> via_branch(g.gverts.size(), false);
    for (const RailSegment& seg : g.segments)
      if (g.macuts[seg.ma.index()].branch) via_branch[g.cuts[seg.cut.index()].g.index()] = true;
    // Widths within rounding of each other, or of the threshold, must decide the same in every
    // pose: compare them on a grid of 1e-9 x the part's size (and so the rails' lengths below).
    const auto quantum = [&](double x) { return width_quantum(part, x); };
    // The branch point each rail set meets, for rails through branch points. A set that meets
    // several takes the one its links reach from the G-CUT-VERT first along the boundary
    // (place), then by the shorter rail: keys of the part's own geometry, the same in every
    // pose. The first link laid followed the axis's numbering, which differs between poses
    // (fuzz seed 38038's bent_027, a grid outline bent in two: a concave corner's rail met two
    // branch points, and which one it took decided whether its last ray was in a unit; 383
    // quads as given, 404 scaled by 1e3).
    constexpr std::uint32_t kNone = UINT32_MAX;
    std::vector<std::uint32_t> branch_of(g.gverts.size(), kNone);
    {
      using BranchKey = std::tuple<LoopKey, long long>;
      std::vector<BranchKey> branch_key(g.gverts.size());
      for (const auto& l : links) {
        if (!(l.to & kMaNodeFlag) || (l.from & kMaNodeFlag)) continue;
        const MaCutVert& mc = g.macuts[l.to & ~kMaNodeFlag];
        if (!mc.branch) continue;
        const Vec3 at = part.patches[mc.patch.index()].frame.to_3d(mc.point.position);
        const BranchKey k{place[l.from], quantum(distance(at, g.gverts[l.from].position))};
        const std::size_t set = uf.find(l.from);
        if (branch_of[set] == kNone || k < branch_key[set]) {
          branch_of[set] = l.to;
          branch_key[set] = k;
        }
      }
    }
    std::vector<std::pair<long long, std::size_t>> order;
    for (std::size_t corridor = 0; corridor < corridors; ++corridor) {
      const double w = width[corridor];
      if (quantum(w) < quantum(narrow_fraction * track_width(radius[corridor])))
        order.push_back({quantum(w), corridor});
    }
    std::sort(order.begin(), order.end());
    std::vector<std::pair<double, std::size_t>> narrow;
    for (const auto& [q, corridor] : order) narrow.push_back({width[corridor], corridor});
    // Patches per rail set; the corridors each rail set bounds (ascending).
    std::vector<std::vector<std::uint32_t>> set_patches(g.gverts.size());
    for (const auto& l : links)
      for (std::uint32_t end : {l.from, l.to})
        if (!(end & kMaNodeFlag)) set_patches[uf.find(end)].push_back(l.patch.value);
    for (auto& sp : set_patches) sort_unique(sp);
    std::vector<std::vector<std::size_t>> corridors_of_set(g.gverts.size());
    for (std::size_t corridor = 0; corridor < corridors; ++corridor)
      for (std::uint32_t b : bounds[corridor]) corridors_of_set[uf.find(b)].push_back(corridor);
    for (auto& cs : corridors_of_set) sort_unique(cs);
    // What each deletion of the round (made, or waiting for the next round) claims: its region
    // and the patches beside it, the corridors it merges and those beside them; by patch and by
    // corridor, the claims that hold it.
    std::vector<std::vector<std::uint32_t>> claims_at_patch(part.patches.size());
    std::vector<std::vector<std::uint32_t>> claims_at_corridor(corridors);
    std::uint32_t claim_count = 0;
    std::vector<std::uint32_t> seen(part.patches.size(), UINT32_MAX);  // claim marking a patch
    std::vector<std::uint32_t> seen_corridor(corridors, UINT32_MAX);
    std::vector<char> meets;  // per claim: meets this deletion's region (by patches)
    bool removed = false;
    kept = 0;
    for (const auto& [w, corridor] : narrow) {
      if (small_feature[corridor]) {
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
        if (sources_of[set].empty()) continue;
        const std::uint32_t unit =
            branch_of[set] != kNone ? branch_of[set] : static_cast<std::uint32_t>(set);
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
        if (holds_last_ray(srcs, g, rays_at_vertex)) continue;
        const LoopKey unit_key = first_place(srcs, place);
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
      std::vector<std::uint32_t> region = corridor_patches[corridor];
      for (std::uint32_t src : best) {
        const auto& sp = set_patches[uf.find(src)];
        region.insert(region.end(), sp.begin(), sp.end());
      }
      sort_unique(region);
      // The corridors it merges: this one and those across the deleted rails.
      std::vector<std::size_t> touched{corridor};
      for (std::size_t set : best_sets)
        touched.insert(touched.end(), corridors_of_set[set].begin(), corridors_of_set[set].end());
      sort_unique(touched);
      // Far from every claim of the round by patches or by corridors: no claim meets both its
      // region (by patches) and the corridors it merges (by corridors).
      meets.assign(claim_count, 0);
      for (std::uint32_t p : region)
        for (std::uint32_t c : claims_at_patch[p]) meets[c] = 1;
      bool waits = one_per_round && removed;
      for (std::size_t k : touched)
        for (std::uint32_t c : claims_at_corridor[k]) waits = waits || meets[c];
      // Its claim, recorded once per patch and per corridor it holds.
      const std::uint32_t claim = claim_count++;
      const auto hold = [&](std::vector<std::uint32_t>& seen_by, auto& lists, std::size_t k) {
        if (seen_by[k] == claim) return;
        seen_by[k] = claim;
        lists[k].push_back(claim);
      };
      for (std::uint32_t p : region) {
        hold(seen, claims_at_patch, p);
        for (std::uint32_t q : neighbours[p]) hold(seen, claims_at_patch, q);
      }
      for (std::size_t c : touched) {
        hold(seen_corridor, claims_at_corridor, c);
        for (std::uint32_t b : bounds[c])
          for (std::size_t k : corridors_of_set[uf.find(b)])
            hold(seen_corridor, claims_at_corridor, k);
      }
      if (waits) continue;  // a narrower corridor of the round is near: the next round
      for (std::uint32_t src : best) {
        const GCutVert& gv = g.gverts[src];
        suppressed.push_back(gv.position);
        DeletedRail d;
        d.at = gv.position;
        d.corridor_width = w;
        d.patch = patch_of[src];
        d.through_branch_point = via_branch[src];
        deleted.push_back(d);
      }
      for (std::uint32_t src : best)
        if (g.gverts[src].vertex) --rays_at_vertex[g.gverts[src].vertex->index()];
      removed = true;
    }
    if (!removed) {
      if (last) *last = std::move(laid);
      return;
    }
    ++rounds;
  }
}

}  // namespace laytracks::cutgraph_detail
