#include "sites.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace laytracks::medial_detail {

Vec2 inward_normal(const Polygon2& poly, const BoundarySite& segment) {
  const Vec2 d =
      seg_end(poly, segment.loop, segment.index) - seg_start(poly, segment.loop, segment.index);
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

namespace {

/// Largest minus smallest distance from x to the sites in [first, last).
template <typename It>
double spread_of(const Polygon2& poly, It first, It last, Vec2 x) {
  double lo = INFINITY;
  double hi = -INFINITY;
  for (It s = first; s != last; ++s) {
    const double d = site_distance(poly, *s, x);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return hi - lo;
}

}  // namespace

double distance_spread(const Polygon2& poly, const std::vector<BoundarySite>& sites, Vec2 x) {
  return spread_of(poly, sites.begin(), sites.end(), x);
}

double distance_spread(const Polygon2& poly, const std::array<BoundarySite, 3>& sites, Vec2 x) {
  return spread_of(poly, sites.begin(), sites.end(), x);
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

namespace {

/// Roots of a s^2 + b s + c = 0 (one root when a is negligible). With `length` > 0, s is a
/// length of about that size, and a, b, c are of dimension 1, length and length^2: whether a
/// is negligible is decided on a s^2, b s and c at s = length, the same at every scale. (Compared
/// as they are, a = 2e-16 from two nearly parallel sides counted at a part's size 1e-3 and not
/// at 1: the second root, 1e12 away, became a Voronoi vertex of fuzz seed 74074's bent_023
/// mirrored and scaled, and its axis failed its self-check.)
std::vector<double> quadratic_roots(double a, double b, double c, double length = 0.0) {
  std::vector<double> out;
  const bool sized = length > 0.0 && std::isfinite(length);
  const double a_s = sized ? std::fabs(a) * length * length : std::fabs(a);
  const double b_s = sized ? std::fabs(b) * length : std::fabs(b);
  const double scale = std::max({a_s, b_s, std::fabs(c)});
  if (scale == 0.0) return out;
  if (a_s <= 1e-14 * scale) {
    if (b != 0.0) out.push_back(-c / b);
    return out;
  }
  double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) {
    if (disc < -1e-12 * b * b) return out;
    disc = 0.0;
  }
  // Numerically stable form.
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  out.push_back(q / a);
  if (q != 0.0) out.push_back(c / q);
  return out;
}

/// Centres of the circles touching the three constraints, in closed form (up to two).
std::vector<Vec2> closed_form_centres(const std::array<Constraint, 3>& cs) {
  std::array<Constraint, 3> c = cs;
  // Points first, then lines.
  std::stable_sort(c.begin(), c.end(), [](const Constraint& a, const Constraint& b) {
    return !a.is_line && b.is_line;
  });
  const int points = static_cast<int>(!c[0].is_line) + !c[1].is_line + !c[2].is_line;
  std::vector<Vec2> out;
  if (points == 3) {  // circumcentre
    const Vec2 b = c[1].a - c[0].a;
    const Vec2 d = c[2].a - c[0].a;
    const double den = 2.0 * cross(b, d);
    if (den == 0.0) return out;
    const double bb = dot(b, b);
    const double dd = dot(d, d);
    out.push_back(c[0].a + Vec2{(d.y * bb - b.y * dd) / den, (b.x * dd - d.x * bb) / den});
    return out;
  }
  if (points == 0) {  // three lines: n_i . x - r = n_i . a_i
    const double m[3][3] = {
        {c[0].n.x, c[0].n.y, -1.0}, {c[1].n.x, c[1].n.y, -1.0}, {c[2].n.x, c[2].n.y, -1.0}};
    const double rhs[3] = {dot(c[0].n, c[0].a), dot(c[1].n, c[1].a), dot(c[2].n, c[2].a)};
    auto det3 = [](const double a[3][3]) {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double det = det3(m);
    if (std::fabs(det) < 1e-15) return out;
    double sol[2];
    for (int k = 0; k < 2; ++k) {
      double mk[3][3];
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) mk[i][j] = j == k ? rhs[i] : m[i][j];
      }
      sol[k] = det3(mk) / det;
    }
    out.push_back({sol[0], sol[1]});
    return out;
  }
  // One or two points: the centre moves on a line x0 + s t, and r(s) is known along it.
  Vec2 x0;
  Vec2 t;
  double r0 = 0.0;
  double r1 = 0.0;  // r(s) = r0 + r1 s for the line constraint used
  const Constraint* line = nullptr;
  const Constraint& p = c[0];
  if (points == 2) {  // on the perpendicular bisector of the two points
    x0 = lerp(c[0].a, c[1].a, 0.5);
    const Vec2 d = c[1].a - c[0].a;
    const double len = norm(d);
    if (len == 0.0) return out;
    t = perp((1.0 / len) * d);
    line = &c[2];
  } else {  // on the bisector of the two lines: (n1 - n2) . x = n1 . a1 - n2 . a2
    const Vec2 g = c[1].n - c[2].n;
    const double gg = dot(g, g);
    if (gg < 1e-24) return out;
    const double rhs = dot(c[1].n, c[1].a) - dot(c[2].n, c[2].a);
    x0 = (rhs / gg) * g;
    t = (1.0 / std::sqrt(gg)) * perp(g);
    line = &c[1];
  }
  r0 = dot(x0 - line->a, line->n);
  r1 = dot(t, line->n);
  // |x0 + s t - p|^2 = (r0 + r1 s)^2
  const Vec2 w = x0 - p.a;
  const double qa = 1.0 - r1 * r1;
  const double qb = 2.0 * (dot(w, t) - r0 * r1);
  const double qc = dot(w, w) - r0 * r0;
  for (double s : quadratic_roots(qa, qb, qc, std::max(norm(w), std::fabs(r0))))
    out.push_back(x0 + s * t);
  return out;
}

/// Heights h at which x = p + h m, whose signed distance to two lines through p is h c0 (m the
/// unit bisector of their inward normals), is as far from constraint c; none when degenerate.
std::vector<double> bisector_heights(Vec2 p, Vec2 m, double c0, const Constraint& c) {
  if (c.is_line) {
    const double denom = c0 - dot(m, c.n);
    if (!(std::fabs(denom) > 1e-15)) return {};
    return {dot(p - c.a, c.n) / denom};
  }
  // |p + h m - c.a|^2 = (h c0)^2
  const Vec2 w = p - c.a;
  return quadratic_roots(1.0 - c0 * c0, 2.0 * dot(w, m), dot(w, w), norm(w));
}

/// The point where the circle centred at x touches a constraint.
Vec2 touch(const Constraint& c, Vec2 x) { return c.is_line ? x - dot(x - c.a, c.n) * c.n : c.a; }

}  // namespace

Vec2 refine_vertex(const Polygon2& poly,
                   const std::vector<BoundarySite>& all_sites,
                   Vec2 approx,
                   Vec2 centre,
                   double size) {
  if (all_sites.size() < 3) return approx;
  // The first three sites pin the disk down; the others (cocircular) only repeat it.
  const std::array<BoundarySite, 3> sites = {all_sites[0], all_sites[1], all_sites[2]};
  // A corner with both its segments: the vertex is the corner itself (radius 0).
  for (const auto& c : sites) {
    if (c.kind != BoundarySite::Kind::Corner) continue;
    int adjacent = 0;
    for (const auto& s : sites) adjacent += is_endpoint_of(poly, c, s) ? 1 : 0;
    if (adjacent == 2) return poly.loops[c.loop][c.index];
  }
  const std::array<Constraint, 3> cs = {
      constraint_of(poly, sites[0]), constraint_of(poly, sites[1]), constraint_of(poly, sites[2])};
  std::vector<Vec2> candidates;
  // A segment with one of its own end points: the vertex lies on the segment's normal at that
  // end point, at the height where the disk touches the third site. Two segments meeting end
  // to end (not folding back): it lies on the bisector of their lines through the joint. (The
  // general formulas are singular for collinear segments, and for nearly collinear ones they
  // lose the bisector's direction: the vertex drifts sideways by about 1e-16 / the turn angle.)
  bool reduced = false;
  const auto reduce_at = [&](Vec2 a, const BoundarySite& segment, const Constraint& third) {
    const Vec2 n = inward_normal(poly, segment);
    const double h = ray_height(a, n, third);
    if (std::isfinite(h) && h >= 0.0) candidates.push_back(a + h * n);
    reduced = true;
  };
  for (std::size_t i = 0; i < 3 && !reduced; ++i) {
    for (std::size_t j = 0; j < 3 && !reduced; ++j) {
      if (is_endpoint_of(poly, sites[i], sites[j])) {
        reduce_at(poly.loops[sites[i].loop][sites[i].index], sites[j], cs[3 - i - j]);
      }
    }
  }
  // The adjacent pair with the smallest turn, if under 60 degrees (beyond, the general formulas
  // are well-conditioned). The smallest, not the first found: with a square corner as the pair,
  // a third segment nearly parallel to one of its sides makes the height ill-conditioned.
  std::size_t pi = 3;
  std::size_t pj = 3;
  double best_cos = 0.5;
  Vec2 joint;
  for (std::size_t i = 0; i < 3 && !reduced; ++i) {
    for (std::size_t j = i + 1; j < 3 && !reduced; ++j) {
      const BoundarySite& a = sites[i];
      const BoundarySite& b = sites[j];
      if (a.kind != BoundarySite::Kind::Segment || b.kind != BoundarySite::Kind::Segment ||
          a.loop != b.loop) {
        continue;
      }
      const std::size_t n = poly.loops[a.loop].size();
      const bool b_follows = (a.index + 1) % n == b.index;
      const bool a_follows = (b.index + 1) % n == a.index;
      if (!a_follows && !b_follows) continue;
      const double c = dot(inward_normal(poly, a), inward_normal(poly, b));
      if (c <= best_cos) continue;
      best_cos = c;
      pi = i;
      pj = j;
      joint = b_follows ? seg_start(poly, b.loop, b.index) : seg_start(poly, a.loop, a.index);
    }
  }
  if (!reduced && pi < 3) {
    const Vec2 na = inward_normal(poly, sites[pi]);
    const Vec2 sum = na + inward_normal(poly, sites[pj]);
    const Vec2 m = (1.0 / norm(sum)) * sum;
    for (double h : bisector_heights(joint, m, dot(m, na), cs[3 - pi - pj])) {
      if (std::isfinite(h)) candidates.push_back(joint + h * m);
    }
    reduced = true;
  }
  if (!reduced) {
    candidates = closed_form_centres(cs);
    candidates.push_back(newton(cs, approx));
  }
  // Candidates must be about as consistent as the approximation (spreads below 1e-12 x size
  // count as equal: far from the polygon, CGAL's point can be 1e30 away with a spread of 0).
  // The sites of a Delaunay face are counter-clockwise, and so are their touching points on
  // the Voronoi circle: that picks the right one of two roots. Then the point nearest to the
  // approximation wins, or the smaller circle when the approximation is far off.
  double approx_spread = distance_spread(poly, sites, approx);
  const bool approx_usable = approx_spread >= 0.0 && std::isfinite(approx.x) &&
                             std::isfinite(approx.y) && norm(approx - centre) <= 4.0 * size;
  if (!approx_usable) approx_spread = INFINITY;
  const double accept = std::max(approx_spread, 1e-12 * size);
  Vec2 best = approx;
  bool found = false;
  bool best_ccw = false;
  double best_key = INFINITY;
  for (Vec2 x : candidates) {
    if (!std::isfinite(x.x) || !std::isfinite(x.y)) continue;
    if (!reduced) x = newton(cs, x);  // polish
    const double spread = distance_spread(poly, sites, x);
    if (!std::isfinite(spread) || spread > accept) continue;
    const Vec2 t0 = touch(cs[0], x);
    const bool ccw = cross(touch(cs[1], x) - t0, touch(cs[2], x) - t0) > 0.0;
    const double key = approx_usable ? distance(x, approx) : site_distance(poly, sites[0], x);
    if (!found || (ccw && !best_ccw) || (ccw == best_ccw && key < best_key)) {
      best = x;
      best_ccw = ccw;
      best_key = key;
      found = true;
    }
  }
  return best;
}

}  // namespace laytracks::medial_detail
