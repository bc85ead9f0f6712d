// The MedialAxis graph: evaluation of edges, the two-way mapping and the self-check.
#include "laytracks/medial/medial_axis.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "laytracks/brep/union_find.hpp"
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
/// A spread zone reaches into the covered boundary on each side of its stretch by this x the
/// stretch's length (docs/medial.md): the stretch and its reaches, 3 lengths of boundary, map
/// onto the axis beside the root that the reaches alone had, rails converging by a third.
constexpr double kSpreadReach = 1.0;
/// A spread zone is made only where the axis beside its root (the image of the reaches) is at
/// least this x the stretch's length: the stretch is taken at most 2:1.
constexpr double kMinSpreadImage = 0.5;
/// Nor where either reach is below this x the stretch's length.
constexpr double kMinSpreadReach = 1e-3;
/// An extended zone's image (find_spread_zones) ends at most this fraction of the way to a
/// vertex whose axis another zone of its side may take ...
constexpr double kSpreadShare = 0.45;
/// ... and at most this fraction of the way to a branch point.
constexpr double kSpreadToBranch = 0.75;
/// choose_round_holes: fans within this relative slack of the limit count as at it.
constexpr double kRoundHoleSlack = 1e-7;
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
  find_spread_zones();
  // Per segment: the circle it is a chord of when the region lies outside that circle (its
  // centre right of the segment), else -1 (site_circle).
  if (!polygon_.circle.empty()) {
    chord_circle_.assign(loop_offset_.back(), -1);
    for (std::uint32_t l = 0; l < polygon_.loops.size(); ++l)
      for (std::uint32_t j = 0; j < polygon_.loops[l].size(); ++j) {
        const std::int32_t k = polygon_.circle[l][j];
        const Vec2 a = seg_start(polygon_, l, j);
        if (k >= 0 && cross(seg_end(polygon_, l, j) - a,
                            polygon_.circles[static_cast<std::size_t>(k)].centre - a) < 0.0)
          chord_circle_[loop_offset_[l] + j] = k;
      }
  }
}

