// The mesh writers. Every format goes through write_file_atomically, and every number through
// std::to_chars or a stream imbued with the classic locale: the bytes depend on the input only.
//
// The formats live here, sharing the checks and the number formatting. For OBJ and OFF,
// OpenMesh (write_openmesh.cpp, which keeps its headers to itself) decides the polygons.
#include "laytracks/io/mesh_output.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <locale>
#include <ostream>
#include <set>
#include <string>
#include <system_error>
#include <vector>

#include "laytracks/brep/error.hpp"
#include "laytracks/io/atomic_file.hpp"

namespace laytracks {

namespace detail {
/// Defined in write_openmesh.cpp (declared here alone: its only caller). points = the mesh's
/// nodes, then copies; faces[i] = element i's node ids, or ids of copies when OpenMesh's
/// PolyMesh cannot hold the face as it is (nodes[3] = kNoNode for a triangle).
void halfedge_polygons(const QuadMesh& mesh,
                       std::vector<Vec3>& points,
                       std::vector<std::array<std::uint32_t, 4>>& faces);
}  // namespace detail

namespace {

// ---------------------------------------------------------------------------------------------
// Numbers and names

/// The shortest text that reads back to exactly `x` (std::to_chars: no locale, no rounding).
std::string shortest(double x) {
  std::array<char, 64> buf{};
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return std::string(buf.data(), r.ptr);
}

/// A real for fixed-width-minded readers (Nastran, Abaqus): always a decimal point, at most
/// `max_len` characters. The shortest exact text when it fits, else scientific notation with as
/// many digits as fit, trailing zeros dropped (16 characters keep 10 significant digits, 9 when
/// the exponent has three).
std::string real_field(double x, std::size_t max_len, bool upper_exponent) {
  const auto with_point = [upper_exponent](std::string t) {
    std::size_t e = t.find('e');
    if (t.find('.') == std::string::npos) {
      t.insert(e == std::string::npos ? t.size() : e, ".");
    } else if (e != std::string::npos) {
      while (t[e - 1] == '0') t.erase(--e, 1);  // "1.5000e-01" -> "1.5e-01"
    }
    if (upper_exponent) std::replace(t.begin(), t.end(), 'e', 'E');
    return t;
  };
  std::string s = with_point(shortest(x));
  for (int digits = 16; s.size() > max_len && digits >= 1; --digits) {
    std::array<char, 64> buf{};
    const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), x,
                                 std::chars_format::scientific, digits);
    s = with_point(std::string(buf.data(), r.ptr));
  }
  return s;
}

/// One line of text: control characters (a newline in a patch name) become '_'.
std::string one_line(std::string s) {
  for (char& c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = '_';
  }
  return s;
}

std::string lower(std::string s) {
  for (char& c : s) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return s;
}

std::string extension_of(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  return lower(path.substr(dot));
}

std::size_t node_count(const MeshElement& e) { return e.is_quad() ? 4 : 3; }

/// Everything the writers rely on, checked before any file is opened.
void check_input(const Part& part, const QuadMesh& mesh, const std::vector<double>* quality) {
  for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
    if (!is_finite(mesh.nodes[i])) {
      throw Error("cannot write the mesh: node " + std::to_string(i) +
                  " has a non-finite coordinate");
    }
  }
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    const MeshElement& e = mesh.elements[i];
    const std::string which = "cannot write the mesh: element " + std::to_string(i);
    if (!e.patch.valid() || e.patch.index() >= part.patches.size()) {
      throw Error(which + " refers to patch " + std::to_string(e.patch.value) +
                  " but the part has " + std::to_string(part.patches.size()));
    }
    if (e.shell != part.patches[e.patch.index()].shell) {
      throw Error(which + " is in shell " + std::to_string(e.shell) + " but its " +
                  part.patch_label(e.patch) + " is in shell " +
                  std::to_string(part.patches[e.patch.index()].shell));
    }
    for (std::size_t k = 0; k < node_count(e); ++k) {
      if (e.nodes[k] >= mesh.nodes.size()) {
        throw Error(which + " refers to node " + std::to_string(e.nodes[k]) + " but the mesh has " +
                    std::to_string(mesh.nodes.size()));
      }
    }
  }
  for (const Patch& p : part.patches) {
    if (p.shell >= part.shell_count) {
      throw Error("cannot write the mesh: patch \"" + p.name + "\" is in shell " +
                  std::to_string(p.shell) + " but the part has " +
                  std::to_string(part.shell_count) + " shells");
    }
  }
  if (quality != nullptr) {
    if (quality->size() != mesh.elements.size()) {
      throw Error("cannot write the mesh: " + std::to_string(quality->size()) +
                  " quality values for " + std::to_string(mesh.elements.size()) + " elements");
    }
    for (std::size_t i = 0; i < quality->size(); ++i) {
      if (!std::isfinite((*quality)[i])) {
        throw Error("cannot write the mesh: the quality of element " + std::to_string(i) +
                    " is not finite");
      }
    }
  }
}

