// A picture of a quad mesh: elements coloured by their scaled Jacobian (or another measure of
// quality.md), patch boundaries bold.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// How the picture lays the part out.
enum class MeshView {
  kUnfolded,  ///< one panel per patch, in the patch's own plane (Patch::frame)
  kOblique,   ///< the whole part seen from the front right, above (ObliqueCamera)
};

/// What the elements' colours show: one value per element of a quality.md measure, and how
/// to read it. The colour ramp runs from `worst` (dark blue) to `ideal` (yellow), values
/// beyond either end drawn as that end; the bar below the picture marks `bad` (quality.md's
/// threshold, in red) and the element farthest from ideal.
struct MeshColouring {
  std::string name;           ///< as the legend says it: "scaled Jacobian", "taper", ...
  std::vector<double> value;  ///< one per element (non-finite: drawn as `worst`)
  double worst = 0.0;         ///< the value drawn dark blue
  double ideal = 1.0;         ///< the value drawn yellow
  double bad = 0.2;           ///< quality.md's threshold
  const char* bad_when = "<=";  ///< bad at or beyond `bad` on the worst side: "<=" or ">="
};

/// The names colour_by knows, in the order the help lists them.
const std::vector<std::string>& colour_measures();

/// The colouring by one measure of quality.md: "jacobian" (scaled Jacobian, 0 to 1, bad <=
/// 0.2), "taper" (0 to 1, bad <= 0.8), "skew" (90 to 0 degrees, bad >= 30), "aspect" (10 to 1,
/// bad >= 5) or "edge-ratio" (10 to 1, bad >= 5), each element measured as quality.md says on
/// its patch's normal. Throws laytracks::Error for another name.
MeshColouring colour_by(const std::string& measure, const Part& part, const QuadMesh& mesh);

/// Writes an SVG picture of `mesh` of `part`. Every element is one <polygon>, outlined in dark
/// grey and filled with ramp_colour of where its value lies between `colouring.worst` (0: dark
/// blue) and `colouring.ideal` (1: yellow), clamped; nothing else in the picture is a
/// <polygon> (patch boundaries are bold black <polyline>s, the legend is <rect>s and <text>).
/// Unfolded: the elements of each patch in its panel, in element order, panels laid out as
/// write_rails_svg lays them. Oblique: patches drawn far to near by the depth of their frame
/// origins, as write_rails_oblique_svg, each patch's elements in element order and then its
/// boundary. Below the picture, the colour bar with the 'bad' threshold (quality.md) and the
/// element farthest from ideal marked, and the element and node counts. Deterministic.
/// Throws laytracks::Error when `colouring` has not one value per element, or an element
/// refers to a missing node or patch.
void write_mesh_svg(std::ostream& out,
                    const Part& part,
                    const QuadMesh& mesh,
                    const MeshColouring& colouring,
                    MeshView view);

}  // namespace laytracks
