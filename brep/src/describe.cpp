#include "describe.hpp"

#include <cmath>
#include <cstdio>

#include "laytracks/brep/error.hpp"

namespace laytracks::detail {

std::string num(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  std::string text = buffer;
  if (text.find_first_of(".en") == std::string::npos) text += ".0";  // 4 -> 4.0; not inf/nan
  return text;
}

std::string len(const BuildState& s, double value) { return num(value, 3) + " " + s.raw.units; }

std::string point(Vec3 p, double scale) {
  const auto clean = [scale](double c) { return std::fabs(c) < 1e-12 * scale ? 0.0 : c; };
  return "(" + num(clean(p.x)) + ", " + num(clean(p.y)) + ", " + num(clean(p.z)) + ")";
}

std::string patch_name(const BuildState& s, std::size_t patch) {
  return s.part.patch_label(PatchId(patch));
}

std::string loop_name(std::size_t loop) {
  return loop == 0 ? "the outer loop" : "loop " + std::to_string(loop) + " (a hole)";
}

std::string arc_name(const BuildState& s, std::size_t arc) {
  const RawArc& a = s.raw.arcs[arc];
  return "arc " + std::to_string(arc) + " (edge " + std::to_string(a.from) + "-" +
         std::to_string(a.to) + ")";
}

std::string vertex_name(const BuildState& s, VertexId v) {
  if (v.index() < s.file_vertex_count()) return "vertex " + std::to_string(v.index());
  const auto& [arc, k] = s.arc_point_of[v.index() - s.file_vertex_count()];
  return "point " + std::to_string(k) + " of " + arc_name(s, arc);
}

std::string edge_name(const BuildState& s, VertexId a, VertexId b) {
  const std::size_t n = s.file_vertex_count();
  if (a.index() < n && b.index() < n) {
    return "edge " + std::to_string(a.index()) + "-" + std::to_string(b.index());
  }
  const VertexId p = a.index() >= n ? a : b;
  return "a segment of " + arc_name(s, s.arc_point_of[p.index() - n].first);
}

void fail(const std::string& message) { throw InputError(message); }

}  // namespace laytracks::detail
