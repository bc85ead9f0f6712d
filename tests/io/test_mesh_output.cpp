// The mesh writers, checked by independent readers: meshio (python3-meshio) reads every format
// back and Gmsh opens the .msh; read_msh round-trips our .msh and reads Gmsh's own output.
#include <sys/wait.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <locale>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../brep/parts.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/brep/error.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/io/msh_reader.hpp"

namespace fs = std::filesystem;
using namespace laytracks;
using laytracks::test::make_part;
using laytracks::test::patch;

namespace {

// ---------------------------------------------------------------------------------------------
// Meshes built by hand

MeshElement quad(std::uint32_t a,
                 std::uint32_t b,
                 std::uint32_t c,
                 std::uint32_t d,
                 std::size_t patch_index,
                 std::uint32_t shell = 0) {
  MeshElement e;
  e.nodes = {a, b, c, d};
  e.patch = PatchId(patch_index);
  e.shell = shell;
  return e;
}

/// A 3 x 2 grid of quads on one patch "plate" of 0.3 x 0.7 (coordinates with 17 digits).
struct Fixture {
  Part part;
  QuadMesh mesh;
};

Fixture grid() {
  const double w = 0.3;
  const double h = 0.7;
  Fixture f;
  f.part = build_part(make_part({{0, 0, 0.1}, {w, 0, 0.1}, {w, h, 0.1}, {0, h, 0.1}},
                                {patch("plate", {{0, 1, 2, 3}})}));
  for (std::uint32_t j = 0; j <= 2; ++j) {
    for (std::uint32_t i = 0; i <= 3; ++i) f.mesh.nodes.push_back({w * i / 3.0, h * j / 2.0, 0.1});
  }
  for (std::uint32_t j = 0; j < 2; ++j) {
    for (std::uint32_t i = 0; i < 3; ++i) {
      const std::uint32_t n = 4 * j + i;
      f.mesh.elements.push_back(quad(n, n + 1, n + 5, n + 4, 0));
    }
  }
  return f;
}

/// A floor (normal +z) and a wall (normal -x) sharing the edge x = 2, z = 0 with shared nodes,
/// plus a "tab" apart from them in a second shell. Names need sanitising in some formats.
Fixture fold() {
  Fixture f;
  RawPart raw = make_part({{0, 0, 0},
                           {2, 0, 0},
                           {2, 1, 0},
                           {0, 1, 0},
                           {2, 0, 1.5},
                           {2, 1, 1.5},
                           {5, 0, 0},
                           {6, 0, 0},
                           {6, 1, 0},
                           {5, 1, 0}},
                          {patch("floor", {{0, 1, 2, 3}}), patch("wall 2 \"west\"", {{1, 4, 5, 2}}),
                           patch("9-tab", {{6, 7, 8, 9}})});
  f.part = build_part(raw);
  // floor: 2 x 1 quads, nodes 0..5; wall: 1 x 2 quads on top of floor nodes 2 and 5.
  f.mesh.nodes = {{0, 0, 0}, {1, 0, 0},    {2, 0, 0},    {0, 1, 0},   {1, 1, 0},
                  {2, 1, 0}, {2, 0, 0.75}, {2, 1, 0.75}, {2, 0, 1.5}, {2, 1, 1.5},
                  {5, 0, 0}, {6, 0, 0},    {6, 1, 0},    {5, 1, 0}};
  const auto s = [&](std::size_t p) { return static_cast<std::uint32_t>(f.part.patches[p].shell); };
  f.mesh.elements = {quad(0, 1, 4, 3, 0, s(0)), quad(1, 2, 5, 4, 0, s(0)),
                     quad(2, 6, 7, 5, 1, s(1)), quad(6, 8, 9, 7, 1, s(1)),
                     quad(10, 11, 12, 13, 2, s(2))};
  return f;
}

// ---------------------------------------------------------------------------------------------
// Files and the independent readers

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("laytracks-test-mesh-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t entries(const fs::path& d) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}

/// Runs a command; returns its exit status and what it printed (stdout and stderr).
int run(const std::string& command, std::string* output) {
  const std::string full = command + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::string text;
  char buf[4096];
  std::size_t got = 0;
  while ((got = std::fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, got);
  const int status = pclose(pipe);
  if (output != nullptr) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Prints what the file holds, by meshio (or, for OFF, which meshio reads only with triangles,
// a parser of a few lines): counts, the sum of all coordinates, and the sum over cells of
// sum_k (k + 1) * (x_k + 2 y_k + 3 z_k), which sees node order within a cell but not numbering.
const char* const kSummaryScript = R"PY(
import math, sys
path = sys.argv[1]
sets = []
data = {}
if path.endswith(".assimp.obj"):
    # What assimp exported from our .obj or .off: v lines, then f lines of "i//n" (1-based).
    points = []
    cells = []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "v":
                points.append([float(x) for x in w[1:4]])
            elif w and w[0] == "f":
                c = [int(x.split("/")[0]) - 1 for x in w[1:]]
                cells.append(("polygon%d" % len(c), c))
elif path.endswith(".off"):
    words = []
    with open(path) as f:
        lines = [l.split("#")[0] for l in f]
    words = " ".join(lines[1:]).split()
    nv, nf = int(words[0]), int(words[1])
    pos = 3
    points = []
    for i in range(nv):
        points.append([float(w) for w in words[pos:pos + 3]])
        pos += 3
    cells = []
    for i in range(nf):
        k = int(words[pos])
        cells.append(("polygon%d" % k, [int(w) for w in words[pos + 1:pos + 1 + k]]))
        pos += 1 + k
else:
    import meshio
    m = meshio.read(path)
    points = m.points.tolist()
    cells = [(b.type, list(map(int, c))) for b in m.cells for c in b.data]
    for key, blocks in m.cell_data.items():
        data[key] = math.fsum(float(v) for b in blocks for v in b)
    sets = sorted(set(k for k in m.cell_sets if not k.startswith("gmsh:")) | set(m.field_data))
types = {}
for t, c in cells:
    types[t] = types.get(t, 0) + 1
print("points", len(points))
print("cells", len(cells))
print("sum", repr(math.fsum(x for p in points for x in p)))
print("cellsum", repr(math.fsum((k + 1) * (points[n][0] + 2 * points[n][1] + 3 * points[n][2])
                               for t, c in cells for k, n in enumerate(c))))
for t in sorted(types):
    print("type", t, types[t])
for k in sorted(data):
    print("data", k, repr(data[k]))
for s in sets:
    print("set", s)
for p in points:
    print("point", *(repr(float(x)) for x in p))
)PY";

struct Summary {
  std::size_t points = 0;
  std::size_t cells = 0;
  double sum = 0.0;
  double cellsum = 0.0;
  std::map<std::string, std::size_t> types;
  std::map<std::string, double> data;
  std::vector<std::string> sets;
  std::vector<Vec3> points_read;  ///< in the file's order

  std::size_t type(const std::string& t) const {
    const auto it = types.find(t);
    return it == types.end() ? 0 : it->second;
  }
  double value(const std::string& d) const {
    const auto it = data.find(d);
    return it == data.end() ? std::nan("") : it->second;
  }
};

Summary independent_summary(const fs::path& file) {
  const fs::path script = file.parent_path() / "summary.py";
  {
    std::ofstream out(script);
    out << kSummaryScript;
  }
  std::string text;
  const int status =
      run("/usr/bin/python3 '" + script.string() + "' '" + file.string() + "'", &text);
  INFO("python3 + meshio on " << file << " said:\n"
                              << text << "(install them with scripts/setup.sh: python3-meshio)");
  REQUIRE(status == 0);
  Summary s;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    in.imbue(std::locale::classic());
    std::string key;
    if (!(in >> key)) continue;  // meshio prints a blank line when it reads a .msh
    if (key == "points") {
      in >> s.points;
    } else if (key == "cells") {
      in >> s.cells;
    } else if (key == "sum") {
      in >> s.sum;
    } else if (key == "cellsum") {
      in >> s.cellsum;
    } else if (key == "type") {
      std::string t;
      in >> t >> s.types[t];
    } else if (key == "data") {
      std::string d;
      in >> d >> s.data[d];
    } else if (key == "point") {
      Vec3 x;
      in >> x.x >> x.y >> x.z;
      s.points_read.push_back(x);
    } else if (key == "set") {
      s.sets.push_back(line.substr(4));
    } else {
      FAIL("unexpected output: " << key);
    }
  }
  return s;
}

double coordinate_sum(const QuadMesh& m) {
  double s = 0.0;
  for (const Vec3& x : m.nodes) s += x.x + x.y + x.z;
  return s;
}

double cell_sum(const QuadMesh& m) {
  double s = 0.0;
  for (const MeshElement& e : m.elements) {
    for (std::size_t k = 0; k < (e.is_quad() ? 4u : 3u); ++k) {
      const Vec3 x = m.nodes[e.nodes[k]];
      s += static_cast<double>(k + 1) * (x.x + 2 * x.y + 3 * x.z);
    }
  }
  return s;
}

bool close(double a, double b) { return std::fabs(a - b) <= 1e-9 * std::fmax(1.0, std::fabs(b)); }

/// The summary meshio (or the OFF parser) must give for `m` written as `ext`.
void check_summary(const Summary& s, const QuadMesh& m, const std::string& ext) {
  INFO(ext);
  CHECK(s.points == m.nodes.size());
  CHECK(s.cells == m.elements.size());
  CHECK(close(s.sum, coordinate_sum(m)));
  CHECK(close(s.cellsum, cell_sum(m)));
  const std::string quad_type = ext == ".off" ? "polygon4" : "quad";
  CHECK(s.types.size() == 1);
  CHECK(s.type(quad_type) == m.elements.size());
}

/// `gmsh -check` (headless): reads the file, checks coherence (duplicate nodes or elements,
/// isolated nodes), and exits 1 on a read error.
bool gmsh_checks(const fs::path& file, const QuadMesh& m, std::string* output) {
  return run("gmsh -check '" + file.string() + "'", output) == 0 &&
         output->find("Error") == std::string::npos &&
         output->find("Warning") == std::string::npos &&
         output->find(" " + std::to_string(m.nodes.size()) + " nodes\n") != std::string::npos &&
         output->find(" " + std::to_string(m.elements.size()) + " elements\n") != std::string::npos;
}

const std::vector<std::string> kFormats = {".msh", ".vtu", ".bdf", ".inp", ".obj", ".off"};

}  // namespace

// ---------------------------------------------------------------------------------------------

TEST_CASE("every format reads back in meshio with the same nodes and cells", "[io][mesh]") {
  const fs::path d = fresh_dir("meshio");
  for (const bool folded : {false, true}) {
    const Fixture f = folded ? fold() : grid();
    for (const std::string& ext : kFormats) {
      const fs::path file = d / ((folded ? "fold" : "grid") + ext);
      write_mesh(file.string(), f.part, f.mesh);
      check_summary(independent_summary(file), f.mesh, ext);
    }
  }
}

TEST_CASE("assimp reads our .obj and .off back as quads, with the same nodes", "[io][mesh]") {
  // meshio reads only triangles from OFF; assimp (Debian's assimp-utils, installed by
  // scripts/setup.sh) is a second reader for both OpenMesh formats. `assimp export` reads the
  // file with its own importer and writes it as OBJ, which the script above parses. assimp
  // keeps coordinates in single precision: sums to 1e-6.
  const fs::path d = fresh_dir("assimp");
  const auto near = [](double a, double b) {
    return std::fabs(a - b) <= 1e-6 * std::fmax(1.0, std::fabs(b));
  };
  for (const bool folded : {false, true}) {
    const Fixture f = folded ? fold() : grid();
    for (const std::string ext : {".obj", ".off"}) {
      INFO(ext << (folded ? " fold" : " grid"));
      const fs::path file = d / ((folded ? "fold" : "grid") + ext);
      const fs::path back = d / ((folded ? "fold" : "grid") + ext.substr(1) + ".assimp.obj");
      write_mesh(file.string(), f.part, f.mesh);
      std::string output;
      const int status =
          run("assimp export '" + file.string() + "' '" + back.string() + "'", &output);
      INFO("assimp said:\n" << output << "(install it with scripts/setup.sh: assimp-utils)");
      REQUIRE(status == 0);
      const Summary s = independent_summary(back);
      CHECK(s.cells == f.mesh.elements.size());
      CHECK(s.type("polygon4") == f.mesh.elements.size());
      CHECK(s.types.size() == 1);
      // OBJ's faces index a vertex list per face group; OFF's share them as we wrote them.
      if (ext == ".off") {
        CHECK(s.points == f.mesh.nodes.size());
        CHECK(near(s.sum, coordinate_sum(f.mesh)));
      }
      CHECK(near(s.cellsum, cell_sum(f.mesh)));
    }
  }
}

TEST_CASE("coordinates keep their precision: exactly, or 10 digits in Nastran's 16 characters",
          "[io][mesh]") {
  const fs::path d = fresh_dir("precision");
  Fixture f = grid();
  const std::vector<Vec3> nasty = {{-1.2345678901234567e-5, 98765.43210987654, 1.0 / 3.0},
                                   {2.0 / 3.0, -7.000000000000001e+123, 5e-324},
                                   {-0.0, 1e22, -123456789.12345679}};
  for (std::size_t i = 0; i < nasty.size(); ++i) f.mesh.nodes[i] = nasty[i];
  for (const std::string& ext : kFormats) {
    INFO(ext);
    write_mesh((d / ("m" + ext)).string(), f.part, f.mesh);
    const Summary s = independent_summary(d / ("m" + ext));
    REQUIRE(s.points_read.size() == f.mesh.nodes.size());  // one patch: file order = node order
    const bool exact = ext != ".bdf" && ext != ".inp";
    for (std::size_t i = 0; i < f.mesh.nodes.size(); ++i) {
      const Vec3 a = s.points_read[i];
      const Vec3 b = f.mesh.nodes[i];
      INFO("node " << i);
      if (exact) {
        CHECK(a == b);
      } else {
        for (const auto& [u, v] : {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z}}) {
          CHECK(std::fabs(u - v) <= 1e-9 * std::fabs(v));
        }
      }
    }
  }
  const std::string bdf = slurp(d / "m.bdf");
  std::istringstream lines(bdf);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("GRID,", 0) != 0) continue;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) CHECK(field.size() <= 16);
  }
}

