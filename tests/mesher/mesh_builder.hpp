// Structured grid meshes for the mesher tests: each patch whose boundary is one quadrilateral
// loop is meshed by bilinear mapping of a grid, nodes shared between patches along shared
// edges (found by exact 3D position: edge points are computed symmetrically in their ends).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks::test {

/// The grid of one patch: nu divisions from loop corner 0 to 1, nv from corner 0 to 3.
struct PatchGrid {
  int nu = 0;
  int nv = 0;
  std::vector<std::uint32_t> nodes;  ///< node id of grid point (i, j) at i * (nv + 1) + j
  std::size_t first_element = 0;     ///< quad (i, j) is element first_element + i * nv + j

  std::uint32_t node(int i, int j) const {
    return nodes[static_cast<std::size_t>(i * (nv + 1) + j)];
  }
  std::size_t element(int i, int j) const {
    return first_element + static_cast<std::size_t>(i * nv + j);
  }
};

struct GridMesh {
  QuadMesh mesh;
  std::vector<PatchGrid> grids;  ///< one per patch
};

/// Meshes every patch of `part` (each must have a single loop of 4 vertices) with quads of
/// about size h: nu = round(|P1 - P0| / h), nv = round(|P3 - P0| / h), at least 1, unless
/// `divisions` gives (nu, nv) for the patch. Quads turn counter-clockwise about the patch
/// normal (the loop order). Throws std::invalid_argument for another kind of patch.
GridMesh grid_mesh(const Part& part,
                   double h,
                   const std::map<std::size_t, std::pair<int, int>>& divisions = {});

}  // namespace laytracks::test
