// Rules 1-2 of build_part(): the input's numbers and indices, patch names, the part's size.
#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "build_state.hpp"
#include "describe.hpp"

namespace laytracks::detail {
namespace {

/// Refuses a point that is not finite or beyond Tolerances::kMaxCoordinate; `what` names it.
void check_coordinates(Vec3 p, const std::string& what) {
  if (!is_finite(p)) fail(what + " has a coordinate that is not a finite number");
  const double m = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  if (m > Tolerances::kMaxCoordinate) {
    fail(what + " " + point(p) + " is beyond the largest accepted coordinate magnitude " +
         num(Tolerances::kMaxCoordinate));
  }
}

/// Refuses a vertex index outside [0, count); `where` says who refers to it.
void check_vertex_index(std::int64_t v, std::size_t count, const std::string& where) {
  if (v < 0) fail(where + " refers to vertex " + std::to_string(v) + "; indices start at 0");
  if (static_cast<std::uint64_t>(v) >= count) {
    fail(where + " refers to vertex " + std::to_string(v) + ", but the part has only " +
         std::to_string(count) + " vertices");
  }
}

/// Refuses an optional parameter that is given but not a finite number > 0.
void check_positive(const std::optional<double>& value, const std::string& what) {
  if (value && !(std::isfinite(*value) && *value > 0.0)) {
    fail(what + " must be a finite number > 0, not " + num(*value));
  }
}

/// Rule 1 for the patches' loops.
void check_patch_indices(const BuildState& s) {
  if (s.raw.patches.empty()) fail("the part has no patches");
  for (std::size_t p = 0; p < s.raw.patches.size(); ++p) {
    const auto& loops = s.raw.patches[p].loops;
    if (loops.empty()) fail(patch_name(s, p) + " has no loops");
    for (std::size_t l = 0; l < loops.size(); ++l) {
      for (std::int64_t v : loops[l]) {
        check_vertex_index(v, s.raw.vertices.size(), patch_name(s, p) + ": " + loop_name(l));
      }
    }
  }
}

/// Rule 1 for arcs and the dual graph.
void check_arc_and_graph_indices(const BuildState& s) {
  for (std::size_t a = 0; a < s.raw.arcs.size(); ++a) {
    const RawArc& arc = s.raw.arcs[a];
    check_vertex_index(arc.from, s.raw.vertices.size(), "arc " + std::to_string(a));
    check_vertex_index(arc.to, s.raw.vertices.size(), "arc " + std::to_string(a));
    check_coordinates(arc.via, "the via point of arc " + std::to_string(a));
  }
  if (!s.raw.dual_graph) return;
  const auto& graph = *s.raw.dual_graph;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    for (std::int64_t p : graph[i]) {
      if (p < 0 || static_cast<std::uint64_t>(p) >= s.raw.patches.size()) {
        fail("dual_graph entry " + std::to_string(i) + " refers to patch " + std::to_string(p) +
             ", but the part has patches 0 to " + std::to_string(s.raw.patches.size() - 1));
      }
    }
    if (graph[i][0] == graph[i][1]) {
      fail("dual_graph entry " + std::to_string(i) + " lists patch " + std::to_string(graph[i][0]) +
           " as its own neighbour");
    }
  }
}

}  // namespace

void init_part(BuildState& s) {
  Part& part = s.part;
  part.source = s.raw.source;
  part.units = s.raw.units;
  part.vertices.reserve(s.raw.vertices.size());
  for (std::size_t i = 0; i < s.raw.vertices.size(); ++i) {
    part.vertices.push_back({s.raw.vertices[i], static_cast<std::int64_t>(i), false});
  }
  part.patches.resize(s.raw.patches.size());
  for (std::size_t p = 0; p < s.raw.patches.size(); ++p) {
    const auto& name = s.raw.patches[p].name;
    part.patches[p].name = name ? *name : "patch" + std::to_string(p);
  }
  part.mesh.size = s.raw.mesh.size;
  part.mesh.mode = s.raw.mesh.mode.value_or(MeshMode::Uniform);
  part.mesh.dtheta_deg = s.raw.mesh.dtheta_deg;
}