TEST_CASE("each format carries the patches and shells", "[io][mesh]") {
  const fs::path d = fresh_dir("groups");
  const Fixture f = fold();
  REQUIRE(f.part.shell_count == 2);
  std::vector<double> quality = {1.0, 0.5, 0.25, -0.125, 0.0625};

  SECTION("vtu: patch, shell and quality cell data") {
    write_mesh((d / "m.vtu").string(), f.part, f.mesh, &quality);
    const Summary s = independent_summary(d / "m.vtu");
    CHECK(s.value("patch") == 0 + 0 + 1 + 1 + 2);
    double shells = 0.0;
    for (const MeshElement& e : f.mesh.elements) shells += e.shell;
    CHECK(s.value("shell") == shells);
    CHECK(f.part.patches[2].shell != f.part.patches[0].shell);
    CHECK(s.value("quality") == 1.0 + 0.5 + 0.25 - 0.125 + 0.0625);
  }
  SECTION("msh: a physical group per patch and per shell") {
    write_mesh((d / "m.msh").string(), f.part, f.mesh);
    const Summary s = independent_summary(d / "m.msh");
    const std::vector<std::string> expected = {"9-tab", "floor", "shell0", "shell1",
                                               "wall 2 'west'"};
    CHECK(s.sets == expected);
    CHECK(s.value("gmsh:geometrical") == 1 + 1 + 2 + 2 + 3);
  }
  SECTION("inp: an ELSET per patch, names made valid and unique") {
    write_mesh((d / "m.inp").string(), f.part, f.mesh);
    const Summary s = independent_summary(d / "m.inp");
    const std::vector<std::string> expected = {"P_9_tab", "floor", "wall_2__west_"};
    auto sets = s.sets;
    std::sort(sets.begin(), sets.end());
    CHECK(sets == expected);
    const std::string text = slurp(d / "m.inp");
    CHECK(text.find("*SHELL SECTION, ELSET=wall_2__west_, MATERIAL=LAYTRACKS_MATERIAL\n1.0\n") !=
          std::string::npos);
  }
  SECTION("bdf: property ids are patch index + 1") {
    write_mesh((d / "m.bdf").string(), f.part, f.mesh);
    const Summary s = independent_summary(d / "m.bdf");
    CHECK(s.value("nastran:ref") == 1 + 1 + 2 + 2 + 3);
    const std::string text = slurp(d / "m.bdf");
    CHECK(text.find("PSHELL,3,1,1.0,1,,1\n") != std::string::npos);
    CHECK(text.find("MAT1,1,") != std::string::npos);
    CHECK(text.find("$ PID 2: patch \"wall 2 \"west\"\"") != std::string::npos);
  }
}