void MedialAxis::find_spread_zones() {
  const double eps = kLocateRel * size_;
  // Per segment: the parameter range its cell's edges touch, and the edge and vertex at each
  // end of it (lo > hi: no edge at all, the whole segment is uncovered).
  struct Cover {
    double lo = INFINITY, hi = -INFINITY;
    MaEdgeId lo_edge, hi_edge;
    MaVertexId lo_vertex, hi_vertex;
    double len = 0.0;
  };
  // An uncovered stretch: from the end of segment i's covered range through wholly uncovered
  // segments (`whole`) to the start of segment k's. Its root, the vertex both ends map to,
  // is cover[i].hi_vertex.
  struct Stretch {
    std::uint32_t i = 0, k = 0;
    std::vector<std::uint32_t> whole;
    double length = 0.0;
  };
  // A zone over the boundary from s1 on segment st.i, through st.whole, to s2 on segment st.k
  // (its pieces and length; its steps are the caller's).
  const auto zone_over = [&](std::uint32_t l, const Stretch& st, double s1, double s2,
                             const std::vector<Cover>& cover) {
    SpreadZone z;
    z.loop = l;
    z.pieces.push_back({st.i, s1, 1.0, 0.0});
    double at = (1.0 - s1) * cover[st.i].len;
    for (std::uint32_t w : st.whole) {
      z.pieces.push_back({w, 0.0, 1.0, at});
      at += cover[w].len;
    }
    z.pieces.push_back({st.k, 0.0, s2, at});
    z.length = at + s2 * cover[st.k].len;
    return z;
  };
  // A zone whose image on the root's own two edges is too short (kMinSpreadImage) may take
  // more of the axis (docs/medial.md, "Extended zones"): from the root the walk goes on
  // through every vertex of degree 2 where the zone's side keeps its segment (only the far
  // side's site changes there: a corner over there, whose own zone maps that side only), and
  // stops at the first other vertex. The image ends at most kSpreadShare of the way to a stop
  // whose axis another zone of this side may take (a vertex where this side's segment changes:
  // a corner of this side maps there; a leaf), at most kSpreadToBranch of the way to a branch
  // point (whose touching point on this side starts a source rail), and at most kSpreadReach
  // x the stretch's length from the root. The zone is then the boundary whose normals meet
  // the axis between the two ends, with the stretch, mapped in proportion to arc length; it is
  // made when the image is at least kMinSpreadImage x the stretch's length. Every zone that
  // the root's own edges can take stays as it was.
  const auto extended = [&](std::uint32_t l, const Stretch& st,
                            const std::vector<Cover>& cover) -> std::optional<SpreadZone> {
    const Cover& a = cover[st.i];
    const Cover& b = cover[st.k];
    struct Walked {
      MaEdgeId edge;
      double t_root = 0.0;  ///< the edge's parameter at its end nearer the root
      double len = 0.0;     ///< its chord
    };
    // From the root along `first`, whose site on the zone's side is `near`.
    const auto walk = [&](MaEdgeId first, const BoundarySite& near, double& share) {
      std::vector<Walked> path;
      MaEdgeId e = first;
      MaVertexId from = a.hi_vertex;  // the root
      share = kSpreadShare;
      while (path.size() < edges_.size()) {
        const MaEdge& ed = edges_[e.index()];
        const MaVertexId to = ed.a == from ? ed.b : ed.a;
        path.push_back({e, ed.a == from ? 0.0 : 1.0,
                        distance(vertices_[from.index()].position, vertices_[to.index()].position)});
        const MaVertex& v = vertices_[to.index()];
        if (v.degree != 2 || !(v.radius > 0.0)) {
          if (v.degree >= 3) share = kSpreadToBranch;
          break;
        }
        const auto& inc = incident_[to.index()];
        const MaEdgeId next = inc[0] == e ? inc[1] : inc[0];
        const MaEdge& nx = edges_[next.index()];
        if (nx.left != near && nx.right != near) break;
        from = to;
        e = next;
      }
      return path;
    };
    struct End {
      std::size_t last = 0;  ///< the path's edge the image ends on
      double t = 0.0;        ///< there
      double before = 0.0;   ///< the chords of the path's edges before it
      double image = 0.0;    ///< axis length from the root (chords of the edges)
      double s = 0.0;        ///< the foot of that point on the zone's side
    };
    const auto image_end = [&](const std::vector<Walked>& path, const BoundarySite& near,
                               double share) -> std::optional<End> {
      double total = 0.0;
      for (const Walked& w : path) total += w.len;
      const double want = std::min(kSpreadReach * st.length, share * total);
      if (!(want > eps)) return std::nullopt;
      double before = 0.0;
      for (std::size_t j = 0; j < path.size(); ++j) {
        const Walked& w = path[j];
        if (before + w.len < want && j + 1 < path.size()) {
          before += w.len;
          continue;
        }
        double q = w.len > 0.0 ? std::clamp((want - before) / w.len, 0.0, 1.0) : 1.0;
        if (j + 1 == path.size()) q = std::min(q, share);  // also in the edge's own measure
        End end;
        end.last = j;
        end.t = w.t_root + (1.0 - 2.0 * w.t_root) * q;
        end.before = before;
        end.image = before + q * w.len;
        end.s = std::clamp(
            segment_param(polygon_, near, point_on_edge(w.edge, end.t).position), 0.0, 1.0);
        return end;
      }
      return std::nullopt;
    };
    const BoundarySite near1{BoundarySite::Kind::Segment, l, st.i};
    const BoundarySite near2{BoundarySite::Kind::Segment, l, st.k};
    double share1 = 0.0, share2 = 0.0;
    const std::vector<Walked> p1 = walk(a.hi_edge, near1, share1);
    const std::vector<Walked> p2 = walk(b.lo_edge, near2, share2);
    const std::optional<End> end1 = image_end(p1, near1, share1);
    const std::optional<End> end2 = image_end(p2, near2, share2);
    if (!end1 || !end2 || end1->image + end2->image < kMinSpreadImage * st.length)
      return std::nullopt;
    // As for a zone on the root's edges: no reach of almost nothing.
    const double d1 = (a.hi - end1->s) * a.len, d2 = (end2->s - b.lo) * b.len;
    if (d1 <= eps || d2 <= eps || std::min(d1, d2) < kMinSpreadReach * st.length)
      return std::nullopt;
    SpreadZone z = zone_over(l, st, end1->s, end2->s, cover);
    // Side 1 from its end to the root, then side 2 from the root to its end, each edge taking
    // the zone's fractions in proportion to its chord.
    const double image = end1->image + end2->image;
    double done = 0.0;
    const auto step = [&](const Walked& w, const BoundarySite& near, double t0, double t1,
                          double len) {
      const double f0 = done / image;
      done += len;
      z.steps.push_back({w.edge, t0, t1, f0, std::min(1.0, done / image), near});
    };
    for (std::size_t j = end1->last + 1; j-- > 0;) {
      const Walked& w = p1[j];
      if (j == end1->last)
        step(w, near1, end1->t, w.t_root, end1->image - end1->before);
      else
        step(w, near1, 1.0 - w.t_root, w.t_root, w.len);
    }
    for (std::size_t j = 0; j <= end2->last; ++j) {
      const Walked& w = p2[j];
      if (j == end2->last)
        step(w, near2, w.t_root, end2->t, end2->image - end2->before);
      else
        step(w, near2, w.t_root, 1.0 - w.t_root, w.len);
    }
    z.steps.back().f1 = 1.0;
    return z;
  };
  for (std::uint32_t l = 0; l < polygon_.loops.size(); ++l) {
    const auto n = static_cast<std::uint32_t>(polygon_.loops[l].size());
    std::vector<Cover> cover(n);
    for (std::uint32_t i = 0; i < n; ++i) {
      const BoundarySite seg{BoundarySite::Kind::Segment, l, i};
      Cover& c = cover[i];
      c.len = distance(seg_start(polygon_, l, i), seg_end(polygon_, l, i));
      for (MaEdgeId id : cells_[cell_index(seg)]) {
        const MaEdge& e = edges_[id.index()];
        for (MaVertexId v : {e.a, e.b}) {
          const double f = segment_param(polygon_, seg, vertices_[v.index()].position);
          if (f < c.lo) {
            c.lo = f;
            c.lo_edge = id;
            c.lo_vertex = v;
          }
          if (f > c.hi) {
            c.hi = f;
            c.hi_edge = id;
            c.hi_vertex = v;
          }
        }
      }
    }
    for (std::uint32_t i = 0; i < n; ++i) {
      const Cover& a = cover[i];
      if (!(a.lo <= a.hi) || a.len <= 0.0 || (1.0 - a.hi) * a.len <= eps) continue;
      // An uncovered end: walk on through uncovered segments to the next covered start.
      Stretch st;
      st.i = i;
      st.length = (1.0 - a.hi) * a.len;
      std::uint32_t k = (i + 1) % n;
      for (std::uint32_t step = 0; step < n && !(cover[k].lo <= cover[k].hi); ++step) {
        st.whole.push_back(k);
        st.length += cover[k].len;
        k = (k + 1) % n;
      }
      const Cover& b = cover[k];
      if (k == i || !(b.lo <= b.hi) || b.lo * b.len <= eps) continue;
      st.k = k;
      st.length += b.lo * b.len;
      const double length = st.length;
      // Both ends at one vertex of degree 2, whose two edges hold the ends: the axis runs on
      // both ways from the vertex the whole stretch maps to.
      const MaVertexId root = a.hi_vertex;
      if (b.lo_vertex != root || vertices_[root.index()].degree != 2 ||
          a.hi_edge == b.lo_edge || !(vertices_[root.index()].radius > 0.0))
        continue;
      // Parameter along an edge of a segment's foot there: linear (a line's t follows arc
      // length, a parabola's its touching point along its segment site).
      const auto t_at = [&](MaEdgeId id, std::uint32_t seg, double f) {
        const MaEdge& e = edges_[id.index()];
        const BoundarySite site{BoundarySite::Kind::Segment, l, seg};
        const double fa = segment_param(polygon_, site, vertices_[e.a.index()].position);
        const double fb = segment_param(polygon_, site, vertices_[e.b.index()].position);
        return fb != fa ? std::clamp((f - fa) / (fb - fa), 0.0, 1.0) : 0.0;
      };
      const auto other_foot = [&](MaEdgeId id, std::uint32_t seg) {
        const MaEdge& e = edges_[id.index()];
        const BoundarySite site{BoundarySite::Kind::Segment, l, seg};
        return segment_param(polygon_, site,
                             vertices_[(e.a == root ? e.b : e.a).index()].position);
      };
      // The zone reaches on each side into the covered boundary by the stretch's length, at
      // most half of what the root's edge covers there (kSpreadReach).
      const double d1 = std::min(kSpreadReach * length,
                                 0.5 * std::max(0.0, a.hi - other_foot(a.hi_edge, i)) * a.len);
      const double d2 = std::min(kSpreadReach * length,
                                 0.5 * std::max(0.0, other_foot(b.lo_edge, k) - b.lo) * b.len);
      // A reach of almost nothing is an edge of almost nothing beside the root (rounding split
      // a branch point: cgal_wheel_16_spokes has one at 8 of its 16 spoke ends, 6e-6 long): the
      // zone would spread the stretch on one side only.
      if (d1 <= eps || d2 <= eps || std::min(d1, d2) < kMinSpreadReach * length) continue;
      const double s1 = a.hi - d1 / a.len, s2 = b.lo + d2 / b.len;
      SpreadZone z = zone_over(l, st, s1, s2, cover);
      const MaEdgeId e1 = a.hi_edge, e2 = b.lo_edge;
      const double t1 = t_at(e1, i, s1);
      const double t1v = edges_[e1.index()].a == root ? 0.0 : 1.0;
      const double t2v = edges_[e2.index()].a == root ? 0.0 : 1.0;
      const double t2 = t_at(e2, k, s2);
      const Vec2 r = vertices_[root.index()].position;
      const double l1 = distance(point_on_edge(e1, t1).position, r);
      const double l2 = distance(point_on_edge(e2, t2).position, r);
      if (!(l1 + l2 > eps)) continue;
      if (l1 + l2 < kMinSpreadImage * length) {
        // Too little axis on the root's own edges: the image may go on along the axis
        // (`extended`), else the fan stays.
        if (std::optional<SpreadZone> ez = extended(l, st, cover))
          zones_.push_back(std::move(*ez));
        continue;
      }
      const double split = l1 / (l1 + l2);
      z.steps.push_back({e1, t1, t1v, 0.0, split, {BoundarySite::Kind::Segment, l, i}});
      z.steps.push_back({e2, t2v, t2, split, 1.0, {BoundarySite::Kind::Segment, l, k}});
      zones_.push_back(std::move(z));
    }
  }
  zones_on_segment_.assign(loop_offset_.back(), {});
  zones_on_edge_.assign(edges_.size(), {});
  for (std::uint32_t i = 0; i < zones_.size(); ++i) {
    const SpreadZone& z = zones_[i];
    for (const auto& piece : z.pieces) {
      auto& on = zones_on_segment_[loop_offset_[z.loop] + piece.segment];
      if (on.empty() || on.back() != i) on.push_back(i);
    }
    for (const auto& step : z.steps) {
      auto& on = zones_on_edge_[step.edge.index()];
      if (on.empty() || on.back() != i) on.push_back(i);
    }
  }
}

