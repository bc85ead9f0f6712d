// The MedialAxis graph: evaluation of edges, the two-way mapping and the self-check.
#include "laytracks/medial/medial_axis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sites.hpp"

namespace laytracks {

using medial_detail::inward_normal;
using medial_detail::seg_end;
using medial_detail::seg_start;
using medial_detail::site_distance;
using medial_detail::site_foot;

namespace {

/// Points are "on" an edge, and radii agree, within this x the polygon's diagonal.
constexpr double kLocateRel = 1e-9;
/// Radii must equal the distance to the boundary within this x the polygon's diagonal.
constexpr double kRadiusRel = 1e-9;
/// validate() compares radii against a brute-force distance to every segment; above this many
/// vertex x segment pairs it checks an evenly spread subset of the vertices.
constexpr double kBruteForceBudget = 5e7;

std::string fmt(Vec2 p) {
  std::ostringstream s;
  s.precision(10);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

/// Height at which the disk centred on the ray a + h n touches a site, or NaN.
double height_to_site(const Polygon2& poly, Vec2 a, Vec2 n, const BoundarySite& site) {
  if (site.kind == BoundarySite::Kind::Segment) {
    const Vec2 m = inward_normal(poly, site);
    const double denom = 1.0 - dot(n, m);
    return denom > 1e-15 ? dot(a - seg_start(poly, site.loop, site.index), m) / denom : NAN;
  }
  const Vec2 d = poly.loops[site.loop][site.index] - a;
  const double denom = 2.0 * dot(d, n);
  if (denom <= 0.0) return dot(d, d) == 0.0 ? 0.0 : NAN;
  return dot(d, d) / denom;
}

/// Unclamped parameter of the foot of x on a segment site.
double segment_param(const Polygon2& poly, const BoundarySite& s, Vec2 x) {
  const Vec2 a = seg_start(poly, s.loop, s.index);
  const Vec2 d = seg_end(poly, s.loop, s.index) - a;
  return dot(x - a, d) / dot(d, d);
}

bool point_in_polygon(const Polygon2& poly, Vec2 p) {
  bool inside = false;
  for (const auto& loop : poly.loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      const Vec2 a = loop[i];
      const Vec2 b = loop[j];
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) {
        inside = !inside;
      }
    }
  }
  return inside;
}

double distance_to_boundary(const Polygon2& poly, Vec2 p) {
  double best = INFINITY;
  for (std::uint32_t l = 0; l < poly.loops.size(); ++l) {
    for (std::uint32_t i = 0; i < poly.loops[l].size(); ++i) {
      best = std::min(best, site_distance(poly, {BoundarySite::Kind::Segment, l, i}, p));
    }
  }
  return best;
}

}  // namespace

MedialAxis::MedialAxis(Polygon2 polygon, std::vector<MaVertex> vertices, std::vector<MaEdge> edges)
    : polygon_(std::move(polygon)), vertices_(std::move(vertices)), edges_(std::move(edges)) {
  Box2 box;
  loop_offset_.resize(polygon_.loops.size() + 1, 0);
  for (std::size_t l = 0; l < polygon_.loops.size(); ++l) {
    for (Vec2 p : polygon_.loops[l]) box.add(p);
    loop_offset_[l + 1] = loop_offset_[l] + polygon_.loops[l].size();
  }
  size_ = box.diagonal();
  incident_.assign(vertices_.size(), {});
  cells_.assign(2 * loop_offset_.back(), {});
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const MaEdge& e = edges_[i];
    incident_[e.a.index()].push_back(MaEdgeId(i));
    incident_[e.b.index()].push_back(MaEdgeId(i));
    cells_[cell_index(e.left)].push_back(MaEdgeId(i));
    cells_[cell_index(e.right)].push_back(MaEdgeId(i));
  }
}

std::size_t MedialAxis::cell_index(const BoundarySite& s) const {
  return 2 * (loop_offset_[s.loop] + s.index) + (s.kind == BoundarySite::Kind::Corner ? 1 : 0);
}

std::vector<MaVertexId> MedialAxis::branch_points() const {
  std::vector<MaVertexId> out;
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (vertices_[v].degree >= 3) out.push_back(MaVertexId(v));
  }
  return out;
}

