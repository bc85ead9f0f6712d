// Private: the segment Voronoi diagram of a polygon's boundary, as plain data. Two
// implementations give the same contract: voronoi_cgal.cpp (CGAL's Segment_Delaunay_graph_2,
// exact on the input doubles) and voronoi_boost.cpp (Boost.Polygon's sweep line, exact on the
// input rounded to a 32-bit grid). See docs/medial-backends.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/polygon.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks::medial_detail {

/// A Voronoi vertex: the centre of a disk touching three or more sites (approximate position).
struct VoronoiVertex {
  Vec2 position;
  /// Every site the disk touches, at least three, distinct. The first three are counter-
  /// clockwise around the disk (a Delaunay face) and pin the disk down: refine_vertex uses
  /// them alone. CGAL reports exactly three; Boost reports all the sites of a cocircular vertex,
  /// with a well-spread triple first.
  std::vector<BoundarySite> sites;
};

/// A bounded Voronoi edge between two Voronoi vertices. Walking from a to b, `left` is the site
/// on the left. Unbounded edges are not reported (they lie outside the polygon).
struct VoronoiEdge {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  BoundarySite left;
  BoundarySite right;
  /// True when the edge belongs to the medial axis: inside the polygon, and not the normal
  /// between a segment and its own end point. Decided combinatorially and exactly (see the
  /// implementations), never from the computed positions.
  bool medial = false;
};

struct VoronoiDiagram {
  std::vector<VoronoiVertex> vertices;
  std::vector<VoronoiEdge> edges;
  /// turn[l][i]: exact sign of the turn at corner i of loop l: +1 convex (left turn), -1 reflex,
  /// 0 straight. Exact on the coordinates the backend decided its topology on.
  std::vector<std::vector<std::int8_t>> turn;
};

/// The Voronoi diagram of the open segments and the corners of the polygon's loops, by the
/// chosen backend (VoronoiBackend::Boost falls back to CGAL where segment_voronoi_boost gives
/// up). Precondition: the loops are simple and do not touch (as build_part guarantees).
VoronoiDiagram segment_voronoi(const Polygon2& polygon, VoronoiBackend backend);

/// The CGAL backend: exact predicates on the input doubles.
VoronoiDiagram segment_voronoi_cgal(const Polygon2& polygon);

/// The Boost.Polygon backend: exact predicates on the corners rounded to a grid of +-2^30 units
/// over the polygon's box, with positions already refined (refine_vertex). Empty, with the
/// reason in *why, when the rounding changes the diagram beyond local repair (see the
/// implementation). Throws InternalError when two corners round to the same grid point.
std::optional<VoronoiDiagram> segment_voronoi_boost(const Polygon2& polygon, std::string* why);

/// Exact sign of the turn at every corner, on the input doubles (as VoronoiDiagram::turn).
std::vector<std::vector<std::int8_t>> exact_turns(const Polygon2& polygon);

}  // namespace laytracks::medial_detail