/// Element indices per patch, ascending, quads before triangles (one block each).
struct PatchElements {
  std::vector<std::size_t> quads;
  std::vector<std::size_t> triangles;
};

std::vector<PatchElements> elements_by_patch(const Part& part, const QuadMesh& mesh) {
  std::vector<PatchElements> by(part.patches.size());
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    const MeshElement& e = mesh.elements[i];
    auto& list = e.is_quad() ? by[e.patch.index()].quads : by[e.patch.index()].triangles;
    list.push_back(i);
  }
  return by;
}

void write_connectivity(std::ostream& out, const MeshElement& e, const char* separator) {
  for (std::size_t k = 0; k < node_count(e); ++k) out << separator << (e.nodes[k] + 1);
}

// ---------------------------------------------------------------------------------------------
// Gmsh MSH 4.1 ASCII

/// A physical name between double quotes: Gmsh has no escape for '"', so it becomes '\''.
std::string msh_name(const std::string& name) {
  std::string s = one_line(name);
  std::replace(s.begin(), s.end(), '"', '\'');
  return "\"" + s + "\"";
}

void write_msh(std::ostream& out, const Part& part, const QuadMesh& mesh) {
  const std::size_t patch_count = part.patches.size();
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";

  out << "$PhysicalNames\n" << (patch_count + part.shell_count) << "\n";
  for (std::size_t p = 0; p < patch_count; ++p) {
    out << "2 " << (p + 1) << " " << msh_name(part.patches[p].name) << "\n";
  }
  for (std::size_t s = 0; s < part.shell_count; ++s) {
    out << "2 " << (patch_count + s + 1) << " \"shell" << s << "\"\n";
  }
  out << "$EndPhysicalNames\n";

  // Surfaces only; the bounding box is the patch's boundary (file vertices and arc points).
  out << "$Entities\n0 0 " << patch_count << " 0\n";
  for (std::size_t p = 0; p < patch_count; ++p) {
    const Patch& patch = part.patches[p];
    Box3 box;
    for (const Loop& loop : patch.loops) {
      for (const VertexId v : loop.vertices) box.add(part.vertices[v.index()].position);
    }
    if (box.empty()) box.add(Vec3{});
    out << (p + 1) << " " << shortest(box.lo.x) << " " << shortest(box.lo.y) << " "
        << shortest(box.lo.z) << " " << shortest(box.hi.x) << " " << shortest(box.hi.y) << " "
        << shortest(box.hi.z) << " 2 " << (p + 1) << " " << (patch_count + patch.shell + 1)
        << " 0\n";
  }
  out << "$EndEntities\n";

  // A node goes to the block of the lowest patch whose elements use it (unused ones: patch 0).
  std::vector<std::size_t> owner(mesh.nodes.size(), patch_count);
  for (const MeshElement& e : mesh.elements) {
    for (std::size_t k = 0; k < node_count(e); ++k) {
      std::size_t& o = owner[e.nodes[k]];
      o = std::min(o, e.patch.index());
    }
  }
  std::vector<std::vector<std::size_t>> nodes_of(std::max<std::size_t>(patch_count, 1));
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    nodes_of[owner[n] == patch_count ? 0 : owner[n]].push_back(n);
  }
  std::size_t node_blocks = 0;
  for (const auto& list : nodes_of) {
    if (!list.empty()) ++node_blocks;
  }
  out << "$Nodes\n"
      << node_blocks << " " << mesh.nodes.size() << " " << (mesh.nodes.empty() ? 0 : 1) << " "
      << mesh.nodes.size() << "\n";
  for (std::size_t p = 0; p < nodes_of.size(); ++p) {
    if (nodes_of[p].empty()) continue;
    out << "2 " << (p + 1) << " 0 " << nodes_of[p].size() << "\n";
    for (const std::size_t n : nodes_of[p]) out << (n + 1) << "\n";
    for (const std::size_t n : nodes_of[p]) {
      const Vec3 x = mesh.nodes[n];
      out << shortest(x.x) << " " << shortest(x.y) << " " << shortest(x.z) << "\n";
    }
  }
  out << "$EndNodes\n";

  const std::vector<PatchElements> by = elements_by_patch(part, mesh);
  std::size_t element_blocks = 0;
  for (const PatchElements& pe : by) {
    if (!pe.quads.empty()) ++element_blocks;
    if (!pe.triangles.empty()) ++element_blocks;
  }
  out << "$Elements\n"
      << element_blocks << " " << mesh.elements.size() << " " << (mesh.elements.empty() ? 0 : 1)
      << " " << mesh.elements.size() << "\n";
  for (std::size_t p = 0; p < by.size(); ++p) {
    for (const auto* list : {&by[p].quads, &by[p].triangles}) {
      if (list->empty()) continue;
      const int type = list == &by[p].quads ? 3 : 2;  // 4-node quad, 3-node triangle
      out << "2 " << (p + 1) << " " << type << " " << list->size() << "\n";
      for (const std::size_t i : *list) {
        out << (i + 1);
        write_connectivity(out, mesh.elements[i], " ");
        out << "\n";
      }
    }
  }
  out << "$EndElements\n";
}