MaPoint MedialAxis::point_on_edge(MaEdgeId id, double t) const {
  const MaEdge& e = edges_[id.index()];
  const MaVertex& va = vertices_[e.a.index()];
  const MaVertex& vb = vertices_[e.b.index()];
  MaPoint p;
  p.edge = id;
  p.t = t;
  if (t <= 0.0 || t >= 1.0) {
    const MaVertex& end = t <= 0.0 ? va : vb;
    p.position = end.position;
    p.radius = end.radius;
    return p;
  }
  if (e.kind == MaEdgeKind::Line) {
    p.position = lerp(va.position, vb.position, t);
    p.radius = std::min(site_distance(polygon_, e.left, p.position),
                        site_distance(polygon_, e.right, p.position));
    return p;
  }
  // Parabola: the touching point moves linearly along the segment site; the centre is on the
  // segment's normal there, equidistant from the corner.
  const BoundarySite& seg = e.left.kind == BoundarySite::Kind::Segment ? e.left : e.right;
  const BoundarySite& corner = e.left.kind == BoundarySite::Kind::Segment ? e.right : e.left;
  const double fa = segment_param(polygon_, seg, va.position);
  const double fb = segment_param(polygon_, seg, vb.position);
  const Vec2 foot = lerp(seg_start(polygon_, seg.loop, seg.index),
                         seg_end(polygon_, seg.loop, seg.index), fa + t * (fb - fa));
  const Vec2 n = inward_normal(polygon_, seg);
  const double h = height_to_site(polygon_, foot, n, corner);
  if (!std::isfinite(h)) {  // degenerate (the corner on the segment's line): fall back to a chord
    p.position = lerp(va.position, vb.position, t);
    p.radius = site_distance(polygon_, corner, p.position);
    return p;
  }
  p.position = foot + h * n;
  p.radius = h;
  return p;
}

std::vector<Vec2> MedialAxis::sample_edge(MaEdgeId id, double max_chord) const {
  const MaEdge& e = edges_[id.index()];
  const Vec2 a = vertices_[e.a.index()].position;
  const Vec2 b = vertices_[e.b.index()].position;
  if (e.kind == MaEdgeKind::Line || !(max_chord > 0.0)) return {a, b};
  // Refine until every chord is short enough (parabolic arcs are gently curved).
  std::size_t n =
      std::max<std::size_t>(2, static_cast<std::size_t>(std::ceil(distance(a, b) / max_chord)));
  n = std::min<std::size_t>(n, 4096);
  std::vector<Vec2> pts;
  pts.reserve(n + 1);
  for (std::size_t i = 0; i <= n; ++i) {
    pts.push_back(point_on_edge(id, static_cast<double>(i) / static_cast<double>(n)).position);
  }
  pts.front() = a;
  pts.back() = b;
  return pts;
}

std::optional<MaPoint> MedialAxis::locate(MaEdgeId id, Vec2 x) const {
  const MaEdge& e = edges_[id.index()];
  const Vec2 a = vertices_[e.a.index()].position;
  const Vec2 b = vertices_[e.b.index()].position;
  double t;
  if (e.kind == MaEdgeKind::Line) {
    const Vec2 d = b - a;
    const double dd = dot(d, d);
    t = dd > 0.0 ? dot(x - a, d) / dd : 0.0;
  } else {
    const BoundarySite& seg = e.left.kind == BoundarySite::Kind::Segment ? e.left : e.right;
    const double fa = segment_param(polygon_, seg, a);
    const double fb = segment_param(polygon_, seg, b);
    const double fx = segment_param(polygon_, seg, x);
    t = fb != fa ? (fx - fa) / (fb - fa) : 0.0;
  }
  const double tol = kLocateRel * size_;
  const double len = distance(a, b);
  const double slack = len > 0.0 ? tol / len : 1.0;
  if (t < -slack || t > 1.0 + slack) return std::nullopt;
  MaPoint p = point_on_edge(id, std::clamp(t, 0.0, 1.0));
  if (distance(p.position, x) > std::max(tol, 1e-7 * p.radius)) return std::nullopt;
  return p;
}

