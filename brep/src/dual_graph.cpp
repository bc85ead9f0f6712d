#include "laytracks/brep/dual_graph.hpp"

#include <boost/graph/connected_components.hpp>
#include <limits>

namespace laytracks {

DualGraph build_dual_graph(const Part& part) {
  DualGraph graph(part.patches.size());
  for (std::size_t e = 0; e < part.edges.size(); ++e) {
    const auto& ps = part.edges[e].patches;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      for (std::size_t j = i + 1; j < ps.size(); ++j) {
        boost::add_edge(ps[i].index(), ps[j].index(), DualEdge{EdgeId(e)}, graph);
      }
    }
  }
  return graph;
}

std::vector<std::size_t> shells_of(const DualGraph& graph, std::size_t& count) {
  const std::size_t n = boost::num_vertices(graph);
  std::vector<std::size_t> component(n);
  if (n > 0) boost::connected_components(graph, component.data());
  // Renumber in order of each component's lowest patch index, whatever Boost's numbering.
  std::vector<std::size_t> renamed(n, std::numeric_limits<std::size_t>::max());
  count = 0;
  for (std::size_t p = 0; p < n; ++p) {
    std::size_t& r = renamed[component[p]];
    if (r == std::numeric_limits<std::size_t>::max()) r = count++;
    component[p] = r;
  }
  return component;
}

}  // namespace laytracks
