// The medial axes of every patch of a part.
#pragma once

#include <functional>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/medial/medial_axis.hpp"

namespace laytracks {

/// Called after each patch: (patches done, patch count).
using ProgressFn = std::function<void(std::size_t, std::size_t)>;

/// The medial axis of each patch, in the patch's own 2D frame, indexed like Part::patches.
/// Uses the part's chord tolerance to recognise discretisation artefacts (see MedialOptions).
std::vector<MedialAxis> compute_medial_axes(const Part& part, const ProgressFn& progress = {});

}  // namespace laytracks
