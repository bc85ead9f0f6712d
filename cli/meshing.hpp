// What the commands that mesh a part share (mesh, batch, draw --stage mesh): the options
// --size, --smooth and --chord-tol, reading and building the part, and writing the mesh with
// its per-element scaled Jacobian. One place, so that every command meshes a part the same way.
#pragma once

#include <string>
#include <vector>

#include "args.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks::cli {

/// The options of a meshing command.
struct MeshingOptions {
  BuildOptions build;    ///< --chord-tol T (default: the part's own, see BuildOptions)
  MeshPartOptions mesh;  ///< --size W (default: mesh.size, else 1/40 of the part's size) and
                         ///< --smooth N (default kDefaultSmooth)
};

/// Reads --size, --smooth and --chord-tol from `args`, which must declare them as options with
/// a value. Throws UsageError for a value out of range.
MeshingOptions meshing_options(const Args& args);

/// Reads the part file and builds the part: throws InputError (message with the place) when
/// it cannot be read or breaks a rule of brep-json.md.
Part read_part(const std::string& path, const BuildOptions& options);

/// The scaled Jacobian of every element of `mesh` (measure_quad with its patch's normal), in
/// element order. Every element must be a quad of a patch of `part`, as mesh_part makes them.
std::vector<double> element_scaled_jacobians(const Part& part, const QuadMesh& mesh);

/// write_mesh(path, part, mesh) with the scaled Jacobians as the quality field (only .vtu
/// stores it). Atomic; throws laytracks::Error when the file cannot be written.
void write_part_mesh(const std::string& path, const Part& part, const QuadMesh& mesh);

}  // namespace laytracks::cli