// ---------------------------------------------------------------------------------------------
// VTK XML UnstructuredGrid, ASCII

void write_vtu(std::ostream& out, const QuadMesh& mesh, const std::vector<double>* quality) {
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << mesh.nodes.size() << "\" NumberOfCells=\""
      << mesh.elements.size() << "\">\n";
  out << "      <Points>\n"
         "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (const Vec3& x : mesh.nodes) {
    out << "          " << shortest(x.x) << " " << shortest(x.y) << " " << shortest(x.z) << "\n";
  }
  out << "        </DataArray>\n      </Points>\n      <Cells>\n";
  out << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const MeshElement& e : mesh.elements) {
    out << "         ";
    for (std::size_t k = 0; k < node_count(e); ++k) out << " " << e.nodes[k];
    out << "\n";
  }
  out << "        </DataArray>\n"
         "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  std::size_t offset = 0;
  for (const MeshElement& e : mesh.elements) {
    offset += node_count(e);
    out << "          " << offset << "\n";
  }
  out << "        </DataArray>\n"
         "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (const MeshElement& e : mesh.elements) out << "          " << (e.is_quad() ? 9 : 5) << "\n";
  out << "        </DataArray>\n      </Cells>\n";

  out << "      <CellData Scalars=\"patch\">\n"
         "        <DataArray type=\"Int32\" Name=\"patch\" format=\"ascii\">\n";
  for (const MeshElement& e : mesh.elements) out << "          " << e.patch.value << "\n";
  out << "        </DataArray>\n"
         "        <DataArray type=\"Int32\" Name=\"shell\" format=\"ascii\">\n";
  for (const MeshElement& e : mesh.elements) out << "          " << e.shell << "\n";
  out << "        </DataArray>\n";
  if (quality != nullptr) {
    out << "        <DataArray type=\"Float64\" Name=\"quality\" format=\"ascii\">\n";
    for (const double q : *quality) out << "          " << shortest(q) << "\n";
    out << "        </DataArray>\n";
  }
  out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
}

// ---------------------------------------------------------------------------------------------
// Nastran bulk data, free-field

/// Free-field reals: at most the large-field width (16), which keeps 10 significant digits where
/// the exact text is longer; Nastran needs the decimal point to read a real.
std::string nastran_real(double x) { return real_field(x, 16, true); }

void write_bdf(std::ostream& out, const Part& part, const QuadMesh& mesh) {
  out << "$ laytracks mesh of " << one_line(part.source) << ", units " << one_line(part.units)
      << "\n$ Free-field bulk data. MAT1 holds placeholder values: set the real ones before "
         "solving.\nBEGIN BULK\n";
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    out << "$ PID " << (p + 1) << ": patch \"" << one_line(part.patches[p].name) << "\" (shell "
        << part.patches[p].shell << ")\n";
    // PID, MID1, T, MID2 (bending), 12I/T^3 (default), MID3 (transverse shear)
    out << "PSHELL," << (p + 1) << ",1,1.0,1,,1\n";
  }
  out << "MAT1,1,1.0,,0.3\n";
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Vec3 x = mesh.nodes[n];
    out << "GRID," << (n + 1) << ",," << nastran_real(x.x) << "," << nastran_real(x.y) << ","
        << nastran_real(x.z) << "\n";
  }
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    const MeshElement& e = mesh.elements[i];
    out << (e.is_quad() ? "CQUAD4," : "CTRIA3,") << (i + 1) << "," << (e.patch.index() + 1);
    write_connectivity(out, e, ",");
    out << "\n";
  }
  out << "ENDDATA\n";
}

// ---------------------------------------------------------------------------------------------
// Abaqus input

/// Abaqus names: letters, digits and '_', starting with a letter, at most 80 characters, and
/// (Abaqus ignores case) unique in lower case. A clash gets "_<patch index + 1>" appended.
std::vector<std::string> abaqus_set_names(const Part& part) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    std::string s;
    for (const char c : part.patches[p].name) {
      const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
      s += ok ? c : '_';
    }
    if (s.empty() || !((s[0] >= 'A' && s[0] <= 'Z') || (s[0] >= 'a' && s[0] <= 'z'))) {
      s = "P_" + s;
    }
    const std::string suffix = "_" + std::to_string(p + 1);
    if (s.size() > 80) s.resize(80);
    if (taken.count(lower(s)) != 0) s = s.substr(0, 80 - suffix.size()) + suffix;
    // Still taken only if another patch's name ends like this one's suffix: use the index alone.
    if (taken.count(lower(s)) != 0) s = "PATCH" + suffix;
    taken.insert(lower(s));
    names.push_back(s);
  }
  return names;
}

