// Reading a Gmsh MSH 4.1 ASCII file: ours (to check round trips) or Gmsh's own (to rate it).
#pragma once

#include <string>
#include <vector>

#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// Reads the 2D elements of a Gmsh MSH 4.1 ASCII file.
/// - Nodes: every node of $Nodes (whatever entity holds it), in ascending tag order; node tags
///   may be sparse. Parametric coordinates, if any, are skipped.
/// - Elements: those of surface entities, 3-node triangles (type 2) and 4-node quads (type 3),
///   in ascending tag order; point and line elements (dimension 0 and 1) are skipped. Any other
///   surface element type, or a volume element, is refused.
/// - element.patch = surface entity tag - 1 (so our own files give back the patch indices).
/// - element.shell = i when the entity carries a physical surface named "shell<i>", else 0.
/// - group_names, if given, is resized to the largest surface entity tag (of $Entities and
///   $Elements), and entry t - 1 gets the name of the first named physical surface of entity t
///   that is not a "shell<i>" group ("" if none): for our files, the patch names.
/// A file written by write_mesh reads back to the same nodes (bit for bit) and elements.
/// Throws laytracks::Error "path:line: what" for another version (2.2, 4.0, ...), a binary
/// file, a syntax error, a missing $MeshFormat/$Nodes/$Elements section, or an element that
/// refers to a missing node.
QuadMesh read_msh(const std::string& path, std::vector<std::string>* group_names = nullptr);

}  // namespace laytracks