std::optional<MaPoint> MedialAxis::project(const BoundaryPoint& bp) const {
  if (bp.site.kind != BoundarySite::Kind::Segment) return std::nullopt;
  if (edges_.empty()) {
    // A polygonised disk: its axis is its centre, which every boundary point maps to.
    if (vertices_.empty()) return std::nullopt;
    MaPoint centre;
    centre.position = vertices_.front().position;
    centre.radius = vertices_.front().radius;
    return centre;
  }
  const Vec2 s0 = seg_start(polygon_, bp.site.loop, bp.site.index);
  const Vec2 s1 = seg_end(polygon_, bp.site.loop, bp.site.index);
  const Vec2 p = lerp(s0, s1, bp.s);
  const Vec2 n = inward_normal(polygon_, bp.site);
  std::optional<MaPoint> best;
  for (MaEdgeId id : cells_[cell_index(bp.site)]) {
    const MaEdge& e = edges_[id.index()];
    const BoundarySite& other = e.left == bp.site ? e.right : e.left;
    const double h = height_to_site(polygon_, p, n, other);
    if (std::isfinite(h) && h >= 0.0) {
      if (auto m = locate(id, p + h * n); m && (!best || m->radius < best->radius)) best = m;
    }
  }
  if (best) return best;
  // The normal meets no edge of this segment's cell: the point is on a polygonised arc (or
  // beside one) whose branches were pruned. Its maximal disk is then, up to the chord
  // tolerance, the disk of the vertex whose circle passes closest to it: the arc's centre.
  double best_miss = INFINITY;
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    if (!(vertices_[v].radius > 0.0) || incident_[v].empty()) continue;
    const double miss = std::fabs(distance(p, vertices_[v].position) - vertices_[v].radius);
    if (miss < best_miss) {
      best_miss = miss;
      const MaEdgeId id = incident_[v].front();
      best = point_on_edge(id, edges_[id.index()].a == MaVertexId(v) ? 0.0 : 1.0);
    }
  }
  return best;
}

std::optional<MaPoint> MedialAxis::project_corner(std::uint32_t loop,
                                                  std::uint32_t vertex,
                                                  double w) const {
  const auto& l = polygon_.loops[loop];
  const std::uint32_t n = static_cast<std::uint32_t>(l.size());
  const BoundarySite in{BoundarySite::Kind::Segment, loop, (vertex + n - 1) % n};
  const BoundarySite out{BoundarySite::Kind::Segment, loop, vertex};
  const Vec2 n_in = inward_normal(polygon_, in);
  const Vec2 n_out = inward_normal(polygon_, out);
  const double sweep = std::atan2(cross(n_in, n_out), dot(n_in, n_out));
  if (sweep >= 0.0) return std::nullopt;  // not a reflex corner: no fan
  const double angle = std::clamp(w, 0.0, 1.0) * sweep;
  const Vec2 u{n_in.x * std::cos(angle) - n_in.y * std::sin(angle),
               n_in.x * std::sin(angle) + n_in.y * std::cos(angle)};
  const BoundarySite corner{BoundarySite::Kind::Corner, loop, vertex};
  const Vec2 q = l[vertex];
  std::optional<MaPoint> best;
  for (MaEdgeId id : cells_[cell_index(corner)]) {
    const MaEdge& e = edges_[id.index()];
    const BoundarySite& other = e.left == corner ? e.right : e.left;
    const double h = height_to_site(polygon_, q, u, other);
    if (!std::isfinite(h) || h <= 0.0) continue;
    if (auto m = locate(id, q + h * u); m && (!best || m->radius < best->radius)) best = m;
  }
  if (best) return best;
  // The fan's extreme directions end on the cell's boundary vertices: use the nearest one.
  for (MaEdgeId id : cells_[cell_index(corner)]) {
    for (double t : {0.0, 1.0}) {
      MaPoint m = point_on_edge(id, t);
      const Vec2 d = m.position - q;
      if (!best || std::fabs(cross(u, d)) / norm(d) <
                       std::fabs(cross(u, best->position - q)) / norm(best->position - q)) {
        best = m;
      }
    }
  }
  return best;
}

BoundaryPoint MedialAxis::touching_point(const MaPoint& p, Side side) const {
  const MaEdge& e = edges_[p.edge.index()];
  BoundaryPoint bp;
  bp.site = side == Side::Left ? e.left : e.right;
  bp.position = site_foot(polygon_, bp.site, p.position, &bp.s);
  return bp;
}

