// build_part(): the validation pipeline. Each step checks one group of rules of
// ../shared/spec/brep-json.md (see build_state.hpp) and throws InputError on the first violation.
#include "laytracks/brep/build.hpp"

#include "build_state.hpp"

namespace laytracks {

Part build_part(const RawPart& raw, const BuildOptions& options) {
  detail::BuildState s(raw);
  detail::init_part(s);
  detail::check_input(s, options);
  detail::check_patch_names(s);
  detail::measure_part(s);
  detail::check_loops(s);
  detail::build_arcs(s, options);
  detail::fit_planes(s);
  detail::check_polygons(s);
  detail::shape_polygons(s);
  detail::build_edges(s);
  detail::check_vertices_on_edges(s);
  detail::check_patch_contacts(s);
  detail::check_dual_graph_and_shells(s);
  return std::move(s.part);
}

}  // namespace laytracks
