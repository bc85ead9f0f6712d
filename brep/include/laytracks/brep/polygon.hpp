// A patch's region in its own 2D frame: the input of the medial-axis stage.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks {

/// A circle of the plane: a discretised arc's, in a patch frame.
struct Circle2 {
  Vec2 centre;
  double radius = 0.0;
};

/// A polygon with holes. Loop 0 is the outer boundary, counter-clockwise; the others are holes,
/// clockwise, so the region is always on the left of every boundary segment. Loops are closed
/// implicitly (last vertex back to the first). Segment i of a loop runs from vertex i to i+1.
struct Polygon2 {
  std::vector<std::vector<Vec2>> loops;
  /// smooth[l][i] is true when the boundary is tangent-continuous at loops[l][i]: a vertex made
  /// by discretising an arc, or a joint whose two edges have the same tangent. The medial stage
  /// ignores the branches such corners would create.
  std::vector<std::vector<bool>> smooth;
  /// The circles of the arcs the loops discretise (arcs of one circle share one), and
  /// circle[l][i]: the circle segment i of loop l is a chord of, or -1 (a straight edge). Empty
  /// for a polygon not made from a part: every segment is then straight to the medial mapping.
  std::vector<Circle2> circles;
  std::vector<std::vector<std::int32_t>> circle;

  std::size_t segment_count() const {
    std::size_t n = 0;
    for (const auto& l : loops) n += l.size();
    return n;
  }
};

/// Twice the signed area of a closed loop (shoelace; > 0 for counter-clockwise).
double twice_signed_area(const std::vector<Vec2>& loop);

}  // namespace laytracks