const MedialAxis::SpreadZone* MedialAxis::zone_of(const BoundaryPoint& p) const {
  if (zones_.empty() || p.site.kind != BoundarySite::Kind::Segment) return nullptr;
  for (std::uint32_t i : zones_on_segment_[loop_offset_[p.site.loop] + p.site.index]) {
    const SpreadZone& z = zones_[i];
    for (const auto& piece : z.pieces) {
      if (piece.segment == p.site.index && p.s >= piece.s0 && p.s <= piece.s1) return &z;
    }
  }
  return nullptr;
}

int MedialAxis::site_circle(const BoundarySite& s) const {
  if (chord_circle_.empty()) return -1;
  const std::size_t at = loop_offset_[s.loop];
  if (s.kind == BoundarySite::Kind::Segment) return chord_circle_[at + s.index];
  // A corner between two chords of the circle, or where the circle meets a tangent line (the
  // end of a slot's round end): its cell's points map along rays too, onto the chords.
  const auto n = static_cast<std::uint32_t>(polygon_.loops[s.loop].size());
  const std::int32_t in = chord_circle_[at + (s.index + n - 1) % n],
                     out = chord_circle_[at + s.index];
  if (in >= 0 && in == out) return in;
  if ((in >= 0) != (out >= 0) && polygon_.smooth[s.loop][s.index]) return in >= 0 ? in : out;
  return -1;
}

