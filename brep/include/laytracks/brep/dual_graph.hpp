// The dual graph of a part: patches are vertices, with one graph edge per shared B-Rep edge and
// patch pair. Shells are its connected components.
#pragma once

#include <boost/graph/adjacency_list.hpp>

#include "laytracks/brep/part.hpp"

namespace laytracks {

struct DualEdge {
  EdgeId edge;  ///< the B-Rep edge the two patches share
};

/// Vertex i is patch i.
using DualGraph = boost::
    adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property, DualEdge>;

DualGraph build_dual_graph(const Part& part);

/// Shell id of every patch (connected components of the dual graph, numbered by their lowest
/// patch index) and the number of shells.
std::vector<std::size_t> shells_of(const DualGraph& graph, std::size_t& count);

}  // namespace laytracks
