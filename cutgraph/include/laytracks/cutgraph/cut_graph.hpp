// Rails across patches: G-CUT-VERTs, their per-patch images (CUT-VERTs), MA-CUT-VERTs, and the
// CUT-GRAPH that joins them (paper, section 4.1, Algorithm II).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks {

using GCutId = Id<struct GCutTag>;
using CutVertId = Id<struct CutVertTag>;
using MaCutId = Id<struct MaCutTag>;
using RailId = Id<struct RailTag>;

/// A point of the part on its B-Rep boundary: on edge `edge` at parameter t in [0, 1] from the
/// edge's vertex a to its vertex b, or at a B-Rep vertex (then t is 0 or 1 and `vertex` is set).
struct GCutVert {
  EdgeId edge;
  double t = 0.0;
  std::optional<VertexId> vertex;
  Vec3 position;
  bool source = false;  ///< a touching point of an MA branch point (a Source G-CUT-VERT)
};

/// Where a CUT-VERT sits on its patch's boundary: loop, segment (vertex i to i+1) and the
/// parameter s along it; `u = segment + s` orders CUT-VERTs along the loop.
struct LoopPoint {
  std::uint32_t loop = 0;
  std::uint32_t segment = 0;
  double s = 0.0;
  double u() const { return static_cast<double>(segment) + s; }
};

/// An image of a G-CUT-VERT on one patch.
struct CutVert {
  GCutId g;
  PatchId patch;
  LoopPoint at;
  Vec2 position;  ///< in the patch frame

  /// This point as a point of its segment of the loop (what the medial mapping takes).
  BoundaryPoint on_segment() const {
    return {{BoundarySite::Kind::Segment, at.loop, at.segment}, at.s, position};
  }
};

/// A point of a patch's medial axis where a rail meets it.
struct MaCutVert {
  PatchId patch;
  MaPoint point;
  std::optional<MaVertexId> vertex;  ///< set when the point is an MA vertex
  bool branch = false;               ///< the vertex is a branch point (degree >= 3)
  /// The vertex is an end of the axis inside the patch (degree 1, radius > 0): the centre of a
  /// polygonised convex arc, where the rails from the arc meet.
  bool round_end = false;
};

/// A rail segment: from a CUT-VERT to an MA-CUT-VERT of the same patch.
struct RailSegment {
  CutVertId cut;
  MaCutId ma;
  /// It closes a loop or a spiral on an existing point, so it is longer or shorter than the
  /// radius at its MA point and not along the two-way mapping (RailLayer).
  bool leans = false;
};

/// How a rail chain ends (see docs/cutgraph.md).
enum class RailEnd : std::uint8_t {
  Loop,           ///< it closes on itself
  FreeEdge,       ///< on an edge used by one patch only
  ConcaveVertex,  ///< at a reflex corner
  BranchPoint,    ///< at an MA branch point, where it forks
  Junction,       ///< on an edge shared by 3 or more patches, where it forks
  ConvexVertex,   ///< at a convex corner (a degenerate rail of length 0)
  RoundCorner,    ///< at the centre of a rounded convex corner (a polygonised arc)
  Lost,           ///< nowhere the geometry allows: a bug
};
const char* to_string(RailEnd end);

/// A rail chain: a maximal path of rail segments through points where exactly two meet.
struct RailChain {
  std::vector<GCutId> through;   ///< the boundary points it passes, in order
  std::vector<PatchId> patches;  ///< the patches it crosses, ascending, each once
  RailEnd start = RailEnd::Lost;
  RailEnd end = RailEnd::Lost;
  double closure_gap = 0.0;  ///< for loops: how far the last landing is from the first point
  bool source = false;       ///< starts at a branch point's touching point
};

/// A source rail deleted to remove a narrow corridor (paper 4.2.3): where its source point was,
/// and the corridor that was too narrow. The medial axis is never changed.
struct DeletedRail {
  Vec3 at;
  PatchId patch;
  double corridor_width = 0.0;
  bool through_branch_point = false;  ///< Table I cases 3 and 4: MA-CUT-VERTs merged
};

