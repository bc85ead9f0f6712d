// A picture of a quad mesh: elements coloured by their scaled Jacobian, patch boundaries bold.
#pragma once

#include <ostream>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// How the picture lays the part out.
enum class MeshView {
  kUnfolded,  ///< one panel per patch, in the patch's own plane (Patch::frame)
  kOblique,   ///< the whole part seen from the front right, above (ObliqueCamera)
};

/// Writes an SVG picture of `mesh` of `part`. Every element is one <polygon>, outlined in dark
/// grey and filled with ramp_colour(its scaled Jacobian clamped to [0, 1]): dark blue for 0,
/// yellow for 1; nothing else in the picture is a <polygon> (patch boundaries are bold black
/// <polyline>s, the legend is <rect>s and <text>). Unfolded: the elements of each patch in its
/// panel, in element order, panels laid out as write_rails_svg lays them. Oblique: patches
/// drawn far to near by the depth of their frame origins, as write_rails_oblique_svg, each
/// patch's elements in element order and then its boundary. Below the picture, a colour bar
/// for the scaled Jacobian from 0 to 1, the 'bad' threshold (0.2, quality.md) and the smallest
/// value marked, and the element and node counts.
/// `scaled_jacobian[i]` is element i's value (non-finite values are drawn as 0). Deterministic.
/// Throws laytracks::Error when `scaled_jacobian` is not one value per element, or an element
/// refers to a missing node or patch.
void write_mesh_svg(std::ostream& out,
                    const Part& part,
                    const QuadMesh& mesh,
                    const std::vector<double>& scaled_jacobian,
                    MeshView view);

}  // namespace laytracks
