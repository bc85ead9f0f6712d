// Rules 6-7 of build_part(), after the exact loop checks: holes turned clockwise, smooth corners,
// and the final Patch::loops, Patch::polygon and Patch::area.
#include <algorithm>
#include <cmath>

#include "build_state.hpp"
#include "describe.hpp"
#include "predicates.hpp"

namespace laytracks::detail {
namespace {

/// Exact orientation of a simple loop: the turn at its lowest (then leftmost) vertex, which is
/// convex. +1 counter-clockwise, -1 clockwise.
int loop_orientation(const std::vector<Vec2>& loop) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < loop.size(); ++i) {
    if (loop[i].y < loop[k].y || (loop[i].y == loop[k].y && loop[i].x < loop[k].x)) k = i;
  }
  const std::size_t m = loop.size();
  return orientation(loop[(k + m - 1) % m], loop[k], loop[(k + 1) % m]);
}

/// Reverses a loop in place, keeping its first element first.
template <class T>
void reverse_loop(std::vector<T>& v) {
  std::reverse(v.begin() + 1, v.end());
}

/// Reverses a chain: vertices keep their first; segment j becomes old segment m-1-j, turned.
void reverse_chain(Chain& c) {
  reverse_loop(c.vertices);
  std::reverse(c.seg_arc.begin(), c.seg_arc.end());
  std::reverse(c.seg_forward.begin(), c.seg_forward.end());
  for (char& f : c.seg_forward) f = f ? 0 : 1;
}

/// Unit tangent of segment j of the chain at its point `at`, in the chain's direction: the
/// circle's tangent for a piece of an arc, the segment's direction otherwise.
Vec3 tangent(const BuildState& s, const Chain& c, std::size_t j, Vec3 at) {
  const std::size_t m = c.vertices.size();
  if (c.seg_arc[j] < 0) {
    return normalized(s.part.vertices[c.vertices[(j + 1) % m].index()].position -
                      s.part.vertices[c.vertices[j].index()].position);
  }
  const ArcInfo& arc = s.arcs[static_cast<std::size_t>(c.seg_arc[j])];
  const Vec3 t = normalized(cross(arc.axis, at - arc.center));
  return c.seg_forward[j] ? t : -t;
}

/// smooth[i]: vertex i is an arc point, or the boundary turns there by less than kSmoothAngle.
std::vector<bool> smooth_flags(const BuildState& s, const Chain& c) {
  const std::size_t m = c.vertices.size();
  std::vector<bool> smooth(m, false);
  for (std::size_t i = 0; i < m; ++i) {
    const BrepVertex& v = s.part.vertices[c.vertices[i].index()];
    if (v.from_arc) {
      smooth[i] = true;
      continue;
    }
    const Vec3 in = tangent(s, c, (i + m - 1) % m, v.position);
    const Vec3 out = tangent(s, c, i, v.position);
    smooth[i] = std::atan2(norm(cross(in, out)), dot(in, out)) < Tolerances::kSmoothAngle;
  }
  return smooth;
}

/// Patch p's Polygon2::circles and circle, from its chains (already oriented). Arcs whose centres
/// and radii agree within Tolerances::kOnEdge x the part size (a hole given as four quarter
/// arcs) share a circle, so the medial mapping runs on across their joints.
void fill_circles(BuildState& s, std::size_t p) {
  Patch& patch = s.part.patches[p];
  Polygon2& poly = patch.polygon;
  poly.circles.clear();
  poly.circle.assign(s.chains[p].size(), {});
  const double tol = Tolerances::kOnEdge * s.part.size;
  std::vector<Vec3> centres;  // of poly.circles, in 3D
  for (std::size_t l = 0; l < s.chains[p].size(); ++l) {
    for (const std::int64_t a : s.chains[p][l].seg_arc) {
      if (a < 0) {
        poly.circle[l].push_back(-1);
        continue;
      }
      const ArcInfo& arc = s.arcs[static_cast<std::size_t>(a)];
      std::size_t k = 0;
      while (k < centres.size() && !(distance(centres[k], arc.center) <= tol &&
                                     std::abs(poly.circles[k].radius - arc.radius) <= tol))
        ++k;
      if (k == centres.size()) {
        centres.push_back(arc.center);
        poly.circles.push_back({patch.frame.to_2d(arc.center), arc.radius});
      }
      poly.circle[l].push_back(static_cast<std::int32_t>(k));
    }
  }
}

/// Orients patch p's loops (outer CCW, holes CW) and fills its loops, polygon and area.
void shape_patch(BuildState& s, std::size_t p) {
  Patch& patch = s.part.patches[p];
  auto& loops = s.loops2d[p];
  patch.loops.assign(loops.size(), {});
  patch.area = 0.0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const int wanted = l == 0 ? 1 : -1;
    if (loop_orientation(loops[l]) != wanted) {
      if (l == 0) {
        fail(patch_name(s, p) + " is degenerate: its outer loop does not turn with its normal");
      }
      reverse_loop(loops[l]);
      reverse_chain(s.chains[p][l]);
      patch.loops[l].reversed = true;
    }
    patch.loops[l].vertices = s.chains[p][l].vertices;
    patch.loops[l].smooth = smooth_flags(s, s.chains[p][l]);
    patch.area += 0.5 * twice_signed_area(loops[l]);
  }
  patch.polygon.loops = loops;
  patch.polygon.smooth.clear();
  for (const Loop& loop : patch.loops) patch.polygon.smooth.push_back(loop.smooth);
  fill_circles(s, p);
}

}  // namespace

void shape_polygons(BuildState& s) {
  for (std::size_t p = 0; p < s.part.patches.size(); ++p) shape_patch(s, p);
}

}  // namespace laytracks::detail
