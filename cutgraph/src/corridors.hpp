// Private: CUT-SEGs, corridors and where the track rails of uniform mode start.
#pragma once

#include <functional>
#include <vector>

#include "laytracks/cutgraph/adaptive.hpp"
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

/// Algorithm III, Step 3: below this ratio of the length left to the two end widths the rest
/// is one track; up to kManyCutsRatio it is two, split in the ratio of the end widths.
constexpr double kOneCutRatio = 0.7;
constexpr double kManyCutsRatio = 1.3;

/// Algorithm III along a CUT-SEG of this length, `width(x)` the track width Delta S at arc
/// length x: where its CUT-VERTs go, ascending. Tracks are laid from both ends, the narrower
/// end first, until the ratio rule of Step 3 ends it (docs/adaptive.md).
std::vector<double> march_tracks(double length, const std::function<double(double)>& width);

/// Adaptive mode: the seeds of Algorithm III along each corridor's longest CUT-SEG.
std::vector<TrackSeed> adaptive_track_seeds(const Part& part,
                                            const std::vector<MedialAxis>& axes,
                                            const CutGraph& graph,
                                            const TrackWidthLaw& law);

/// Adaptive mode: seeds for every CUT-SEG longer than kGapWidths x its end widths' mean.
std::vector<TrackSeed> adaptive_gap_seeds(const Part& part,
                                          const std::vector<MedialAxis>& axes,
                                          const CutGraph& graph,
                                          const TrackWidthLaw& law);

}  // namespace laytracks::cutgraph_detail