std::vector<BoundaryPoint> MedialAxis::touching_points(MaVertexId id) const {
  const MaVertex& v = vertices_[id.index()];
  std::vector<BoundaryPoint> out;
  const double tol = kLocateRel * size_;
  for (const BoundarySite& site : v.sites) {
    BoundaryPoint bp;
    bp.site = site;
    bp.position = site_foot(polygon_, site, v.position, &bp.s);
    if (std::fabs(distance(bp.position, v.position) - v.radius) > std::max(tol, 1e-7 * v.radius)) {
      continue;  // not on the disk (cannot happen for a valid axis)
    }
    bool duplicate = false;
    for (const auto& o : out) duplicate = duplicate || distance(o.position, bp.position) <= tol;
    if (!duplicate) out.push_back(bp);
  }
  return out;
}

std::optional<BoundaryPoint> MedialAxis::opposite(const BoundaryPoint& p) const {
  const std::optional<MaPoint> m = project(p);
  if (!m || !m->edge.valid()) return std::nullopt;  // a disk's centre has no other side
  const MaEdge& e = edges_[m->edge.index()];
  return touching_point(*m, e.left == p.site ? Side::Right : Side::Left);
}

std::vector<std::string> MedialAxis::validate() const {
  std::vector<std::string> problems;
  const double tol = kRadiusRel * size_;
  std::vector<std::uint32_t> degree(vertices_.size(), 0);
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    const MaEdge& e = edges_[i];
    if (e.a.index() >= vertices_.size() || e.b.index() >= vertices_.size() || e.a == e.b) {
      problems.push_back("edge " + std::to_string(i) + " has invalid end points");
      continue;
    }
    ++degree[e.a.index()];
    ++degree[e.b.index()];
    for (const MaVertexId end : {e.a, e.b}) {
      const MaVertex& v = vertices_[end.index()];
      for (const BoundarySite& s : {e.left, e.right}) {
        const double d = site_distance(polygon_, s, v.position);
        if (std::fabs(d - v.radius) > tol) {
          problems.push_back("edge " + std::to_string(i) + ": vertex " +
                             std::to_string(end.index()) + " at " + fmt(v.position) + " is " +
                             std::to_string(d) + " from a site, but its radius is " +
                             std::to_string(v.radius));
        }
      }
    }
    // The left site must be on the left of the walk from a to b.
    const Vec2 a = vertices_[e.a.index()].position;
    const Vec2 b = vertices_[e.b.index()].position;
    if (distance(a, b) > 1e3 * tol) {
      const MaPoint mid = point_on_edge(MaEdgeId(i), 0.5);
      const Vec2 dir =
          point_on_edge(MaEdgeId(i), 0.51).position - point_on_edge(MaEdgeId(i), 0.49).position;
      const Vec2 fl = site_foot(polygon_, e.left, mid.position);
      const Vec2 fr = site_foot(polygon_, e.right, mid.position);
      if (cross(dir, fl - mid.position) < 0.0 || cross(dir, fr - mid.position) > 0.0) {
        problems.push_back("edge " + std::to_string(i) + " has its sites on the wrong sides");
      }
    }
  }
  std::size_t step = 1;
  const double pairs =
      static_cast<double>(vertices_.size()) * static_cast<double>(polygon_.segment_count());
  if (pairs > kBruteForceBudget)
    step = static_cast<std::size_t>(std::ceil(pairs / kBruteForceBudget));
  for (std::size_t i = 0; i < vertices_.size(); ++i) {
    const MaVertex& v = vertices_[i];
    if (degree[i] != v.degree) {
      problems.push_back("vertex " + std::to_string(i) + " has degree " + std::to_string(v.degree) +
                         " but " + std::to_string(degree[i]) + " edges");
    }
    if (!(v.radius >= 0.0) || !std::isfinite(v.radius)) {
      problems.push_back("vertex " + std::to_string(i) + " at " + fmt(v.position) + " has radius " +
                         std::to_string(v.radius) + " (" + std::to_string(v.sites.size()) +
                         " sites)");
      continue;
    }
    if (i % step != 0) continue;
    const double d = distance_to_boundary(polygon_, v.position);
    if (std::fabs(d - v.radius) > tol) {
      problems.push_back("vertex " + std::to_string(i) + " at " + fmt(v.position) + " has radius " +
                         std::to_string(v.radius) + " but is " + std::to_string(d) +
                         " from the boundary");
    }
    if (!v.corner && !point_in_polygon(polygon_, v.position)) {
      problems.push_back("vertex " + std::to_string(i) + " at " + fmt(v.position) +
                         " is outside the polygon");
    }
  }
  return problems;
}

}  // namespace laytracks
