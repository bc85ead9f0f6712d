// Private: the match template's triangles and their pairing (docs/mesher.md, "Matched
// triangles"). Plain 2D geometry on a polygon; the caller poses it in the face's LocalFrame.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::mesher_detail {

/// A triangulation of a polygon with inner points, and a set of its inner edges that gives
/// every triangle one or three ("marks"): mostly one (the triangles paired into quads), three
/// only on the paths that join the triangles no pairing reached. Node i < polygon.size() is
/// polygon node i, node i >= it is inner[i - polygon.size()].
struct MarkedTriangles {
  std::vector<Vec2> inner;
  std::vector<std::array<std::uint32_t, 3>> triangles;         ///< counter-clockwise
  std::vector<std::pair<std::uint32_t, std::uint32_t>> marks;  ///< (smaller, larger) node
  std::size_t unpaired = 0;  ///< triangles the matching left, joined by paths
};

/// The simple counter-clockwise polygon (an even node count) triangulated with inner points
/// graded from its edge lengths (Delaunay refinement, then smoothed), and its triangles paired
/// (matched) into quads: best quads first, completed by augmenting paths (Edmonds) to a
/// maximum matching over the pairs that make valid quads; the triangles left are joined in
/// pairs by the cheapest paths across inner edges (fewest triangles left with three marks,
/// fewest poor pairs), whose edges toggle their marks. Of the gradings tried, the first that
/// pairs every triangle, else the one that leaves the fewest. Nothing when there is no
/// triangulation or it would need too many points.
std::optional<MarkedTriangles> matched_triangles(const std::vector<Vec2>& polygon);

}  // namespace laytracks::mesher_detail