int MedialAxis::concave_circle(const BoundarySite& s) const {
  if (round_.empty()) return -1;
  const int k = site_circle(s);
  return k >= 0 && round_[static_cast<std::size_t>(k)] ? k : -1;
}

std::vector<Circle2> MedialAxis::round_circles() const {
  std::vector<Circle2> out;
  for (std::size_t k = 0; k < round_.size(); ++k)
    if (round_[k]) out.push_back(polygon_.circles[k]);
  return out;
}

std::size_t MedialAxis::choose_round_holes(double element_size) {
  const std::size_t nc = polygon_.circles.size();
  round_.assign(nc, 0);
  std::vector<double> delta(nc, 0.0), beside(nc, 0.0);
  std::vector<char> concave(nc, 0);
  for (std::uint32_t l = 0; l < polygon_.circle.size(); ++l) {
    for (std::uint32_t j = 0; j < polygon_.circle[l].size(); ++j) {
      for (const BoundarySite site : {BoundarySite{BoundarySite::Kind::Segment, l, j},
                                      BoundarySite{BoundarySite::Kind::Corner, l, j}}) {
        const int k = site_circle(site);
        if (k < 0) continue;
        const auto kk = static_cast<std::size_t>(k);
        concave[kk] = 1;
        if (site.kind == BoundarySite::Kind::Segment) {
          const Vec2 c = polygon_.circles[kk].centre;
          const Vec2 a = seg_start(polygon_, l, j) - c, b = seg_end(polygon_, l, j) - c;
          delta[kk] = std::max(delta[kk], std::abs(std::atan2(cross(a, b), dot(a, b))));
        }
        for (MaEdgeId id : cells_[cell_index(site)]) {
          const MaEdge& e = edges_[id.index()];
          beside[kk] =
              std::max({beside[kk], vertices_[e.a.index()].radius, vertices_[e.b.index()].radius});
        }
      }
    }
  }
  std::size_t chosen = 0;
  for (std::size_t k = 0; k < nc; ++k) {
    const double fan = (polygon_.circles[k].radius + beside[k]) * delta[k] / element_size;
    // With the rounding slack of the mesher's counts: a fan of exactly three in one pose is
    // one in every pose.
    round_[k] = concave[k] && fan > kRoundHoleFanRails * (1.0 + kRoundHoleSlack) ? 1 : 0;
    if (round_[k]) ++chosen;
  }
  return chosen;
}

