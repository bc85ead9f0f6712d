// Private: the constrained Delaunay triangulation of a polygon with points inside it (CGAL, in
// cdt.cpp only: nothing else in the mesher sees CGAL).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::mesher_detail {

/// The triangles inside the simple counter-clockwise polygon pts[0 .. loop - 1] of the
/// constrained Delaunay triangulation of all of `pts` (those from `loop` on lie strictly
/// inside it), counter-clockwise, as indices into `pts`; every polygon edge is an edge of one
/// triangle. Empty when that does not hold (the polygon crosses or touches itself, a point
/// lies on an edge): the caller then has no such triangulation. Exact predicates decide it, so
/// the same points give the same triangles; points in ties (four on a circle) are decided by
/// their order.
std::vector<std::array<std::uint32_t, 3>> constrained_triangulation(const std::vector<Vec2>& pts,
                                                                    std::uint32_t loop);

/// Delaunay refinement inside the simple counter-clockwise polygon `polygon` (match template,
/// docs/mesher.md "Matched triangles"): the polygon's edges are never split; the circumcentre
/// of an inside triangle whose circumradius exceeds kRefineRadius x size(centre) is added when
/// it lies inside, at least kRefineClear x size from every polygon edge and from the points
/// added before it in the same pass, until a pass adds none or `max_points` are added. Each
/// pass takes its candidates largest first (radius over size, then position), so the result
/// does not depend on CGAL's face order. Returns the added points (empty when the polygon has
/// no triangulation).
std::vector<Vec2> refinement_points(const std::vector<Vec2>& polygon,
                                    const std::function<double(Vec2)>& size,
                                    std::size_t max_points);

}  // namespace laytracks::mesher_detail
