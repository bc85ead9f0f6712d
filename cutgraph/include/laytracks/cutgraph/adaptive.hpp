// Adaptive mode (paper 4.2.4, Algorithm III): track widths from the radius function,
// Delta S = R x Delta theta, across the patches a corridor spans. The rules are in
// docs/adaptive.md.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks {

/// Default angular increment Delta theta_in of adaptive mode, in degrees (docs/adaptive.md).
constexpr double kDefaultDthetaDeg = 15.0;
/// MAX_ANG_INCR as a fraction of Delta theta_in (the paper's 20%).
constexpr double kMaxAngIncrFraction = 0.2;
/// The paper's MIN_END_WIDTH: this fraction of the largest MA radius of the part, at the
/// default dtheta (in proportion to dtheta otherwise).
constexpr double kMinEndWidthFraction = 0.03;

struct AdaptiveOptions {
  double dtheta = 0.0;  ///< Delta theta_in, radians
  double min_size = 0.0;  ///< no track narrower (0: MIN_END_WIDTH)
  double max_size = std::numeric_limits<double>::infinity();  ///< no track wider
};

/// The radius function where a rail from a boundary point runs, over every patch it crosses.
struct RadiusSample {
  double radius = 0.0;    ///< the smallest radius over the patches
  double gradient = 0.0;  ///< |dR/ds| along the axis, averaged over the patches
  int patches = 0;        ///< how many patches the probe crossed
};

/// Track width as a function of the place on the boundary: Delta S = R (Delta theta_in +
/// Delta theta_m), Delta theta_m = (1 - |m|) MAX_ANG_INCR, clamped to [end width, max size].
class TrackWidthLaw {
 public:
  TrackWidthLaw(const Part& part, const std::vector<MedialAxis>& axes, const AdaptiveOptions& o);
  ~TrackWidthLaw();
  TrackWidthLaw(const TrackWidthLaw&) = delete;
  TrackWidthLaw& operator=(const TrackWidthLaw&) = delete;

  /// Radius and gradient at a boundary point of patch p (a segment point), following the rail
  /// from it into every patch it crosses (section 5: the smallest radius, the mean gradient).
  RadiusSample radius(PatchId p, const BoundaryPoint& bp) const;
  /// Delta S at a boundary point of patch p, over the patches its rail crosses.
  double width(PatchId p, const BoundaryPoint& bp) const;
  /// Delta S at parameter t of B-Rep edge e (from its vertex a to b).
  double width_on_edge(EdgeId e, double t) const;
  /// Delta S for a radius and gradient.
  double width_for(double radius, double gradient) const;
  /// MIN_END_WIDTH: the width of a track that ends at a convex corner (radius 0), and the
  /// floor of every width.
  double end_width() const { return end_width_; }
  double max_width() const { return options_.max_size; }
  const AdaptiveOptions& options() const { return options_; }
  /// The largest MA radius over the part's patches.
  double max_radius() const { return max_radius_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  AdaptiveOptions options_;
  double max_radius_ = 0.0;
  double end_width_ = 0.0;
};

}  // namespace laytracks
