// Private: the geometry of boundary sites (segments and corners of a Polygon2).
#pragma once

#include <array>
#include <vector>

#include "laytracks/brep/polygon.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks::medial_detail {

/// Voronoi vertices joined by an interior edge shorter than this x the polygon's diagonal are
/// one vertex: the diagram of cocircular sites (a square's centre) has zero-length edges.
constexpr double kMergeRel = 1e-9;

/// End points of segment `index` of loop `loop`.
inline Vec2 seg_start(const Polygon2& poly, std::uint32_t loop, std::uint32_t index) {
  return poly.loops[loop][index];
}
inline Vec2 seg_end(const Polygon2& poly, std::uint32_t loop, std::uint32_t index) {
  const auto& l = poly.loops[loop];
  return l[(index + 1) % l.size()];
}
/// Unit normal of a segment pointing into the region (to its left).
Vec2 inward_normal(const Polygon2& poly, const BoundarySite& segment);

/// The nearest point of a site to x; for a segment, also its parameter s in [0, 1].
Vec2 site_foot(const Polygon2& poly, const BoundarySite& site, Vec2 x, double* s = nullptr);
/// Euclidean distance from x to a site (to the closed segment, or to the corner).
double site_distance(const Polygon2& poly, const BoundarySite& site, Vec2 x);

/// True when corner site `corner` is an end point of segment site `segment`.
bool is_endpoint_of(const Polygon2& poly, const BoundarySite& corner, const BoundarySite& segment);

/// Recomputes the centre of the disk touching the sites of a Voronoi vertex from its first
/// three sites (a Delaunay face, counter-clockwise; at least three sites), from closed forms and
/// Newton's method, starting from an approximation (CGAL's inexact construction can be far off
/// where sites are nearly degenerate, even 1e30 away; Boost's is exact for the grid-rounded
/// corners). `centre` and `size` are the polygon's box centre and diagonal. Returns the
/// approximation when no candidate is at least as consistent.
Vec2 refine_vertex(const Polygon2& poly,
                   const std::vector<BoundarySite>& sites,
                   Vec2 approx,
                   Vec2 centre,
                   double size);

/// Largest minus smallest distance from x to the sites: 0 for an exact Voronoi vertex.
double distance_spread(const Polygon2& poly, const std::vector<BoundarySite>& sites, Vec2 x);
double distance_spread(const Polygon2& poly, const std::array<BoundarySite, 3>& sites, Vec2 x);

}  // namespace laytracks::medial_detail
