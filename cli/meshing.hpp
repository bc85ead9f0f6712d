// What the commands that mesh a part share (mesh, batch, draw --stage mesh): the options
// --size, --smooth and --chord-tol, reading and building the part, and writing the mesh with
// its per-element scaled Jacobian. One place, so that every command meshes a part the same way.
#pragma once

#include <set>
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

/// Parses a meshing command's arguments: its own options (`with_value`, `flags`) and the
/// meshing options every such command takes (--size, --smooth, --chord-tol, --adaptive,
/// --uniform, --dtheta, --min-size, --max-size).
Args meshing_args(const std::vector<std::string>& argv,
                  std::set<std::string> with_value,
                  std::set<std::string> flags);

/// The help lines of those options, shared by every meshing command's help text (a literal,
/// so that each help is one string literal).
#define LAYTRACKS_MESHING_OPTIONS_HELP                                                           \
  "  --size W         element size of uniform mode, which it implies (default: the part's\n"     \
  "                   mesh.size, else 1/40 of the part's extent: the larger of its size\n"       \
  "                   and twice the largest distance of a vertex or arc point from their\n"      \
  "                   centroid); a size above 1/4 of the extent is lowered to 1/4 (with a\n"     \
  "                   note; if no valid mesh comes there, to 0.8, 0.64, 0.5 of that); at\n"      \
  "                   any other size that gives no valid mesh, 0.9 to 0.4 of it (with\n"         \
  "                   a note saying why; not where the outline folds back on itself); a\n"       \
  "                   size that would give more than 5e7 quads (area / W^2) is refused\n"        \
  "  --adaptive       adaptive mode (also the part's mesh.mode \"adaptive\"): tracks as\n"       \
  "                   wide as the medial radius R x dtheta, fine where the part is thin\n"       \
  "  --uniform        uniform mode, whatever the part's mesh.mode says\n"                        \
  "  --dtheta DEG     adaptive: angular increment (default: the part's mesh.dtheta_deg,\n"       \
  "                   else 15); smaller is finer\n"                                              \
  "  --min-size S     adaptive: no track narrower than S (default: the paper's MIN_END_WIDTH,\n" \
  "                   3% of the largest medial radius at dtheta 15, in proportion to dtheta)\n"  \
  "  --max-size S     adaptive: no track wider than S (default: no bound)\n"                     \
  "  --smooth N       up to N sweeps of each: Laplacian, angle optimisation, untangling\n"       \
  "                   of the worst quads, and untapering (nodes towards parallelograms);\n"      \
  "                   never inverting an element (default 10; 0 keeps the nodes where\n"         \
  "                   the templates put them; the cavity re-fill relaxes its quads with\n"       \
  "                   min(N, 4) sweeps)\n"                                                       \
  "  --chord-tol T    sagitta bound for arcs (default 1e-3 x the part's size)\n"

/// Reads --size, --smooth, --chord-tol, --adaptive, --uniform, --dtheta, --min-size and
/// --max-size from
/// `args`, which must declare them (meshing_args does). Throws UsageError
/// for a value out of range or for options that do not go together.
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
