// The quality of one quad, exactly as ../shared/spec/quality.md defines it: skew, aspect ratio,
// taper, warp, interior angles, scaled Jacobian and edge ratio, and whether it is inverted.
#pragma once

#include <array>

#include "laytracks/brep/geometry.hpp"

namespace laytracks {

/// Every measure of quality.md for one quad. Angles are in degrees.
struct QuadQuality {
  double skew_deg = 0.0;         ///< 90 minus the acute angle between the midlines; ideal 0
  double aspect_ratio = 1.0;     ///< max(|d1|,|d2|) / min(|d1|,|d2|); ideal 1
  double taper = 1.0;            ///< min(Ai) / mean(Ai) over the corner triangles; ideal 1
  double warp_deg = 0.0;         ///< largest fold angle across a diagonal; ideal 0
  double min_angle_deg = 90.0;   ///< smallest interior angle; ideal 90
  double max_angle_deg = 90.0;   ///< largest interior angle; ideal 90
  double scaled_jacobian = 1.0;  ///< min over corners of Ai / (1/2 |a| |b|); ideal 1
  double edge_ratio = 1.0;       ///< longest edge / shortest edge; ideal 1
  /// Inverted or degenerate: the scaled Jacobian is <= 0 at some corner (a corner of 180
  /// degrees or more, a zero-length edge), or a coordinate is not finite.
  bool inverted = false;
};

/// The 'bad' thresholds of quality.md (the NASTRAN-style flags). A quad is bad for a measure
/// when its value is on the far side of the threshold, the threshold itself included, except
/// for the angles, where 45 and 135 degrees are still good.
struct QualityThresholds {
  static constexpr double kSkewDeg = 30.0;        ///< bad when >= 30
  static constexpr double kAspectRatio = 5.0;     ///< bad when >= 5
  static constexpr double kTaper = 0.8;           ///< bad when <= 0.8
  static constexpr double kWarpDeg = 10.0;        ///< bad when >= 10
  static constexpr double kMinAngleDeg = 45.0;    ///< bad when < 45
  static constexpr double kMaxAngleDeg = 135.0;   ///< bad when > 135
  static constexpr double kScaledJacobian = 0.2;  ///< bad when <= 0.2
  static constexpr double kEdgeRatio = 5.0;       ///< bad when >= 5
};

/// Measures the quad with corners P1..P4 = corners[0..3] lying on a patch of unit normal
/// `normal` (normalised here if it is not; it must not be zero).
///
/// As quality.md says, the corners are first projected onto the plane through their centroid
/// with that normal, and every measure but warp is taken on the projected corners; warp is
/// taken on the corners as given (after the projection it would always be 0). Corner triangle
/// i is (P(i-1), Pi, P(i+1)); its area Ai = 1/2 n . ((P(i+1) - Pi) x (P(i-1) - Pi)) is positive
/// when the quad turns counter-clockwise about n at Pi. The interior angle at Pi is measured
/// counter-clockwise about n from P(i+1) - Pi to P(i-1) - Pi, in [0, 360): above 180 at a
/// reflex corner, and 270 everywhere for a quad that runs clockwise.
///
/// Degenerate cases, where quality.md's formulas divide by zero, get the worst value:
/// - a zero-length edge: its two corners have scaled Jacobian 0 and interior angle 0;
/// - a zero-length midline: skew 90 and aspect ratio +inf;
/// - a zero-length shortest edge: edge ratio +inf;
/// - mean(Ai) <= 0 (no area, or the quad turned inside out): taper -inf;
/// - a zero-area triangle beside a diagonal: that diagonal gives warp 0.
/// A planar quad that is concave has a diagonal outside it, across which the two triangles
/// face opposite ways: its warp is 180 (it is inverted anyway).
/// Invariant under rotation (of corners and normal together), translation and scaling.
QuadQuality measure_quad(const std::array<Vec3, 4>& corners, Vec3 normal);

/// measure_quad of the quad a, b, c, d (counter-clockwise) in a patch's plane (its frame).
QuadQuality measure_planar_quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

/// Whether a quad is beyond a threshold that the paper's Table III counts: taper, skew or
/// aspect ratio.
bool beyond_table_iii(const QuadQuality& m);

}  // namespace laytracks
