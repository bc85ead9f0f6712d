// Private: CUT-SEGs, corridors and where the track rails of uniform mode start.
#pragma once

#include <array>
#include <cstdint>
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

/// Where the points sampled on each CUT-SEG map to across the medial axis, kept from one
/// search for corridors to the next (the rounds of narrow-corridor removal, the tracks'
/// seeds): most CUT-SEGs are the same from one search to the next. The images are a function
/// of the CUT-SEG alone (patch, loop, ends), so kept ones are what mapping its points again
/// would give, to the bit. Per loop, the last search's CUT-SEGs in loop order, so that the
/// next search reads them in one sweep.
class OppositeCache {
 public:
  /// The fractions of a CUT-SEG's length at which its points are mapped.
  static constexpr std::array<double, 5> kAt = {0.5, 0.25, 0.75, 0.375, 0.625};
  struct Image {
    bool usable = false;  ///< false: through a branch point, or onto a corner (not used)
    std::uint32_t loop = 0;
    double u = 0.0;  ///< loop parameter of the image
    Vec2 position;
  };
  struct Seg {
    double u0 = 0.0, u1 = 0.0;
    std::array<Image, kAt.size()> images;
  };
  std::vector<std::vector<Seg>> loops;  ///< by loop, the patches' loops one after another
};

/// The CUT-SEGs of every loop, grouped into corridors: two CUT-SEGs are in one corridor when
/// one maps onto the other across the medial axis, or when they share a B-Rep edge. `cache`,
/// if given, keeps the mapped points for the next call.
Corridors find_corridors(const Part& part,
                         const std::vector<MedialAxis>& axes,
                         const CutGraph& graph,
                         OppositeCache* cache = nullptr);

/// The CUT-SEGs with their corridors and the MA points at their ends (corridor_pieces()).
std::vector<CorridorPiece> corridor_pieces_impl(const Part& part,
                                                const std::vector<MedialAxis>& axes,
                                                const CutGraph& graph,
                                                OppositeCache* cache = nullptr);

/// The same from corridors already found (find_corridors of `graph` as it is).
std::vector<CorridorPiece> corridor_pieces_of(const Part& part,
                                              const CutGraph& graph,
                                              Corridors corridors);

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
/// `corridors`: find_corridors of the graph as it is.
std::vector<TrackSeed> track_seeds(const Part& part,
                                   const Corridors& corridors,
                                   const TrackSpacing& spacing);

/// A CUT-SEG longer than this many widths once the corridors' tracks are laid is a gap: a
/// side that the longest CUT-SEG's rails do not reach (a corridor whose other side is a
/// concave corner's fan, or one that spans several CUT-SEGs).
constexpr double kGapWidths = 2.0;

/// Seeds that cut every gap (CUT-SEG longer than kGapWidths x its width) into tracks, as
/// track_seeds cuts a corridor's longest CUT-SEG (`corridors` as there).
std::vector<TrackSeed> gap_seeds(const Part& part,
                                 const Corridors& corridors,
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
