// A reader for Gmsh MSH 4.1 ASCII, enough for surface meshes: ours and Gmsh's own output.
// Format: the "MSH file format" section of the Gmsh reference manual (version 4.1).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "laytracks/brep/error.hpp"
#include "laytracks/io/msh_reader.hpp"

namespace laytracks {

namespace {

/// Whitespace-separated tokens with the line each starts on, for "path:line:" messages.
class Lexer {
 public:
  Lexer(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path_ + ":" + std::to_string(line_) + ": " + what);
  }

  /// Skips blanks; true when nothing but blanks is left.
  bool at_end() {
    skip_blanks();
    return pos_ == text_.size();
  }

  std::string_view word(const char* what) {
    if (at_end()) fail("the file ends where " + std::string(what) + " was expected");
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_blank(text_[pos_])) ++pos_;
    return std::string_view(text_).substr(start, pos_ - start);
  }

  std::int64_t integer(const char* what) {
    const std::string_view w = word(what);
    std::int64_t v = 0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size()) {
      fail("expected " + std::string(what) + " (an integer), found \"" + std::string(w) + "\"");
    }
    return v;
  }

  /// A non-negative integer no larger than `max`.
  std::uint64_t count(const char* what, std::uint64_t max = UINT32_MAX) {
    const std::int64_t v = integer(what);
    if (v < 0 || static_cast<std::uint64_t>(v) > max) {
      fail(std::string(what) + " " + std::to_string(v) + " is out of range");
    }
    return static_cast<std::uint64_t>(v);
  }

  double real(const char* what) {
    const std::string_view w = word(what);
    double v = 0.0;
    const auto r = std::from_chars(w.data(), w.data() + w.size(), v);
    if (r.ec != std::errc() || r.ptr != w.data() + w.size() || !std::isfinite(v)) {
      fail("expected " + std::string(what) + " (a finite number), found \"" + std::string(w) +
           "\"");
    }
    return v;
  }

  /// A name between double quotes, on one line (Gmsh has no escapes).
  std::string quoted(const char* what) {
    if (at_end() || text_[pos_] != '"') fail("expected " + std::string(what) + " in quotes");
    const std::size_t close = text_.find('"', pos_ + 1);
    const std::size_t eol = text_.find('\n', pos_);
    if (close == std::string::npos || close > eol) fail("unterminated " + std::string(what));
    std::string s = text_.substr(pos_ + 1, close - pos_ - 1);
    pos_ = close + 1;
    return s;
  }

  void expect(std::string_view keyword) {
    const std::string_view w = word(std::string(keyword).c_str());
    if (w != keyword) {
      fail("expected " + std::string(keyword) + ", found \"" + std::string(w) + "\"");
    }
  }

  /// Skips to the line after "$End<name>".
  void skip_section(const std::string& name) {
    const std::string end = "$End" + name;
    while (!at_end()) {
      if (word(end.c_str()) == end) return;
    }
    fail("section $" + name + " has no " + end);
  }

 private:
  static bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }
  void skip_blanks() {
    while (pos_ < text_.size() && is_blank(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }

  std::string path_;
  std::string text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
};

/// Nodes per element for the types a surface mesh file may hold; 0 for others.
std::size_t nodes_of_type(std::int64_t type) {
  switch (type) {
    case 15:
      return 1;  // point
    case 1:
      return 2;  // 2-node line
    case 8:
      return 3;  // 3-node line
    case 26:
      return 4;  // 4-node line
    case 27:
      return 5;  // 5-node line
    case 28:
      return 6;  // 6-node line
    case 2:
      return 3;  // 3-node triangle
    case 3:
      return 4;  // 4-node quadrangle
    case 9:
      return 6;  // 6-node triangle
    case 10:
      return 9;  // 9-node quadrangle
    case 16:
      return 8;  // 8-node quadrangle
    case 20:
      return 9;  // 9-node triangle
    case 21:
      return 10;  // 10-node triangle
    default:
      return 0;
  }
}

/// i for a physical name "shell<i>", else -1.
std::int64_t shell_of_name(const std::string& name) {
  if (name.size() <= 5 || name.compare(0, 5, "shell") != 0) return -1;
  std::int64_t v = -1;
  const auto r = std::from_chars(name.data() + 5, name.data() + name.size(), v);
  if (r.ec != std::errc() || r.ptr != name.data() + name.size() || v < 0 || v > UINT32_MAX) {
    return -1;
  }
  return v;
}

struct Reader {
  Lexer lex;
  std::map<std::int64_t, std::string> surface_names;  ///< physical surface tag -> name
  std::map<std::int64_t, std::vector<std::int64_t>> surface_physicals;  ///< entity -> groups
  std::vector<std::pair<std::uint64_t, Vec3>> nodes;                    ///< (tag, position)
  bool have_nodes = false;
  bool have_elements = false;
  std::vector<std::pair<std::uint64_t, MeshElement>> elements;  ///< (tag, element)
  std::int64_t max_surface = 0;

  void mesh_format() {
    const std::string_view version = lex.word("the MSH version");
    if (version != "4.1") {
      lex.fail("MSH version " + std::string(version) +
               " is not supported: only 4.1 ASCII is (gmsh -format msh41)");
    }
    if (lex.integer("the file type") != 0) {
      lex.fail("binary MSH is not supported: only 4.1 ASCII is (gmsh option -bin off)");
    }
    if (lex.integer("the data size") != 8) lex.fail("the data size must be 8");
    lex.expect("$EndMeshFormat");
  }

  void physical_names() {
    const std::uint64_t n = lex.count("the number of physical names");
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::int64_t dim = lex.integer("a physical dimension");
      const std::int64_t tag = lex.integer("a physical tag");
      std::string name = lex.quoted("a physical name");
      if (dim == 2) surface_names[tag] = std::move(name);
    }
    lex.expect("$EndPhysicalNames");
  }

  void entities() {
    std::uint64_t counts[4];
    for (auto& c : counts) c = lex.count("an entity count");
    for (int dim = 0; dim < 4; ++dim) {
      for (std::uint64_t i = 0; i < counts[dim]; ++i) {
        const std::int64_t tag = lex.integer("an entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) lex.real("a bounding-box coordinate");
        std::vector<std::int64_t> physicals(lex.count("the number of physical tags"));
        for (auto& p : physicals) p = lex.integer("a physical tag");
        if (dim > 0) {
          const std::uint64_t bounding = lex.count("the number of bounding entities");
          for (std::uint64_t b = 0; b < bounding; ++b) lex.integer("a bounding entity tag");
        }
        if (dim == 2) {
          if (tag > 0) max_surface = std::max(max_surface, tag);
          surface_physicals[tag] = std::move(physicals);
        }
      }
    }
    lex.expect("$EndEntities");
  }

  void read_nodes() {
    if (have_nodes) lex.fail("a second $Nodes section");
    have_nodes = true;
    const std::uint64_t blocks = lex.count("the number of node blocks");
    lex.count("the number of nodes", UINT64_MAX);
    lex.count("the smallest node tag", UINT64_MAX);
    lex.count("the largest node tag", UINT64_MAX);
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = lex.integer("the entity dimension");
      lex.integer("the entity tag");
      const std::int64_t parametric = lex.integer("the parametric flag");
      const std::uint64_t n = lex.count("the number of nodes in the block");
      const std::size_t first = nodes.size();
      for (std::uint64_t i = 0; i < n; ++i) {
        nodes.emplace_back(lex.count("a node tag", UINT64_MAX), Vec3{});
      }
      const int extra = parametric != 0 && (dim == 1 || dim == 2) ? static_cast<int>(dim) : 0;
      for (std::uint64_t i = 0; i < n; ++i) {
        Vec3& x = nodes[first + i].second;
        x.x = lex.real("a node coordinate");
        x.y = lex.real("a node coordinate");
        x.z = lex.real("a node coordinate");
        for (int k = 0; k < extra; ++k) lex.real("a parametric coordinate");
      }
    }
    lex.expect("$EndNodes");
    std::sort(nodes.begin(), nodes.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      if (nodes[i].first == nodes[i - 1].first) {
        lex.fail("node tag " + std::to_string(nodes[i].first) + " appears twice in $Nodes");
      }
    }
    if (nodes.size() >= MeshElement::kNoNode) lex.fail("too many nodes");
  }

  std::uint32_t node_index(std::uint64_t tag) {
    const auto it = std::lower_bound(nodes.begin(), nodes.end(), tag,
                                     [](const auto& n, std::uint64_t t) { return n.first < t; });
    if (it == nodes.end() || it->first != tag) {
      lex.fail("an element refers to node " + std::to_string(tag) + ", which $Nodes lacks");
    }
    return static_cast<std::uint32_t>(it - nodes.begin());
  }

  std::uint32_t shell_of_entity(std::int64_t entity) const {
    const auto it = surface_physicals.find(entity);
    if (it == surface_physicals.end()) return 0;
    for (const std::int64_t group : it->second) {
      const auto name = surface_names.find(group);
      if (name == surface_names.end()) continue;
      const std::int64_t shell = shell_of_name(name->second);
      if (shell >= 0) return static_cast<std::uint32_t>(shell);
    }
    return 0;
  }

  void read_elements() {
    if (!have_nodes) lex.fail("$Elements comes before $Nodes");
    if (have_elements) lex.fail("a second $Elements section");
    have_elements = true;
    const std::uint64_t blocks = lex.count("the number of element blocks");
    lex.count("the number of elements", UINT64_MAX);
    lex.count("the smallest element tag", UINT64_MAX);
    lex.count("the largest element tag", UINT64_MAX);
    for (std::uint64_t b = 0; b < blocks; ++b) {
      const std::int64_t dim = lex.integer("the entity dimension");
      const std::int64_t entity = lex.integer("the entity tag");
      const std::int64_t type = lex.integer("the element type");
      const std::uint64_t n = lex.count("the number of elements in the block", UINT64_MAX);
      const std::size_t per = nodes_of_type(type);
      if (dim == 3) lex.fail("volume elements (type " + std::to_string(type) + ") are not read");
      if (dim < 0 || dim > 3) lex.fail("entity dimension " + std::to_string(dim));
      if (per == 0) lex.fail("element type " + std::to_string(type) + " is not read");
      const bool keep = dim == 2;
      if (keep && type != 2 && type != 3) {
        lex.fail("element type " + std::to_string(type) +
                 " is not read: surfaces must hold 3-node triangles or 4-node quads");
      }
      if (keep && entity <= 0) lex.fail("surface entity tag " + std::to_string(entity));
      if (keep) max_surface = std::max(max_surface, entity);
      const std::uint32_t shell = keep ? shell_of_entity(entity) : 0;
      for (std::uint64_t i = 0; i < n; ++i) {
        const std::uint64_t tag = lex.count("an element tag", UINT64_MAX);
        MeshElement e;
        e.nodes = {MeshElement::kNoNode, MeshElement::kNoNode, MeshElement::kNoNode,
                   MeshElement::kNoNode};
        for (std::size_t k = 0; k < per; ++k) {
          const std::uint64_t node = lex.count("a node tag", UINT64_MAX);
          if (keep) e.nodes[k] = node_index(node);
        }
        if (!keep) continue;
        e.patch = PatchId(static_cast<std::size_t>(entity - 1));
        e.shell = shell;
        elements.emplace_back(tag, e);
      }
    }
    lex.expect("$EndElements");
    std::sort(elements.begin(), elements.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 1; i < elements.size(); ++i) {
      if (elements[i].first == elements[i - 1].first) {
        lex.fail("element tag " + std::to_string(elements[i].first) + " appears twice");
      }
    }
  }

  void run() {
    bool first = true;
    while (!lex.at_end()) {
      const std::string_view w = lex.word("a section");
      if (w.empty() || w[0] != '$') {
        lex.fail("expected a section such as $Nodes, found \"" + std::string(w) + "\"");
      }
      const std::string name(w.substr(1));
      if (first && name != "MeshFormat") lex.fail("not a Gmsh MSH file: no $MeshFormat first");
      first = false;
      if (name == "MeshFormat") {
        mesh_format();
      } else if (name == "PhysicalNames") {
        physical_names();
      } else if (name == "Entities") {
        entities();
      } else if (name == "Nodes") {
        read_nodes();
      } else if (name == "Elements") {
        read_elements();
      } else {
        lex.skip_section(name);  // unknown sections are ignored, as the format says
      }
    }
    if (first) lex.fail("empty file: not a Gmsh MSH file");
    if (!have_nodes) lex.fail("no $Nodes section");
    if (!have_elements) lex.fail("no $Elements section");
  }
};

}  // namespace

QuadMesh read_msh(const std::string& path, std::vector<std::string>* group_names) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error("cannot read " + path + ": the read failed");

  Reader r{Lexer(path, text.str()), {}, {}, {}, false, false, {}, 0};
  r.run();

  QuadMesh mesh;
  mesh.nodes.reserve(r.nodes.size());
  for (const auto& n : r.nodes) mesh.nodes.push_back(n.second);
  mesh.elements.reserve(r.elements.size());
  for (const auto& e : r.elements) mesh.elements.push_back(e.second);

  if (group_names != nullptr) {
    group_names->assign(static_cast<std::size_t>(r.max_surface), std::string());
    for (std::int64_t entity = 1; entity <= r.max_surface; ++entity) {
      const auto it = r.surface_physicals.find(entity);
      if (it == r.surface_physicals.end()) continue;
      for (const std::int64_t group : it->second) {
        const auto name = r.surface_names.find(group);
        if (name == r.surface_names.end() || shell_of_name(name->second) >= 0) continue;
        (*group_names)[static_cast<std::size_t>(entity - 1)] = name->second;
        break;
      }
    }
  }
  return mesh;
}

}  // namespace laytracks
