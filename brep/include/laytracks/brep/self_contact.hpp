// Where a patch's boundary comes closest to itself away from its corners: the diagnosis the
// mesher gives when it cannot mesh a part whose outline folds back within a hair of itself.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "laytracks/brep/part.hpp"

namespace laytracks {

/// A vertex of a patch's boundary near a segment of the same patch's boundary.
struct SelfContact {
  PatchId patch;
  std::uint32_t loop = 0, vertex = 0;   ///< the vertex: its loop, its place in the loop
  std::uint32_t seg_loop = 0, seg = 0;  ///< the segment from place seg to seg + 1 of seg_loop
  double distance = 0.0;                ///< in the part's units (in the patch's frame)
};

/// The closest vertex-segment pair of one patch's polygon (arc points included) at most
/// `within` apart, over all patches; none when there is none. Not counted as contacts: on one
/// loop, the segments at the vertex and at its two neighbours (the two sides of a needle's tip
/// are close by nature). Ties go to the first patch, loop, vertex and segment.
std::optional<SelfContact> closest_self_contact(const Part& part, double within);

/// `patch "p0" (index 0): its boundary comes within 1.5e-06 mm (6.3e-09 x the part's size) of
/// itself: vertex 60 at (x, y, z) and the segment from vertex 57 to vertex 58 (the outer
/// loop)`.
std::string describe(const Part& part, const SelfContact& contact);

}  // namespace laytracks
