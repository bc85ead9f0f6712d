#include "laytracks/cutgraph/boost_view.hpp"

#include <boost/graph/bipartite.hpp>

namespace laytracks {

CutGraphBoost to_boost_graph(const CutGraph& graph) {
  const std::size_t ng = graph.gverts.size();
  CutGraphBoost g(ng + graph.macuts.size());
  for (std::size_t i = 0; i < ng; ++i) g[i] = {false, static_cast<std::uint32_t>(i)};
  for (std::size_t i = 0; i < graph.macuts.size(); ++i) {
    g[ng + i] = {true, static_cast<std::uint32_t>(i)};
  }
  for (std::size_t s = 0; s < graph.segments.size(); ++s) {
    const RailSegment& seg = graph.segments[s];
    const CutVert& c = graph.cuts[seg.cut.index()];
    boost::add_edge(c.g.index(), ng + seg.ma.index(),
                    CutGraphArc{c.patch, static_cast<std::uint32_t>(s)}, g);
  }
  return g;
}

bool is_bipartite_by_kind(const CutGraphBoost& g) {
  for (auto [e, end] = boost::edges(g); e != end; ++e) {
    if (g[boost::source(*e, g)].on_axis == g[boost::target(*e, g)].on_axis) return false;
  }
  return boost::is_bipartite(g);
}

}  // namespace laytracks