namespace {

/// Calls visit(j) for the segments of loop l that are chords of circle k, contiguous with
/// segment `hint` (itself first, then onwards, then backwards), until visit returns true.
template <class Visit>
void walk_run(
    const Polygon2& poly, std::uint32_t l, std::uint32_t hint, std::int32_t k, const Visit& visit) {
  const std::vector<std::int32_t>& circle = poly.circle[l];
  const auto n = static_cast<std::uint32_t>(circle.size());
  std::uint32_t j = hint;
  std::uint32_t seen = 0;
  for (; seen < n && circle[j] == k; ++seen, j = (j + 1) % n)
    if (visit(j)) return;
  for (j = (hint + n - 1) % n; seen < n && circle[j] == k; ++seen, j = (j + n - 1) % n)
    if (visit(j)) return;
}

}  // namespace

std::optional<BoundaryPoint> MedialAxis::radial_foot(std::uint32_t loop,
                                                     std::uint32_t hint,
                                                     int k,
                                                     Vec2 x) const {
  const Vec2 c = polygon_.circles[static_cast<std::size_t>(k)].centre;
  const Vec2 d = x - c;
  std::optional<BoundaryPoint> out;
  walk_run(polygon_, loop, hint, k, [&](std::uint32_t j) {
    const Vec2 a = seg_start(polygon_, loop, j), b = seg_end(polygon_, loop, j);
    const double ca = cross(a - c, d), cb = cross(b - c, d);
    if ((ca > 0.0 && cb > 0.0) || (ca < 0.0 && cb < 0.0) || ca == cb) return false;
    if (!(dot((a - c) + (b - c), d) > 0.0)) return false;  // the ray's other half
    const double s = std::clamp(ca / (ca - cb), 0.0, 1.0);
    out = BoundaryPoint{{BoundarySite::Kind::Segment, loop, j}, s, lerp(a, b, s)};
    return true;
  });
  if (out) return out;
  // The ray passes an end of the run (a point of the axis beside the arc's end): that end, so
  // that the feet keep their order along the boundary as the point moves.
  // The run's first and last chords (the hint itself may be the tangent line beyond its end).
  const auto n = static_cast<std::uint32_t>(polygon_.loops[loop].size());
  std::optional<std::uint32_t> lo, hi;
  walk_run(polygon_, loop, hint, k, [&](std::uint32_t j) {
    if (!hi) {
      lo = hi = j;
    } else if (j == (*hi + 1) % n) {
      hi = j;
    } else if (j == (*lo + n - 1) % n) {
      lo = j;
    }
    return false;
  });
  if (!hi) return std::nullopt;
  const Vec2 start = seg_start(polygon_, loop, *lo), end = seg_end(polygon_, loop, *hi);
  const auto along = [&](Vec2 q) { return dot(q - c, d) / norm(q - c); };
  if (along(end) >= along(start))
    return BoundaryPoint{{BoundarySite::Kind::Segment, loop, *hi}, 1.0, end};
  return BoundaryPoint{{BoundarySite::Kind::Segment, loop, *lo}, 0.0, start};
}

