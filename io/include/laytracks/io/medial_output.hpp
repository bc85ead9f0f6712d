// Writing the medial axes of a part: JSON (for tools) and SVG (for people).
#pragma once

#include <ostream>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks {

/// {"patches":[{"name":..,"vertices":[{"xyz":[x,y,z],"radius":r,"degree":d},..],
///   "edges":[[i,j],..]}]}, coordinates in the part's 3D frame. Deterministic.
void write_medial_json(std::ostream& out, const Part& part, const std::vector<MedialAxis>& axes);

/// One panel per patch, in the patch's own plane: the boundary, the axis coloured by radius,
/// branch points marked, and a legend.
void write_medial_svg(std::ostream& out, const Part& part, const std::vector<MedialAxis>& axes);

}  // namespace laytracks
