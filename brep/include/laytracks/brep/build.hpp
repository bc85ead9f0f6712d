// Validation of a RawPart and construction of the Part model.
#pragma once

#include <optional>

#include "laytracks/brep/part.hpp"
#include "laytracks/brep/raw_part.hpp"

namespace laytracks {

/// Named tolerances. All lengths are relative to the part's size (Part::size, twice the radius
/// of the vertices about their centroid) or, for planarity, to the patch's bounding-box
/// diagonal, as the spec says.
struct Tolerances {
  /// Planarity: every vertex and arc point within this x patch diagonal of the best-fit plane.
  static constexpr double kPlanarity = 1e-6;
  /// Two distinct vertices closer than this x part size are refused (quality.md rule 5 needs
  /// nodes at least 1e-9 x size apart).
  static constexpr double kMinVertexDistance = 1e-9;
  /// A vertex closer than this x part size to the inside of another patch's edge "lies on" it.
  static constexpr double kOnEdge = 1e-9;
  /// Default sagitta bound for arc discretisation, x part size, when none is given.
  static constexpr double kDefaultChord = 1e-3;
  /// A joint is tangent-continuous (smooth) when its two edges turn by less than this (rad).
  static constexpr double kSmoothAngle = 1e-6;
  /// Coordinates beyond this magnitude are refused as absurd.
  static constexpr double kMaxCoordinate = 1e12;
  /// A part must be larger than this x its largest coordinate, or double precision cannot
  /// resolve it.
  static constexpr double kMinRelativeSize = 1e-9;
};

struct BuildOptions {
  /// Sagitta bound for arcs, in the part's units; default Tolerances::kDefaultChord x size.
  std::optional<double> chord_tol;
};

/// Validates every rule of ../shared/spec/brep-json.md and builds the part.
/// Throws InputError with a message naming what is wrong and where (patch name and index,
/// vertex index, coordinates). Never returns an invalid Part.
Part build_part(const RawPart& raw, const BuildOptions& options = {});

}  // namespace laytracks