TEST_CASE("gmsh opens our .msh files, and what it saves from them reads back", "[io][mesh][gmsh]") {
  const fs::path d = fresh_dir("gmsh");
  for (const bool folded : {false, true}) {
    const fs::path file = d / (folded ? "fold.msh" : "grid.msh");
    const fs::path saved = d / (folded ? "fold-gmsh.msh" : "grid-gmsh.msh");
    const Fixture f = folded ? fold() : grid();
    write_mesh(file.string(), f.part, f.mesh);
    std::string output;
    const bool checked = gmsh_checks(file, f.mesh, &output);
    INFO("gmsh said:\n" << output);
    CHECK(checked);
    const int status =
        run("gmsh '" + file.string() + "' -0 -format msh41 -o '" + saved.string() + "'", &output);
    REQUIRE(status == 0);
    std::vector<std::string> names;
    const QuadMesh back = read_msh(saved.string(), &names);
    CHECK(back.nodes.size() == f.mesh.nodes.size());
    CHECK(back.elements.size() == f.mesh.elements.size());
    CHECK(close(coordinate_sum(back), coordinate_sum(f.mesh)));
    CHECK(close(cell_sum(back), cell_sum(f.mesh)));
    for (std::size_t i = 0; i < std::min(back.elements.size(), f.mesh.elements.size()); ++i) {
      CHECK(back.elements[i].patch == f.mesh.elements[i].patch);
      CHECK(back.elements[i].shell == f.mesh.elements[i].shell);
    }
    CHECK(names.size() == f.part.patches.size());
  }
}