std::optional<MaPoint> MedialAxis::radial_project(const BoundarySite& site, int k, Vec2 x) const {
  const Vec2 c = polygon_.circles[static_cast<std::size_t>(k)].centre;
  const Vec2 d = x - c;
  const double from = norm(d);
  if (!(from > 0.0)) return std::nullopt;
  const double tol = kLocateRel * size_;
  const auto side = [&](Vec2 q) { return cross(d, q - c); };
  std::optional<MaPoint> best;
  double best_at = INFINITY;
  const auto try_edge = [&](MaEdgeId id) {
    const MaEdge& e = edges_[id.index()];
    const double f0 = side(vertices_[e.a.index()].position);
    const double f1 = side(vertices_[e.b.index()].position);
    if ((f0 > 0.0 && f1 > 0.0) || (f0 < 0.0 && f1 < 0.0)) return;
    double t = 0.0;
    if (f0 == 0.0 || f1 == 0.0) {
      t = f0 == 0.0 ? 0.0 : 1.0;  // an end on the ray's line (both: the start)
    } else if (e.kind == MaEdgeKind::Line) {
      t = f0 / (f0 - f1);
    } else {
      double lo = 0.0, hi = 1.0;  // f changes sign on [lo, hi]
      for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
        const double mid = 0.5 * (lo + hi);
        const double fm = side(point_on_edge(id, mid).position);
        if ((fm > 0.0) == (f0 > 0.0) && fm != 0.0) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      t = 0.5 * (lo + hi);
    }
    const MaPoint m = point_on_edge(id, std::clamp(t, 0.0, 1.0));
    const Vec2 r = m.position - c;
    const double at = dot(r, d) / from;
    if (at < from - tol || at >= best_at) return;
    best = m;
    best_at = at;
  };
  const std::uint32_t l = site.loop;
  walk_run(polygon_, l, site.index, k, [&](std::uint32_t j) {
    for (MaEdgeId id : cells_[cell_index({BoundarySite::Kind::Segment, l, j})]) try_edge(id);
    // The corners at the chord's ends, when they are the circle's (concave_circle); a corner
    // between two chords is met twice, and its edges tried twice, to no effect.
    const auto n = static_cast<std::uint32_t>(polygon_.loops[l].size());
    for (const std::uint32_t v : {j, (j + 1) % n}) {
      const BoundarySite corner{BoundarySite::Kind::Corner, l, v};
      if (concave_circle(corner) == k)
        for (MaEdgeId id : cells_[cell_index(corner)]) try_edge(id);
    }
    return false;
  });
  return best;
}

