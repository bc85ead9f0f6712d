// Pictures of the rails: corridors or tracks shaded, rails drawn, one panel per patch.
#pragma once

#include <ostream>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks {

/// One panel per patch, in its own plane (the part unfolded patch by patch): each CUT-SEG's
/// region shaded in its corridor's colour, the medial axis in grey, source rails in red and
/// track rails in blue. `title` names the stage.
void write_rails_svg(std::ostream& out,
                     const Part& part,
                     const std::vector<MedialAxis>& axes,
                     const CutGraph& graph,
                     const std::string& title);

/// The whole part in an oblique view (seen from the front-right, above): each patch drawn far
/// to near with its CUT-SEG regions shaded and its rails, so a shell reads as one object.
void write_rails_oblique_svg(std::ostream& out,
                             const Part& part,
                             const std::vector<MedialAxis>& axes,
                             const CutGraph& graph,
                             const std::string& title);

}  // namespace laytracks
