// Private to brep: the wording of error messages (numbers, points, vertices, edges, loops).
#pragma once

#include <cstdint>
#include <string>

#include "build_state.hpp"

namespace laytracks::detail {

/// A number with `digits` significant digits, always showing it is real: 4 -> "4.0".
std::string num(double value, int digits = 6);
/// A length with 3 significant digits and the part's units: "0.31 mm".
std::string len(const BuildState& s, double value);
/// "(39.2, 4.0, 0.0)"; coordinates below 1e-12 x `scale` in magnitude (rounding noise of a
/// computed point) are shown as 0.
std::string point(Vec3 p, double scale = 0.0);
/// `patch "wall" (index 1)`
std::string patch_name(const BuildState& s, std::size_t patch);
/// "the outer loop" or "loop 2 (a hole)"
std::string loop_name(std::size_t loop);
/// "arc 2 (edge 6-7)"
std::string arc_name(const BuildState& s, std::size_t arc);
/// "vertex 5" for a file vertex, "point 3 of arc 2 (edge 6-7)" for an arc point.
std::string vertex_name(const BuildState& s, VertexId v);
/// "edge 3-4" between file vertices, "a segment of arc 2 (edge 6-7)" inside an arc.
std::string edge_name(const BuildState& s, VertexId a, VertexId b);
/// Throws InputError(message).
[[noreturn]] void fail(const std::string& message);

}  // namespace laytracks::detail
