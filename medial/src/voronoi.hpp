// Private: the segment Voronoi diagram of a polygon's boundary, as plain data. The only
// implementation (voronoi_cgal.cpp) uses CGAL's Segment_Delaunay_graph_2; see docs/medial.md.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "laytracks/brep/polygon.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks::medial_detail {

/// A Voronoi vertex: the centre of a disk touching three sites (approximate position).
struct VoronoiVertex {
  Vec2 position;
  std::array<BoundarySite, 3> sites;
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
  /// implementation), never from the computed positions.
  bool medial = false;
};

struct VoronoiDiagram {
  std::vector<VoronoiVertex> vertices;
  std::vector<VoronoiEdge> edges;
  /// turn[l][i]: exact sign of the turn at corner i of loop l: +1 convex (left turn), -1 reflex,
  /// 0 straight.
  std::vector<std::vector<std::int8_t>> turn;
};

/// The Voronoi diagram of the open segments and the corners of the polygon's loops.
/// Precondition: the loops are simple and do not touch (as build_part guarantees).
VoronoiDiagram segment_voronoi(const Polygon2& polygon);

}  // namespace laytracks::medial_detail
