// Private: CUT-SEGs, corridors and where the track rails of uniform mode start.
#pragma once

#include <vector>

#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

/// A piece of a loop between two consecutive rails or corners: u from u0 to u1 (u = segment +
/// s; u1 may exceed the loop's segment count when the piece wraps around its start).
struct CutSeg {
  PatchId patch;
  std::uint32_t loop = 0;
  double u0 = 0.0;
  double u1 = 0.0;
  double length = 0.0;  ///< along the boundary, in the part's units
  std::size_t corridor = 0;
};

struct Corridors {
  std::vector<CutSeg> segs;
  std::size_t count = 0;
};

/// The CUT-SEGs of every loop, grouped into corridors: two CUT-SEGs are in one corridor when
/// one maps onto the other across the medial axis, or when they share a B-Rep edge.
Corridors find_corridors(const Part& part, const std::vector<MedialAxis>& axes,
                         const CutGraph& graph);

/// Where to start a track rail.
struct TrackSeed {
  PatchId patch;
  BoundaryPoint point;
};

/// Uniform mode (Eq. 1): in each corridor, round(L / w) tracks (at least one), L the length of
/// its longest CUT-SEG; the track rails start at equal spacing along that CUT-SEG.
std::vector<TrackSeed> track_seeds(const Part& part, const std::vector<MedialAxis>& axes,
                                   const CutGraph& graph, double width);

}  // namespace laytracks::cutgraph_detail