Side MedialAxis::far_side(const MaPoint& m, const BoundaryPoint& p) const {
  const MaEdge& e = edges_[m.edge.index()];
  if (e.left == p.site) return Side::Right;
  if (e.right == p.site) return Side::Left;
  // A point of a round hole maps along the ray from its centre (project): its MA point's
  // near site is another chord or corner of that circle.
  if (const int k = concave_circle(p.site); k >= 0) {
    if (concave_circle(e.left) == k) return Side::Right;
    if (concave_circle(e.right) == k) return Side::Left;
  }
  if (const SpreadZone* z = zone_of(p)) {
    const BoundarySite* near = &z->steps.back().near;
    for (const auto& step : z->steps)
      if (step.edge == m.edge) {
        near = &step.near;
        break;
      }
    return e.left == *near ? Side::Right : Side::Left;
  }
  return Side::Left;
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
  if (const SpreadZone* z = zone_of(bp)) {
    double x = 0.0;
    for (const auto& piece : z->pieces) {
      if (piece.segment != bp.site.index) continue;
      const double len = distance(seg_start(polygon_, bp.site.loop, piece.segment),
                                  seg_end(polygon_, bp.site.loop, piece.segment));
      x = piece.at + (bp.s - piece.s0) * len;
      break;
    }
    const double f = std::clamp(x / z->length, 0.0, 1.0);
    const SpreadZone::Step* on = &z->steps.back();
    for (const auto& step : z->steps)
      if (f <= step.f1) {
        on = &step;
        break;
      }
    MaPoint m = point_on_edge(on->edge, on->t0 + (on->t1 - on->t0) * ((f - on->f0) / (on->f1 - on->f0)));
    m.off_normal = true;
    return m;
  }
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
  // On a round hole (or a concave fillet) along the ray from the circle's centre, as on the
  // circle itself: the rails across it spread over the hole instead of meeting at a chord's
  // end (docs/medial.md, "Round holes").
  if (const int k = concave_circle(bp.site); k >= 0)
    if (auto m = radial_project(bp.site, k, p)) return m;
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
  if (best) best->off_normal = true;
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
  // On a spread zone's side of its edges: the zone's point that project() maps here (the
  // inverse of its proportional map), so that the mapping is one-to-one both ways.
  for (std::uint32_t i : zones_on_edge_[p.edge.index()]) {
    const SpreadZone& z = zones_[i];
    double f = -1.0;
    for (const auto& step : z.steps) {
      if (p.edge != step.edge || bp.site != step.near || step.t1 == step.t0) continue;
      const double u = (p.t - step.t0) / (step.t1 - step.t0);
      if (u >= 0.0 && u <= 1.0) f = step.f0 + u * (step.f1 - step.f0);
      break;
    }
    if (f < 0.0) continue;
    const double x = f * z.length;
    const SpreadZone::Piece* at = &z.pieces.front();
    for (const auto& piece : z.pieces)
      if (piece.at <= x) at = &piece;
    const Vec2 a = seg_start(polygon_, z.loop, at->segment);
    const Vec2 b = seg_end(polygon_, z.loop, at->segment);
    bp.site = {BoundarySite::Kind::Segment, z.loop, at->segment};
    bp.s = std::clamp(at->s0 + (x - at->at) / distance(a, b), at->s0, at->s1);
    bp.position = lerp(a, b, bp.s);
    return bp;
  }
  if (const int k = concave_circle(bp.site); k >= 0)
    if (auto r = radial_foot(bp.site.loop, bp.site.index, k, p.position)) return *r;
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
    if (const int k = concave_circle(site); k >= 0)
      if (auto r = radial_foot(site.loop, site.index, k, v.position)) bp = *r;
    bool duplicate = false;
    for (const auto& o : out) duplicate = duplicate || distance(o.position, bp.position) <= tol;
    if (!duplicate) out.push_back(bp);
  }
  return out;
}

std::optional<BoundaryPoint> MedialAxis::opposite(const BoundaryPoint& p) const {
  const std::optional<MaPoint> m = project(p);
  if (!m || !m->edge.valid()) return std::nullopt;  // a disk's centre has no other side
  return touching_point(*m, far_side(*m, p));
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
  // One piece: the axis of a connected region is connected. (Boost's diagram of a grid-cell
  // outline rotated in 3D once lost the stretch of axis along a corridor, and every other
  // check passed.)
  UnionFind pieces_of(vertices_.size());
  for (const MaEdge& e : edges_)
    if (e.a.index() < vertices_.size() && e.b.index() < vertices_.size())
      pieces_of.unite(e.a.index(), e.b.index());
  std::size_t pieces = 0;
  for (std::size_t i = 0; i < vertices_.size(); ++i)
    if (pieces_of.find(i) == i) ++pieces;
  if (pieces > 1) {
    problems.push_back("the axis is in " + std::to_string(pieces) +
                       " pieces, but the polygon is one region");
  } else if (!vertices_.empty()) {
    // As many cycles as holes: the axis is a deformation retract of the region, a loop round
    // each hole. (Boost's diagram of a grid-cell ring, outline and hole with their collinear
    // corners exactly opposite across a wall, lost one stretch of the wall's axis: a tree,
    // connected, every vertex at its radius, and the rails of that wall ran to two points.)
    const auto cycles =
        static_cast<long long>(edges_.size()) - static_cast<long long>(vertices_.size()) + 1;
    const auto holes = static_cast<long long>(polygon_.loops.size()) - 1;
    if (cycles != holes) {
      problems.push_back("the axis has " + std::to_string(cycles) + " cycles, but the polygon " +
                         std::to_string(holes) + " holes");
    }
  }
  return problems;
}

}  // namespace laytracks