struct CutGraph {
  std::vector<GCutVert> gverts;
  std::vector<CutVert> cuts;
  std::vector<MaCutVert> macuts;
  std::vector<RailSegment> segments;
  std::vector<RailChain> chains;
  /// Largest distance between where a rail landed and the existing G-CUT-VERT it was
  /// identified with (a loop closing, or two rails meeting).
  double max_landing_gap = 0.0;
  /// Rails that crossed more shared edges than a closed chain needs (a spiral) and were ended
  /// on the nearest existing point of their landing edge (RailLayer, kMaxHopsPerPatch).
  std::size_t spiral_closures = 0;
  /// Rails that came back to a shared edge near their own chain's earlier crossing and were
  /// landed on it (RailLayer, kLoopCloseRel): loops round drafted walls.
  std::size_t loop_closures = 0;
  /// Rails that landed within kCoincideRel x their radius of another chain's point, on it.
  std::size_t rail_merges = 0;
  std::vector<std::string> problems;  ///< rails that ended where the geometry does not allow
  std::vector<DeletedRail> deleted;   ///< rails removed with narrow corridors
  /// Narrow corridors left alone: they pass a convex vertex (a small feature that needs its
  /// fine tracks) or their only rail ends at a concave vertex.
  std::size_t narrow_kept = 0;
  /// Rounds of narrow-corridor removal that deleted rails (each lays the source rails again).
  std::size_t narrow_rounds = 0;
  /// Source points not laid because their rail sets ran a fraction of a track beside rails
  /// kept before them across many patches (docs/cutgraph.md, "Crowded rails").
  std::size_t crowded_rails = 0;
  /// Track seeds not laid beside a rail that reached them across many shared edges (a track
  /// drifting round a band of thin triangles; docs/cutgraph.md, "Crowded rails").
  std::size_t crowded_seeds = 0;
  /// Per patch, per arc of the part (Part::arcs): the round hole its rails land on along rays
  /// from the centre (MedialAxis::choose_round_holes), as the index of its circle in the
  /// patch's Polygon2::circles; -1 for the other arcs.
  std::vector<std::vector<std::int32_t>> round_arcs;
  std::size_t corridor_count = 0;  ///< corridors between the source rails (after deletions)
  std::size_t track_count = 0;     ///< tracks, once the track rails are laid
};

class TrackWidthLaw;

struct CutGraphOptions {
  /// Track width for uniform mode. Rails are laid in every corridor at this spacing (Eq. 1);
  /// 0 lays only the source rails.
  double track_width = 0.0;
  /// Adaptive mode (Algorithm III): track widths from this law instead of track_width. The
  /// law must outlive the call.
  const TrackWidthLaw* adaptive = nullptr;
  /// A corridor whose longest CUT-SEG is shorter than this x the track width is narrow, and its
  /// rails are deleted until it is not (0 keeps every rail). In adaptive mode the width is the
  /// law's at the radius of the corridor's branch point.
  double narrow_fraction = 0.5;
  /// Delete for one narrow corridor per round instead of for every corridor of a round whose
  /// deletion no narrower one's can change (docs/cutgraph.md): the slow reference that the
  /// rounds must agree with, for tests.
  bool narrow_one_per_round = false;
  /// Leave out the crowded rail sets before the narrow corridors, and the crowded track seeds
  /// (docs/cutgraph.md, "Crowded rails"); false lays every source rail and seed, for the tests
  /// of what comes after on rails that crowd (a torus of quads' strips, a needle facet's twin
  /// rails).
  bool drop_crowded_rails = true;
  /// Lay the track rails (false: stop after removing narrow corridors, to look at corridors).
  bool lay_tracks = true;
};

/// Lays the rails: from the touching points of every MA branch point (Source G-CUT-VERTs),
/// breadth first across patches through shared edges (Algorithm II); then, if a track width
/// is given, removes narrow corridors by deleting source rails and lays the track rails of
/// every corridor. `axes[p]` is the medial axis of patch p.
CutGraph build_cut_graph(const Part& part,
                         const std::vector<MedialAxis>& axes,
                         const CutGraphOptions& options = {});

/// A CUT-SEG: the piece of a loop between two consecutive rails or corners, u from u0 to u1
/// (u = segment + s; u1 may pass the loop's segment count when the piece wraps round its
/// start), and the corridor it belongs to. `ma0` and `ma1` are where the rails at its two ends
/// meet the medial axis (the corner itself at a corner).
struct CorridorPiece {
  PatchId patch;
  std::uint32_t loop = 0;
  double u0 = 0.0;
  double u1 = 0.0;
  double length = 0.0;
  std::size_t corridor = 0;
  Vec2 ma0;
  Vec2 ma1;
};

/// The CUT-SEGs of every loop and their corridors: two CUT-SEGs are in one corridor when one
/// maps onto the other across the medial axis, or when they share a B-Rep edge.
std::vector<CorridorPiece> corridor_pieces(const Part& part,
                                           const std::vector<MedialAxis>& axes,
                                           const CutGraph& graph);

/// The validator: no two rails cross inside a patch; every CUT-VERT on a shared edge has an
/// image in every patch of that edge at the same 3D point; every MA-CUT-VERT lies on its axis.
/// Returns the problems found, each a sentence; empty when valid.
std::vector<std::string> validate_cut_graph(const Part& part,
                                            const std::vector<MedialAxis>& axes,
                                            const CutGraph& graph);

}  // namespace laytracks