TEST_CASE("read_msh gives back our mesh exactly", "[io][mesh]") {
  const fs::path d = fresh_dir("roundtrip");
  for (const bool folded : {false, true}) {
    const Fixture f = folded ? fold() : grid();
    const fs::path file = d / "m.msh";
    write_mesh(file.string(), f.part, f.mesh);
    std::vector<std::string> names;
    const QuadMesh back = read_msh(file.string(), &names);
    REQUIRE(back.nodes.size() == f.mesh.nodes.size());
    for (std::size_t i = 0; i < back.nodes.size(); ++i) CHECK(back.nodes[i] == f.mesh.nodes[i]);
    REQUIRE(back.elements.size() == f.mesh.elements.size());
    for (std::size_t i = 0; i < back.elements.size(); ++i) {
      CHECK(back.elements[i].nodes == f.mesh.elements[i].nodes);
      CHECK(back.elements[i].patch == f.mesh.elements[i].patch);
      CHECK(back.elements[i].shell == f.mesh.elements[i].shell);
    }
    REQUIRE(names.size() == f.part.patches.size());
    for (std::size_t p = 0; p < names.size(); ++p) {
      std::string expected = f.part.patches[p].name;
      std::replace(expected.begin(), expected.end(), '"', '\'');
      CHECK(names[p] == expected);
    }
  }
}

