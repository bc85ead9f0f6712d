#include "laytracks/medial/part_medial.hpp"

#include <algorithm>
#include <cmath>

#include "laytracks/brep/error.hpp"

namespace laytracks {

std::vector<MedialAxis> compute_medial_axes(const Part& part, const ProgressFn& progress) {
  std::vector<MedialAxis> axes;
  axes.reserve(part.patches.size());
  MedialOptions options;
  options.chord_tol = part.chord_tol;
  for (std::size_t i = 0; i < part.patches.size(); ++i) {
    // The rounding of the corners' coordinates as given (MedialOptions::coordinate_scale).
    options.coordinate_scale = 0.0;
    for (const Loop& loop : part.patches[i].loops)
      for (const VertexId v : loop.vertices) {
        const Vec3 x = part.vertices[v.index()].position;
        options.coordinate_scale =
            std::max({options.coordinate_scale, std::fabs(x.x), std::fabs(x.y), std::fabs(x.z)});
      }
    try {
      axes.push_back(compute_medial_axis(part.patches[i].polygon, options));
    } catch (const InternalError& e) {
      throw InternalError(part.patch_label(PatchId(i)) + ": " + e.what());
    }
    if (progress) progress(i + 1, part.patches.size());
  }
  return axes;
}

}  // namespace laytracks
