// Writing a QuadMesh for other programs: Gmsh, VTK/ParaView, Nastran, Abaqus, OBJ and OFF.
#pragma once

#include <string>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// The extensions write_mesh knows, each with its leading dot, in the order the messages give.
const std::vector<std::string>& mesh_output_extensions();

/// Writes `mesh` of `part` to `path`; the format follows the extension (compared in lower case):
///   .msh  Gmsh MSH 4.1 ASCII: one surface entity per patch (tag = patch index + 1), a named
///         physical surface per patch (its name, tag = patch index + 1) and one per shell
///         ("shell<i>", tag = patch count + i + 1). No curve or point entities are written:
///         a node lives in the block of the lowest-tagged entity whose elements use it (nodes no
///         element uses go with entity 1). Node tag = node index + 1, element tag = element
///         index + 1, so blocks list tags in ascending order but not contiguously.
///   .vtu  VTK XML UnstructuredGrid, ASCII: VTK_QUAD (9) / VTK_TRIANGLE (5) cells, Int32 cell
///         data "patch" (patch index) and "shell", Float64 "quality" when `quality` is given.
///   .bdf  Nastran bulk data, free-field (comma) format so that coordinates keep their
///         precision: every real has a decimal point and at most 16 characters (the large-field
///         width). BEGIN BULK, a "$" comment per patch, GRID, CQUAD4 (CTRIA3 for triangles) with
///         PID = patch index + 1, one PSHELL per patch (T = 1.0, MID 1), a placeholder MAT1
///         (E = 1.0, NU = 0.3; set real values before solving), ENDDATA.
///   .inp  Abaqus: *HEADING, *NODE, one *ELEMENT, TYPE=S4R (S3R for triangles) block per patch
///         with ELSET = the patch name sanitised (letters, digits, '_'; starts with a letter;
///         unique ignoring case; at most 80 characters), a *SHELL SECTION (thickness 1.0) per
///         ELSET and a placeholder *MATERIAL (E = 1.0, nu = 0.3).
///   .obj .off  the polygons as OpenMesh's half-edge PolyMesh holds them: vertex i is node i,
///         face i is element i (a quad stays a quad). A face the PolyMesh cannot take (an edge
///         of three or more faces, a non-manifold vertex) gets its own copies of its nodes,
///         appended after the mesh's nodes, so that OpenMesh-based tools load every face.
///         Patches are not written. The text is ours, not OpenMesh::IO::write_mesh's: Debian's
///         OpenMesh 9.0 writes points as float even for a double mesh.
/// Node ids are node index + 1 and element ids element index + 1 in every format with ids;
/// a quad's nodes keep the mesh's counter-clockwise order about the patch normal.
/// Numbers are written by std::to_chars (shortest text that reads back to the same double),
/// so the output is locale-independent and byte-identical for identical input.
/// `quality`, if given, holds one finite value per element (the scaled Jacobian); only .vtu
/// writes it. Throws laytracks::Error, leaving no file, for an unknown extension (the message
/// names it and the supported ones), an element referring to a missing node or patch, an
/// element whose shell is not its patch's, a non-finite coordinate or quality value, a quality
/// vector of the wrong size, or an I/O failure. The write is atomic (write_file_atomically).
void write_mesh(const std::string& path,
                const Part& part,
                const QuadMesh& mesh,
                const std::vector<double>* quality = nullptr);

}  // namespace laytracks
