// Adaptive mode: the width law of Algorithm III and its probe of the radius function across
// patches (docs/adaptive.md).
#include "laytracks/cutgraph/adaptive.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <tuple>

#include "boundary_index.hpp"
#include "laytracks/brep/error.hpp"

namespace laytracks {

namespace {

/// A probe follows a rail through at most this many patch crossings.
constexpr int kMaxProbeSteps = 16;
/// Parameter step for the numerical gradient of the radius along an MA edge.
constexpr double kGradientStep = 1e-4;
/// An MA point this close (in parameter, or within kSamePointRel x the part's size) to an end
/// of its edge is at that vertex, as for rails: at a branch point the probe stops.
constexpr double kAtEndT = 1e-9;
/// The probe reads the radius at least this far (parameter) inside a boundary segment.
constexpr double kCornerInset = 1e-6;
constexpr double kSamePointRel = 1e-7;

}  // namespace

struct TrackWidthLaw::Impl {
  const Part& part;
  const std::vector<MedialAxis>& axes;
  cutgraph_detail::BoundaryIndex index;

  Impl(const Part& p, const std::vector<MedialAxis>& a) : part(p), axes(a), index(p) {}

  /// |dR/ds| along edge e at parameter t: exact for a line (R is linear in arc length), a
  /// difference over a short step for a parabola.
  double edge_gradient(PatchId p, MaEdgeId e, double t) const {
    const MedialAxis& ma = axes[p.index()];
    const MaPoint a = ma.point_on_edge(e, std::max(0.0, t - kGradientStep));
    const MaPoint b = ma.point_on_edge(e, std::min(1.0, t + kGradientStep));
    const double ds = distance(a.position, b.position);
    if (!(ds > 0.0)) return 0.0;
    return std::min(1.0, std::abs(b.radius - a.radius) / ds);
  }

  /// |dR/ds| along the axis at m. At an MA vertex (a branch point, where a source rail's foot
  /// projects), the mean over its edges: which edge `project` names there is rounding.
  double gradient(PatchId p, const MaPoint& m) const {
    if (!m.edge.valid()) return 0.0;
    const MedialAxis& ma = axes[p.index()];
    const MaEdge& e = ma.edge(m.edge);
    const double tol = kSamePointRel * part.size;
    for (const MaVertexId v : {e.a, e.b}) {
      if (distance(m.position, ma.vertex(v).position) > tol) continue;
      double sum = 0.0;
      for (const MaEdgeId f : ma.incident(v)) sum += edge_gradient(p, f, ma.edge(f).a == v ? 0.0 : 1.0);
      return sum / static_cast<double>(ma.incident(v).size());
    }
    return edge_gradient(p, m.edge, m.t);
  }