TEST_CASE("read_msh reads Gmsh's own output: triangles, quads, lines, several entities",
          "[io][mesh][gmsh]") {
  const fs::path d = fresh_dir("gmsh-output");
  {
    std::ofstream geo(d / "two.geo");
    geo << "Point(1) = {0, 0, 0, 0.4}; Point(2) = {1, 0, 0, 0.4}; Point(3) = {1, 1, 0, 0.4};\n"
           "Point(4) = {0, 1, 0, 0.4}; Point(5) = {2, 0, 0, 0.4}; Point(6) = {2, 1, 0, 0.4};\n"
           "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
           "Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};\n"
           "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
           "Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};\n"
           "Recombine Surface{2};\n"
           "Physical Surface(\"left\") = {1};\n"
           "Physical Surface(\"right\") = {2};\n"
           "Physical Curve(\"edges\") = {1, 2, 3, 4, 5, 6, 7};\n";
  }
  const std::string geo = (d / "two.geo").string();
  for (const std::string& options :
       {std::string("-o '") + (d / "plain.msh").string() + "'",
        "-setnumber Mesh.SaveParametric 1 -o '" + (d / "param.msh").string() + "'"}) {
    std::string output;
    const int status = run("gmsh '" + geo + "' -2 -format msh41 " + options, &output);
    INFO("gmsh said:\n" << output);
    REQUIRE(status == 0);
  }

  const Summary s = independent_summary(d / "plain.msh");
  REQUIRE(s.type("triangle") > 0);
  REQUIRE(s.type("quad") > 0);
  REQUIRE(s.type("line") > 0);

  for (const char* name : {"plain.msh", "param.msh"}) {
    INFO(name);
    std::vector<std::string> groups;
    const QuadMesh m = read_msh((d / name).string(), &groups);
    CHECK(m.nodes.size() == s.points);
    std::size_t tris = 0;
    std::size_t quads = 0;
    for (const MeshElement& e : m.elements) {
      (e.is_quad() ? quads : tris) += 1;
      CHECK(e.patch.index() == (e.is_quad() ? 1u : 0u));  // surface 2 is recombined
      CHECK(e.shell == 0);
    }
    CHECK(tris == s.type("triangle"));
    CHECK(quads == s.type("quad"));
    CHECK(close(coordinate_sum(m), s.sum));
    CHECK(groups == std::vector<std::string>{"left", "right"});
  }

  // The mixed mesh written back in every format (triangles: msh 2, VTK 5, CTRIA3, S3R).
  const Part part =
      build_part(make_part({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}},
                           {patch("left", {{0, 1, 2, 3}}), patch("right", {{1, 4, 5, 2}})}));
  const QuadMesh mixed = read_msh((d / "plain.msh").string());
  for (const std::string& ext : kFormats) {
    INFO(ext);
    const fs::path file = d / ("mixed" + ext);
    write_mesh(file.string(), part, mixed);
    const Summary back = independent_summary(file);
    CHECK(back.points == mixed.nodes.size());
    CHECK(back.cells == mixed.elements.size());
    CHECK(close(back.sum, coordinate_sum(mixed)));
    CHECK(close(back.cellsum, cell_sum(mixed)));
    CHECK(back.type(ext == ".off" ? "polygon3" : "triangle") == s.type("triangle"));
    CHECK(back.type(ext == ".off" ? "polygon4" : "quad") == s.type("quad"));
  }
  const QuadMesh again = read_msh((d / "mixed.msh").string());
  CHECK(again.elements.size() == mixed.elements.size());
  CHECK(cell_sum(again) == cell_sum(mixed));
}

