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

/// How wide the tracks are: `width` in uniform mode (Eq. 1), or the width law of adaptive
/// mode (Algorithm III) when `law` is set.
struct TrackSpacing {
  double width = 0.0;
  const TrackWidthLaw* law = nullptr;
};

/// In each corridor, the track rails along its longest CUT-SEG: uniform, round(L / w) tracks
/// (at least one) at equal spacing, L its length; adaptive, Algorithm III's march.
std::vector<TrackSeed> track_seeds(const Part& part,
                                   const std::vector<MedialAxis>& axes,
                                   const CutGraph& graph,
                                   const TrackSpacing& spacing);

/// A CUT-SEG longer than this many widths once the corridors' tracks are laid is a gap: a
/// side that the longest CUT-SEG's rails do not reach (a corridor whose other side is a
/// concave corner's fan, or one that spans several CUT-SEGs).
constexpr double kGapWidths = 2.0;

/// Seeds that cut every gap (CUT-SEG longer than kGapWidths x its width) into tracks, as
/// track_seeds cuts a corridor's longest CUT-SEG.
std::vector<TrackSeed> gap_seeds(const Part& part,
                                 const std::vector<MedialAxis>& axes,
                                 const CutGraph& graph,
                                 const TrackSpacing& spacing);

/// Algorithm III, Step 3: below this ratio of the length left to the two end widths the rest
/// is one track; up to kManyCutsRatio it is two, split in the ratio of the end widths.
constexpr double kOneCutRatio = 0.7;
constexpr double kManyCutsRatio = 1.3;

/// Algorithm III along a CUT-SEG of this length, `width(x)` the track width Delta S at arc
/// length x: where its CUT-VERTs go, ascending. Tracks are laid from both ends, the narrower
/// end first, until the ratio rule of Step 3 ends it (docs/adaptive.md).
std::vector<double> march_tracks(double length, const std::function<double(double)>& width);

}  // namespace laytracks::cutgraph_detail
