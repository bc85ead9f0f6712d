// Exact 2D predicates and box-overlap searches, implemented with CGAL (EPICK, box_intersection_d)
// in predicates.cpp, the only brep translation unit that includes CGAL headers.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::detail {

/// Exact orientation of (a, b, c): +1 counter-clockwise (c left of a->b), -1 clockwise, 0
/// collinear.
int orientation(Vec2 a, Vec2 b, Vec2 c);

/// Exact: given collinear p, q, r, true when q lies on the closed segment pr.
bool collinear_are_ordered(Vec2 p, Vec2 q, Vec2 r);

/// Exact: the closed segments ab and cd have at least one point in common.
bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

using IndexPairs = std::vector<std::pair<std::size_t, std::size_t>>;

/// Every pair (i, j), i < j, of closed boxes that overlap or touch. Order unspecified.
IndexPairs overlapping_boxes(const std::vector<Box2>& boxes);

/// Every pair (i in a, j in b) of closed boxes that overlap or touch. Order unspecified.
IndexPairs overlapping_boxes(const std::vector<Box2>& a, const std::vector<Box2>& b);

/// Every pair (i in a, j in b) of closed boxes that overlap or touch. Order unspecified.
IndexPairs overlapping_boxes(const std::vector<Box3>& a, const std::vector<Box3>& b);

}  // namespace laytracks::detail
