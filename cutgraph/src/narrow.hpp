// Private: removing narrow corridors by deleting source rails.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "corridors.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

class RailLayer;

/// The source rails as the last round of remove_narrow_corridors laid them (with every
/// deletion made), and their corridors: what laying them again would give.
struct LaidSources {
  std::unique_ptr<CutGraph> graph;
  std::unique_ptr<RailLayer> layer;  ///< lays into *graph
  Corridors corridors;
  LaidSources();
  LaidSources(LaidSources&&) noexcept;
  LaidSources& operator=(LaidSources&&) noexcept;
  ~LaidSources();
};

/// Lays the source rails with the points in `suppressed` left out, and finds their corridors
/// (unless `corridors` is false).
LaidSources lay_sources(const Part& part,
                        const std::vector<MedialAxis>& axes,
                        const std::function<double(double)>& track_width,
                        const std::vector<Vec3>& suppressed,
                        OppositeCache& cache,
                        bool corridors = true);

/// Deletes source rails, round by round (in each, for every narrow corridor whose deletion is
/// far from every narrower one's, by patches or by corridors; with `one_per_round`, for the
/// narrowest only: the reference the rounds must agree with; narrow.cpp), until no corridor
/// is narrower than `narrow_fraction` x `track_width(R)` (R: the longest rail bounding it, the radius at its
/// branch point) except small features (a corridor bounded by a convex corner) and corridors
/// whose only deletable rail is the last one at a concave vertex (counted in `kept`).
/// `suppressed` receives the positions of the deleted source points, `deleted` a record each,
/// `rounds` the count of rounds that deleted rails. With `drop_crowded`, the crowded rail sets
/// are left out before the first round's corridors are read (docs/cutgraph.md, "Crowded
/// rails"; their source points go to `suppressed` too), and `crowded` receives their count. `cache`
/// keeps the points mapped across the axis from round to round. `last`, when given, receives the
/// last round's rails.
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
                             LaidSources* last = nullptr);

}  // namespace laytracks::cutgraph_detail