TEST_CASE("read_msh refuses other versions, binary files and broken ones, with file:line",
          "[io][mesh]") {
  const fs::path d = fresh_dir("msh-errors");
  const auto message = [&](const std::string& text) {
    const fs::path file = d / "bad.msh";
    {
      std::ofstream out(file, std::ios::binary);
      out << text;
    }
    try {
      read_msh(file.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string file = (d / "bad.msh").string();
  CHECK_THAT(message("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"),
             Catch::StartsWith(file + ":2: MSH version 2.2 is not supported"));
  CHECK_THAT(
      message("$MeshFormat\n4.1 1 8\n" + std::string("\x01\0\0\0", 4) + "\n$EndMeshFormat\n"),
      Catch::StartsWith(file + ":2: binary MSH is not supported"));
  CHECK_THAT(message("$Nodes\n"), Catch::Contains("no $MeshFormat"));
  CHECK_THAT(message("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2 1 2\n2 1 0 2\n1\n2\n"
                     "0 0 0\n1 0 x\n$EndNodes\n"),
             Catch::StartsWith(file + ":10: expected a node coordinate"));
  CHECK_THAT(message("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 1 1 1\n2 1 0 1\n1\n"
                     "0 0 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 2 1\n1 1 1 7\n$EndElements\n"),
             Catch::StartsWith(file + ":13: an element refers to node 7"));
  CHECK_THAT(message("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"), Catch::Contains("no $Nodes"));
  CHECK_THROWS_WITH(read_msh((d / "missing.msh").string()), Catch::Contains("cannot read"));
}

TEST_CASE("the output is byte-identical run to run, whatever the global locale",
          "[io][mesh][determinism]") {
  // A locale that groups thousands and writes a decimal comma, as some users' locales do.
  struct Comma : std::numpunct<char> {
    char do_decimal_point() const override { return ','; }
    char do_thousands_sep() const override { return '.'; }
    std::string do_grouping() const override { return "\3"; }
  };
  const fs::path d = fresh_dir("determinism");
  Fixture f = grid();
  // Enough nodes for ids past 1000, where a grouping locale would write "1.000".
  for (std::uint32_t i = 0; i < 1200; ++i) f.mesh.nodes.push_back({0.1 * i, 1.0 / 3.0, 1e-7});
  std::vector<double> quality(f.mesh.elements.size(), 2.0 / 3.0);
  for (const std::string& ext : kFormats) {
    INFO(ext);
    const fs::path a = d / ("a" + ext);
    const fs::path b = d / ("b" + ext);
    write_mesh(a.string(), f.part, f.mesh, &quality);
    const std::locale old = std::locale::global(std::locale(std::locale::classic(), new Comma));
    try {
      write_mesh(b.string(), f.part, f.mesh, &quality);
    } catch (...) {
      std::locale::global(old);
      throw;
    }
    std::locale::global(old);
    CHECK(slurp(a) == slurp(b));
  }
}

TEST_CASE("a failing write leaves no file", "[io][mesh][atomic]") {
  const fs::path d = fresh_dir("atomic");
  const Fixture f = grid();
  SECTION("an unknown extension is named, with the supported ones") {
    CHECK_THROWS_WITH(
        write_mesh((d / "m.stl").string(), f.part, f.mesh),
        Catch::Contains("\".stl\"") && Catch::Contains(".msh, .vtu, .bdf, .inp, .obj, .off"));
    CHECK_THROWS_AS(write_mesh((d / "noext").string(), f.part, f.mesh), Error);
    CHECK(entries(d) == 0);
  }
  SECTION("a folder that does not exist") {
    for (const std::string& ext : kFormats) {
      CHECK_THROWS_AS(write_mesh((d / "missing" / ("m" + ext)).string(), f.part, f.mesh), Error);
    }
    CHECK(entries(d) == 0);
  }
  SECTION("a mesh that breaks the writer's preconditions") {
    QuadMesh bad = f.mesh;
    bad.elements[2].nodes[1] = 99;
    CHECK_THROWS_WITH(write_mesh((d / "m.msh").string(), f.part, bad),
                      Catch::Contains("element 2 refers to node 99"));
    std::vector<double> short_quality(2, 1.0);
    CHECK_THROWS_WITH(write_mesh((d / "m.vtu").string(), f.part, f.mesh, &short_quality),
                      Catch::Contains("2 quality values for 6 elements"));
    CHECK(entries(d) == 0);
  }
  SECTION("an old file survives a failed write") {
    write_mesh((d / "m.msh").string(), f.part, f.mesh);
    const std::string before = slurp(d / "m.msh");
    QuadMesh bad = f.mesh;
    bad.nodes[0].x = std::nan("");
    CHECK_THROWS_AS(write_mesh((d / "m.msh").string(), f.part, bad), Error);
    CHECK(slurp(d / "m.msh") == before);
    CHECK(entries(d) == 1);
  }
}

TEST_CASE("OBJ/OFF: a face on a non-manifold edge gets its own copies of its nodes", "[io][mesh]") {
  const fs::path d = fresh_dir("nonmanifold");
  Fixture f;
  f.part = build_part(laytracks::test::t_junction());
  f.mesh.nodes = {{0, 0, 0},  {10, 0, 0},  {10, 12, 0}, {0, 12, 0},
                  {24, 0, 0}, {24, 12, 0}, {10, 12, 5}, {10, 0, 5}};
  f.mesh.elements = {quad(0, 1, 2, 3, 0), quad(1, 4, 5, 2, 1), quad(1, 2, 6, 7, 2)};
  for (const std::string ext : {".obj", ".off"}) {
    INFO(ext);
    write_mesh((d / ("t" + ext)).string(), f.part, f.mesh);
    const Summary s = independent_summary(d / ("t" + ext));
    CHECK(s.points == f.mesh.nodes.size() + 4);
    CHECK(s.cells == 3);
    CHECK(close(s.cellsum, cell_sum(f.mesh)));
  }
  // The formats with ids keep the mesh as it is.
  write_mesh((d / "t.inp").string(), f.part, f.mesh);
  CHECK(independent_summary(d / "t.inp").points == f.mesh.nodes.size());
}
