// The part exactly as the input file states it, before any validation of geometry.
// io/ fills it from JSON (type errors are its job); brep/ validates it and builds a Part.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks {

struct RawArc {
  std::int64_t from = -1;  ///< vertex index, as given (range checked by brep)
  std::int64_t to = -1;
  Vec3 via;
};

struct RawPatch {
  std::optional<std::string> name;               ///< absent: "patch<i>"
  std::vector<std::vector<std::int64_t>> loops;  ///< vertex indices as given; loop 0 is outer
};

enum class MeshMode { Uniform, Adaptive };

/// Meshing parameters found in the file's "mesh" object; absent keys stay empty.
struct RawMeshParams {
  std::optional<double> size;
  std::optional<MeshMode> mode;
  std::optional<double> dtheta_deg;
};

struct RawPart {
  std::string source = "<memory>";  ///< file name used in messages
  std::string units = "mm";
  std::vector<Vec3> vertices;
  std::vector<RawPatch> patches;
  std::vector<RawArc> arcs;
  std::optional<std::vector<std::array<std::int64_t, 2>>> dual_graph;
  RawMeshParams mesh;
};

}  // namespace laytracks
