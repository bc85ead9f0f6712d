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
/// An MA point this close (in parameter) to an end of its edge is at that vertex: at a branch
/// point the probe stops, as a rail does.
constexpr double kAtEndT = 1e-9;

}  // namespace

struct TrackWidthLaw::Impl {
  const Part& part;
  const std::vector<MedialAxis>& axes;
  cutgraph_detail::BoundaryIndex index;

  Impl(const Part& p, const std::vector<MedialAxis>& a) : part(p), axes(a), index(p) {}

  /// |dR/ds| along the axis at m: exact for a line (R is linear in arc length), a central
  /// difference for a parabola. 0 where the axis is a single point.
  double gradient(PatchId p, const MaPoint& m) const {
    if (!m.edge.valid()) return 0.0;
    const MedialAxis& ma = axes[p.index()];
    const double t0 = std::max(0.0, m.t - kGradientStep);
    const double t1 = std::min(1.0, m.t + kGradientStep);
    const MaPoint a = ma.point_on_edge(m.edge, t0);
    const MaPoint b = ma.point_on_edge(m.edge, t1);
    const double ds = distance(a.position, b.position);
    if (!(ds > 0.0)) return 0.0;
    return std::min(1.0, std::abs(b.radius - a.radius) / ds);
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
  end_width_ = o.min_size > 0.0 ? o.min_size : kMinEndWidthFraction * max_radius_;
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
    const auto [q, b] = queue.front();
    queue.pop_front();
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
    const bool at_branch = (m->t <= kAtEndT && ma.vertex(e.a).degree >= 3) ||
                           (m->t >= 1.0 - kAtEndT && ma.vertex(e.b).degree >= 3);
    if (at_branch) continue;
    const Side other = e.left == b.site ? Side::Right : Side::Left;
    const BoundaryPoint target = ma.touching_point(*m, other);
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
