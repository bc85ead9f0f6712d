#include "sites.hpp"

#include <algorithm>
#include <cmath>

namespace laytracks::medial_detail {

Vec2 inward_normal(const Polygon2& poly, const BoundarySite& segment) {
  const Vec2 d = seg_end(poly, segment.loop, segment.index) - seg_start(poly, segment.loop, segment.index);
  const double n = norm(d);
  return (1.0 / n) * perp(d);
}

Vec2 site_foot(const Polygon2& poly, const BoundarySite& site, Vec2 x, double* s) {
  if (site.kind == BoundarySite::Kind::Corner) {
    if (s) *s = 0.0;
    return poly.loops[site.loop][site.index];
  }
  const Vec2 a = seg_start(poly, site.loop, site.index);
  const Vec2 b = seg_end(poly, site.loop, site.index);
  const Vec2 d = b - a;
  const double t = std::clamp(dot(x - a, d) / dot(d, d), 0.0, 1.0);
  if (s) *s = t;
  return lerp(a, b, t);
}

double site_distance(const Polygon2& poly, const BoundarySite& site, Vec2 x) {
  return distance(x, site_foot(poly, site, x));
}

bool is_endpoint_of(const Polygon2& poly, const BoundarySite& corner, const BoundarySite& segment) {
  if (corner.kind != BoundarySite::Kind::Corner || segment.kind != BoundarySite::Kind::Segment ||
      corner.loop != segment.loop) {
    return false;
  }
  const std::size_t n = poly.loops[corner.loop].size();
  return corner.index == segment.index || corner.index == (segment.index + 1) % n;
}

double distance_spread(const Polygon2& poly, const std::array<BoundarySite, 3>& sites, Vec2 x) {
  double lo = INFINITY;
  double hi = -INFINITY;
  for (const auto& s : sites) {
    const double d = site_distance(poly, s, x);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return hi - lo;
}

namespace {

/// A distance constraint "dist(x, site) = r" in a differentiable form: for a segment, the signed
/// distance to its supporting line (positive inside); for a corner, the distance to the point.
struct Constraint {
  bool is_line = false;
  Vec2 a;  ///< a point of the line, or the corner
  Vec2 n;  ///< unit inward normal (lines only)
};

Constraint constraint_of(const Polygon2& poly, const BoundarySite& s) {
  Constraint c;
  if (s.kind == BoundarySite::Kind::Segment) {
    c.is_line = true;
    c.a = seg_start(poly, s.loop, s.index);
    c.n = inward_normal(poly, s);
  } else {
    c.a = poly.loops[s.loop][s.index];
  }
  return c;
}

/// Height h > 0 along the ray a + h n at which the disk of radius h touches constraint c, or NaN.
double ray_height(Vec2 a, Vec2 n, const Constraint& c) {
  if (c.is_line) {
    const double denom = 1.0 - dot(n, c.n);
    return denom > 1e-15 ? dot(a - c.a, c.n) / denom : NAN;
  }
  const Vec2 d = c.a - a;
  const double denom = 2.0 * dot(d, n);
  return denom > 0.0 ? dot(d, d) / denom : NAN;
}

/// Newton's method on f_i(x) = r for three constraints, from x0. Returns x0 on failure.
Vec2 newton(const std::array<Constraint, 3>& cs, Vec2 x0) {
  Vec2 x = x0;
  double r = 0.0;
  for (const auto& c : cs) r += c.is_line ? dot(x - c.a, c.n) : distance(x, c.a);
  r /= 3.0;
  for (int iter = 0; iter < 8; ++iter) {
    double J[3][3];
    double F[3];
    for (int i = 0; i < 3; ++i) {
      const Constraint& c = cs[static_cast<std::size_t>(i)];
      if (c.is_line) {
        F[i] = dot(x - c.a, c.n) - r;
        J[i][0] = c.n.x;
        J[i][1] = c.n.y;
      } else {
        const double d = distance(x, c.a);
        if (d == 0.0) return x0;
        F[i] = d - r;
        J[i][0] = (x.x - c.a.x) / d;
        J[i][1] = (x.y - c.a.y) / d;
      }
      J[i][2] = -1.0;
    }
    // Solve J dx = -F by Cramer's rule (3x3).
    const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                       J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                       J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
    if (!(std::fabs(det) > 1e-14)) return x0;
    double sol[3];
    for (int k = 0; k < 3; ++k) {
      double M[3][3];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) M[i][j] = (j == k) ? -F[i] : J[i][j];
      }
      sol[k] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
               det;
    }
    x = {x.x + sol[0], x.y + sol[1]};
    r += sol[2];
    if (std::fabs(sol[0]) + std::fabs(sol[1]) <= 1e-17 * (std::fabs(x.x) + std::fabs(x.y))) break;
  }
  return std::isfinite(x.x) && std::isfinite(x.y) ? x : x0;
}

}  // namespace

Vec2 refine_vertex(const Polygon2& poly, const std::array<BoundarySite, 3>& sites, Vec2 approx) {
  // A corner with both its segments: the vertex is the corner itself (radius 0).
  for (const auto& c : sites) {
    if (c.kind != BoundarySite::Kind::Corner) continue;
    int adjacent = 0;
    for (const auto& s : sites) adjacent += is_endpoint_of(poly, c, s) ? 1 : 0;
    if (adjacent == 2) return poly.loops[c.loop][c.index];
  }
  Vec2 candidate = approx;
  // A segment with one of its own end points: the vertex lies on the segment's normal at that
  // end point, at the height where the disk touches the third site.
  bool reduced = false;
  for (std::size_t i = 0; i < 3 && !reduced; ++i) {
    for (std::size_t j = 0; j < 3 && !reduced; ++j) {
      if (!is_endpoint_of(poly, sites[i], sites[j])) continue;
      const std::size_t k = 3 - i - j;
      const Vec2 a = poly.loops[sites[i].loop][sites[i].index];
      const Vec2 n = inward_normal(poly, sites[j]);
      const double h = ray_height(a, n, constraint_of(poly, sites[k]));
      if (std::isfinite(h) && h >= 0.0) candidate = a + h * n;
      reduced = true;
    }
  }
  if (!reduced) {
    candidate = newton({constraint_of(poly, sites[0]), constraint_of(poly, sites[1]),
                        constraint_of(poly, sites[2])},
                       approx);
  }
  return distance_spread(poly, sites, candidate) < distance_spread(poly, sites, approx) ? candidate
                                                                                         : approx;
}

}  // namespace laytracks::medial_detail
