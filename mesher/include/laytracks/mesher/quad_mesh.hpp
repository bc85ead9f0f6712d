// The mesh of a part: plain arrays, shared node ids per shell, each element tagged with its
// patch and shell. Every stage after the mesher (checker, quality report, writers) reads this.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks {

struct MeshElement {
  /// Node ids, counter-clockwise about the patch normal (right-hand rule on the patch's outer
  /// loop as the file gives it). A quad uses all four; a triangle sets nodes[3] = kNoNode.
  std::array<std::uint32_t, 4> nodes{};
  PatchId patch;
  std::uint32_t shell = 0;

  static constexpr std::uint32_t kNoNode = 0xffffffffu;
  bool is_quad() const { return nodes[3] != kNoNode; }
};

struct QuadMesh {
  std::vector<Vec3> nodes;
  /// Quads, and triangles only when the mesh came from elsewhere (a Gmsh mesh being rated):
  /// our mesher never outputs a triangle.
  std::vector<MeshElement> elements;
};

}  // namespace laytracks