void write_inp(std::ostream& out, const Part& part, const QuadMesh& mesh) {
  const std::vector<std::string> sets = abaqus_set_names(part);
  const std::vector<PatchElements> by = elements_by_patch(part, mesh);
  out << "*HEADING\nlaytracks mesh of " << one_line(part.source) << ", units "
      << one_line(part.units) << "\n";
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    out << "** ELSET " << sets[p] << ": patch \"" << one_line(part.patches[p].name) << "\" (index "
        << p << ", shell " << part.patches[p].shell << ")\n";
  }
  out << "*NODE\n";
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n) {
    const Vec3 x = mesh.nodes[n];
    out << (n + 1) << ", " << real_field(x.x, 20, true) << ", " << real_field(x.y, 20, true) << ", "
        << real_field(x.z, 20, true) << "\n";
  }
  for (std::size_t p = 0; p < by.size(); ++p) {
    for (const auto* list : {&by[p].quads, &by[p].triangles}) {
      if (list->empty()) continue;
      out << "*ELEMENT, TYPE=" << (list == &by[p].quads ? "S4R" : "S3R") << ", ELSET=" << sets[p]
          << "\n";
      for (const std::size_t i : *list) {
        out << (i + 1);
        write_connectivity(out, mesh.elements[i], ", ");
        out << "\n";
      }
    }
  }
  out << "** Placeholder material: set the real values before solving.\n"
         "*MATERIAL, NAME=LAYTRACKS_MATERIAL\n*ELASTIC\n1.0, 0.3\n";
  for (std::size_t p = 0; p < by.size(); ++p) {
    if (by[p].quads.empty() && by[p].triangles.empty()) continue;  // an empty ELSET is an error
    out << "*SHELL SECTION, ELSET=" << sets[p] << ", MATERIAL=LAYTRACKS_MATERIAL\n1.0\n";
  }
}

// ---------------------------------------------------------------------------------------------
// OBJ and OFF

/// Vertices in node order (copies after them), faces in element order; OBJ counts from 1, OFF
/// from 0.
void write_polygons(std::ostream& out, const QuadMesh& mesh, bool obj) {
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 4>> faces;
  detail::halfedge_polygons(mesh, points, faces);
  if (obj) {
    out << "# laytracks mesh: " << points.size() << " vertices, " << faces.size() << " faces\n";
  } else {
    out << "OFF\n" << points.size() << " " << faces.size() << " 0\n";
  }
  for (const Vec3& x : points) {
    out << (obj ? "v " : "") << shortest(x.x) << " " << shortest(x.y) << " " << shortest(x.z)
        << "\n";
  }
  for (const auto& f : faces) {
    const std::size_t n = f[3] == MeshElement::kNoNode ? 3 : 4;
    out << (obj ? "f" : n == 4 ? "4" : "3");
    for (std::size_t k = 0; k < n; ++k) out << " " << (obj ? f[k] + 1 : f[k]);
    out << "\n";
  }
}

}  // namespace

const std::vector<std::string>& mesh_output_extensions() {
  static const std::vector<std::string> extensions = {".msh", ".vtu", ".bdf",
                                                      ".inp", ".obj", ".off"};
  return extensions;
}

void write_mesh(const std::string& path,
                const Part& part,
                const QuadMesh& mesh,
                const std::vector<double>* quality) {
  const std::string ext = extension_of(path);
  const auto& known = mesh_output_extensions();
  if (std::find(known.begin(), known.end(), ext) == known.end()) {
    std::string list;
    for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
    throw Error("cannot write " + path + ": " +
                (ext.empty() ? std::string("no extension") : "unknown extension \"" + ext + "\"") +
                "; the mesh formats are " + list);
  }
  check_input(part, mesh, quality);
  write_file_atomically(path, [&](std::ostream& out) {
    out.imbue(std::locale::classic());  // integers too: no digit grouping, whatever the locale
    if (ext == ".msh") {
      write_msh(out, part, mesh);
    } else if (ext == ".vtu") {
      write_vtu(out, mesh, quality);
    } else if (ext == ".bdf") {
      write_bdf(out, part, mesh);
    } else if (ext == ".inp") {
      write_inp(out, part, mesh);
    } else {
      write_polygons(out, mesh, ext == ".obj");
    }
  });
}

}  // namespace laytracks