void check_input(const BuildState& s, const BuildOptions& options) {
  for (std::size_t i = 0; i < s.raw.vertices.size(); ++i) {
    check_coordinates(s.raw.vertices[i], "vertex " + std::to_string(i));
  }
  check_patch_indices(s);
  check_arc_and_graph_indices(s);
  check_positive(s.raw.mesh.size, "mesh size");
  check_positive(s.raw.mesh.dtheta_deg, "mesh dtheta_deg");
  check_positive(options.chord_tol, "the chord tolerance");
}

void check_patch_names(const BuildState& s) {
  std::unordered_map<std::string, std::size_t> first_with;
  for (std::size_t p = 0; p < s.part.patches.size(); ++p) {
    const auto [it, inserted] = first_with.emplace(s.part.patches[p].name, p);
    if (inserted) continue;
    const auto given = [&](std::size_t i) {
      return s.raw.patches[i].name ? std::string("given") : std::string("default");
    };
    fail("patches " + std::to_string(it->second) + " and " + std::to_string(p) +
         " have the same name \"" + s.part.patches[p].name + "\" (" + given(it->second) + " and " +
         given(p) + " name); patch names must be unique");
  }
}

void measure_part(BuildState& s) {
  s.used.assign(s.raw.vertices.size(), 0);
  for (const RawPatch& patch : s.raw.patches) {
    for (const auto& loop : patch.loops) {
      for (std::int64_t v : loop) s.used[static_cast<std::size_t>(v)] = 1;
    }
  }
  Box3 box;
  double largest = 0.0;
  std::vector<std::size_t> unused;
  for (std::size_t i = 0; i < s.raw.vertices.size(); ++i) {
    const Vec3 p = s.raw.vertices[i];
    if (!s.used[i]) {
      unused.push_back(i);
      continue;
    }
    box.add(p);
    largest = std::max({largest, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  }
  s.part.bbox = box;
  // The size is the diameter of the smallest ball about the vertices' centroid that holds
  // them all: unlike a box diagonal it does not change when the part is turned, so neither do
  // the tolerances and the arc discretisation derived from it.
  Vec3 centroid;
  std::size_t count = 0;
  for (std::size_t i = 0; i < s.raw.vertices.size(); ++i) {
    if (!s.used[i]) continue;
    centroid = centroid + s.raw.vertices[i];
    ++count;
  }
  centroid = (1.0 / static_cast<double>(std::max<std::size_t>(count, 1))) * centroid;
  double radius = 0.0;
  for (std::size_t i = 0; i < s.raw.vertices.size(); ++i) {
    if (s.used[i]) radius = std::max(radius, distance(s.raw.vertices[i], centroid));
  }
  s.part.size = 2.0 * radius;
  if (!(s.part.size > 0.0)) {
    if (box.lo.x == box.hi.x && box.lo.y == box.hi.y && box.lo.z == box.hi.z)
      fail("the part has zero size: all its vertices are at " + point(box.lo));
    // Distinct vertices whose distances underflow (a part drawn in units of 1e-300).
    fail("the part is too small to measure: its vertices lie in a box of " +
         num(box.hi.x - box.lo.x) + " x " + num(box.hi.y - box.lo.y) + " x " +
         num(box.hi.z - box.lo.z) + " " + s.raw.units +
         ", whose distances underflow double precision");
  }
  if (s.part.size < Tolerances::kMinRelativeSize * largest) {
    fail("the part is too small for where it is: its size " + len(s, s.part.size) + " is below " +
         num(Tolerances::kMinRelativeSize) + " x its largest coordinate " + len(s, largest) +
         ", beyond what double precision resolves");
  }
  if (unused.empty()) return;
  std::string list;
  for (std::size_t k = 0; k < unused.size() && k < 10; ++k) {
    list += (k ? ", " : "") + std::to_string(unused[k]);
  }
  if (unused.size() > 10) list += " and " + std::to_string(unused.size() - 10) + " more";
  s.part.warnings.push_back((unused.size() == 1 ? "vertex " : "vertices ") + list +
                            (unused.size() == 1 ? " is" : " are") + " not used by any patch");
}

}  // namespace laytracks::detail
