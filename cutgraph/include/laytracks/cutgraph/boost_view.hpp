// The CUT-GRAPH as a Boost.Graph: a bipartite graph whose vertices are the G-CUT-VERTs (on the
// boundary, across patches) and the MA-CUT-VERTs (on each patch's axis), joined by one edge per
// rail segment. Walking it follows a rail across patches and along a corridor.
#pragma once

#include <boost/graph/adjacency_list.hpp>

#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks {

struct CutGraphNode {
  bool on_axis = false;     ///< an MA-CUT-VERT (else a G-CUT-VERT)
  std::uint32_t index = 0;  ///< into CutGraph::macuts or CutGraph::gverts
};

struct CutGraphArc {
  PatchId patch;              ///< the patch the rail segment lies in
  std::uint32_t segment = 0;  ///< into CutGraph::segments
};

using CutGraphBoost =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, CutGraphNode, CutGraphArc>;

/// Vertices 0 .. gverts.size()-1 are the G-CUT-VERTs, then the MA-CUT-VERTs.
CutGraphBoost to_boost_graph(const CutGraph& graph);

/// True when no edge joins two vertices of the same kind (boost::is_bipartite on the graph,
/// with the colouring checked against the kinds).
bool is_bipartite_by_kind(const CutGraphBoost& g);

}  // namespace laytracks
