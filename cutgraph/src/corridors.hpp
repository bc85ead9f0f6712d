// Private: CUT-SEGs, corridors and where the track rails of uniform mode start.
#pragma once

#include <vector>

#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

using CutSeg = CorridorPiece;

struct Corridors {
  std::vector<CutSeg> segs;
  std::size_t count = 0;
};

/// The CUT-SEGs of every loop, grouped into corridors: two CUT-SEGs are in one corridor when
/// one maps onto the other across the medial axis, or when they share a B-Rep edge.
Corridors find_corridors(const Part& part,
                         const std::vector<MedialAxis>& axes,
                         const CutGraph& graph);

/// The CUT-SEGs with their corridors and the MA points at their ends (corridor_pieces()).
std::vector<CorridorPiece> corridor_pieces_impl(const Part& part,
                                                const std::vector<MedialAxis>& axes,
                                                const CutGraph& graph);

/// Where to start a track rail.
struct TrackSeed {
  PatchId patch;
  BoundaryPoint point;
};

/// Uniform mode (Eq. 1): in each corridor, round(L / w) tracks (at least one), L the length of
/// its longest CUT-SEG; the track rails start at equal spacing along that CUT-SEG.
std::vector<TrackSeed> track_seeds(const Part& part,
                                   const std::vector<MedialAxis>& axes,
                                   const CutGraph& graph,
                                   double width);

/// A CUT-SEG longer than this many widths once the corridors' tracks are laid is a gap: a
/// side that the longest CUT-SEG's rails do not reach (a corridor whose other side is a
/// concave corner's fan, or one that spans several CUT-SEGs).
constexpr double kGapWidths = 2.0;

/// Seeds that cut every gap (CUT-SEG longer than kGapWidths x w) into Eq. (1)'s tracks.
std::vector<TrackSeed> gap_seeds(const Part& part,
                                 const std::vector<MedialAxis>& axes,
                                 const CutGraph& graph,
                                 double width);

}  // namespace laytracks::cutgraph_detail