  BoundaryPoint point_on(const cutgraph_detail::SegmentRef& r, double t) const {
    const auto& loop = part.patches[r.patch.index()].polygon.loops[r.loop];
    BoundaryPoint bp;
    bp.site = {BoundarySite::Kind::Segment, r.loop, r.seg};
    bp.s = r.forward ? t : 1.0 - t;
    bp.position = lerp(loop[r.seg], loop[(r.seg + 1) % loop.size()], bp.s);
    return bp;
  }
};

TrackWidthLaw::TrackWidthLaw(const Part& part,
                             const std::vector<MedialAxis>& axes,
                             const AdaptiveOptions& o)
    : impl_(std::make_unique<Impl>(part, axes)), options_(o) {
  if (!(o.dtheta > 0.0)) throw InternalError("adaptive mode: dtheta must be positive");
  for (const MedialAxis& ma : axes)
    for (const MaVertex& v : ma.vertices()) max_radius_ = std::max(max_radius_, v.radius);
  // The paper's 3% of the largest radius at the default dtheta, and in proportion to dtheta
  // (a finer dtheta refines the corners too, instead of stopping at the same floor).
  end_width_ = o.min_size > 0.0 ? o.min_size
                                : kMinEndWidthFraction * max_radius_ * o.dtheta /
                                      (kDefaultDthetaDeg * kPi / 180.0);
  end_width_ = std::min(end_width_, options_.max_size);
  if (!(end_width_ > 0.0)) throw InternalError("adaptive mode: the part has no medial radius");
}

TrackWidthLaw::~TrackWidthLaw() = default;

RadiusSample TrackWidthLaw::radius(PatchId p, const BoundaryPoint& bp) const {
  const Impl& im = *impl_;
  RadiusSample out;
  out.radius = std::numeric_limits<double>::infinity();
  double gradient_sum = 0.0;
  // Breadth first over (patch, boundary point): the point's images on the patches of its
  // edge, then, across each patch's axis, the point on the other side and its images.
  std::deque<std::pair<PatchId, BoundaryPoint>> queue{{p, bp}};
  std::set<std::tuple<std::uint32_t, std::uint32_t, long long>> seen;
  const auto add_images = [&](PatchId q, const BoundaryPoint& b) {
    const EdgeId e = im.index.edge_at(q, b.site.loop, b.site.index);
    const double t = im.index.edge_param(q, b.site.loop, b.site.index, b.s);
    for (const auto& r : im.index.segments_of(e)) {
      if (r.patch == q) continue;
      queue.push_back({r.patch, im.point_on(r, t)});
    }
  };
  add_images(p, bp);
  int steps = 0;
  while (!queue.empty() && steps < kMaxProbeSteps) {
    auto [q, b] = queue.front();
    queue.pop_front();
    // At a corner itself, which disk the point belongs to is decided by rounding: read the
    // radius just inside the segment.
    if (b.s < kCornerInset || b.s > 1.0 - kCornerInset) {
      const auto& loop = im.part.patches[q.index()].polygon.loops[b.site.loop];
      b.s = std::clamp(b.s, kCornerInset, 1.0 - kCornerInset);
      b.position = lerp(loop[b.site.index], loop[(b.site.index + 1) % loop.size()], b.s);
    }
    const auto key = std::make_tuple(q.value, b.site.loop,
                                     std::llround((b.site.index + b.s) * 1e6));
    if (!seen.insert(key).second) continue;
    ++steps;
    const MedialAxis& ma = im.axes[q.index()];
    const std::optional<MaPoint> m = ma.project(b);
    if (!m) continue;
    out.radius = std::min(out.radius, m->radius);
    gradient_sum += im.gradient(q, *m);
    ++out.patches;
    if (!m->edge.valid()) continue;
    const MaEdge& e = ma.edge(m->edge);
    const double tol = kSamePointRel * im.part.size;
    const auto at = [&](MaVertexId v, bool end) {
      return ma.vertex(v).degree >= 3 &&
             (end || distance(m->position, ma.vertex(v).position) <= tol);
    };
    const bool at_branch = at(e.a, m->t <= kAtEndT) || at(e.b, m->t >= 1.0 - kAtEndT);
    if (at_branch) continue;
    const BoundaryPoint target = ma.touching_point(*m, ma.far_side(*m, b));
    if (target.site.kind != BoundarySite::Kind::Segment) continue;
    add_images(q, target);
  }
  if (out.patches == 0) {
    out.radius = 0.0;
    return out;
  }
  out.gradient = gradient_sum / out.patches;
  return out;
}

double TrackWidthLaw::width_for(double radius, double gradient) const {
  // Algorithm III, step 1: Delta theta_m = |1 - m| MAX_ANG_INCR when m <= 1, else 0.
  const double m = std::abs(gradient);
  const double incr = m <= 1.0 ? (1.0 - m) * kMaxAngIncrFraction * options_.dtheta : 0.0;
  const double w = radius * (options_.dtheta + incr);
  return std::clamp(w, end_width_, options_.max_size);
}

double TrackWidthLaw::width(PatchId p, const BoundaryPoint& bp) const {
  const RadiusSample r = radius(p, bp);
  return width_for(r.radius, r.gradient);
}

double TrackWidthLaw::width_on_edge(EdgeId e, double t) const {
  const auto& refs = impl_->index.segments_of(e);
  if (refs.empty()) return end_width_;
  return width(refs.front().patch, impl_->point_on(refs.front(), t));
}

}  // namespace laytracks
