// Reading the B-Rep JSON format: syntax with nlohmann::json, then a check of every type and
// value the format states (../shared/spec/brep-json.md) on the DOM. Positions for messages are
// found only when something is wrong, by scanning the text again (json_locate.hpp).
#include "laytracks/io/brep_json.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "json_locate.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/brep/error.hpp"

namespace laytracks {

namespace {

using nlohmann::json;
namespace loc = json_locate;

constexpr std::string_view kFormatTag = "brep/1";
/// The largest coordinate magnitude accepted; beyond it a part is refused as absurd.
constexpr double kMaxCoordinate = Tolerances::kMaxCoordinate;
constexpr std::size_t kMaxQuotedLiteral = 40;

/// "source:line:column: message" for the byte at `offset` of `text`.
[[noreturn]] void fail_at(std::string_view text,
                          const std::string& source,
                          std::size_t offset,
                          const std::string& message) {
  const loc::TextPosition at = loc::position_of(text, offset);
  throw InputError(source + ":" + std::to_string(at.line) + ":" + std::to_string(at.column) + ": " +
                   message);
}

std::string in_quotes(std::string_view s) { return "\"" + std::string(s) + "\""; }

/// "an array of 2 values", "an object", ... for a value whose literal text is not shown.
std::string kind_of(const json& value) {
  if (value.is_object()) return "an object";
  if (value.is_array()) {
    if (value.empty()) return "an empty array";
    return "an array of " + std::to_string(value.size()) +
           (value.size() == 1 ? " value" : " values");
  }
  return "a value";
}

/// True for a number written without fraction or exponent: -?[0-9]+.
bool is_integer_literal(std::string_view literal) {
  if (!literal.empty() && literal.front() == '-') literal.remove_prefix(1);
  return !literal.empty() && literal.find_first_not_of("0123456789") == std::string_view::npos;
}

/// The edit distance between two short strings (for "did you mean").
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// The path to the value being checked, as a chain of steps living on the stack: making one
/// costs nothing, and it becomes a JsonPath (with strings) only when an error is reported.
/// A Where refers to its parent, so always name the parent in a variable that outlives it.
class Where {
 public:
  Where() = default;  ///< the root
  Where child(const char* key) const { return Where(this, key, 0); }
  Where child(std::size_t index) const { return Where(this, nullptr, index); }

  loc::JsonPath path() const {
    loc::JsonPath steps;
    for (const Where* w = this; w->parent_ != nullptr; w = w->parent_) {
      if (w->key_ != nullptr) {
        steps.emplace_back(w->key_);
      } else {
        steps.emplace_back(w->index_);
      }
    }
    std::reverse(steps.begin(), steps.end());
    return steps;
  }

  /// How messages name the value: `patches[1].loops[0]`; the root object is "the root object".
  std::string name() const { return parent_ == nullptr ? "the root object" : to_string(path()); }

 private:
  Where(const Where* parent, const char* key, std::size_t index)
      : parent_(parent), key_(key), index_(index) {}

  const Where* parent_ = nullptr;
  const char* key_ = nullptr;
  std::size_t index_ = 0;
};

/// The keys an object of the format may hold.
using KnownKeys = std::vector<const char*>;
const KnownKeys kRootKeys = {"laytracks", "units",      "vertices", "patches",
                             "arcs",      "dual_graph", "mesh"};
const KnownKeys kPatchKeys = {"name", "loops"};
const KnownKeys kArcKeys = {"from", "to", "via"};
const KnownKeys kMeshKeys = {"size", "mode", "dtheta_deg"};

/// Checks the DOM of a syntactically valid document against the format and fills a RawPart.
/// Each check throws InputError at the position of the offending value, key or object.
class PartReader {
 public:
  PartReader(std::string_view text, const std::string& source) : text_(text), source_(source) {}

  RawPart read(const json& root) const {
    const Where at;
    if (!root.is_object()) {
      fail(at, "expected an object at the root of a laytracks part, found " + found(root, at));
    }
    check_tag(root, at);
    check_keys(root, at, kRootKeys);
    RawPart part;
    part.source = source_;
    if (root.contains("units")) part.units = read_units(root["units"], at.child("units"));
    const Where at_vertices = at.child("vertices");
    part.vertices =
        read_vertices(require(root, at, "vertices", "an array of [x, y, z] points"), at_vertices);
    const Where at_patches = at.child("patches");
    part.patches = read_patches(require(root, at, "patches", "an array of patches"), at_patches,
                                part.vertices.size());
    if (root.contains("arcs")) {
      const Where at_arcs = at.child("arcs");
      part.arcs = read_arcs(root["arcs"], at_arcs, part.vertices.size());
    }
    if (root.contains("dual_graph")) {
      const Where at_graph = at.child("dual_graph");
      part.dual_graph = read_dual_graph(root["dual_graph"], at_graph, part.patches.size());
    }
    if (root.contains("mesh")) {
      const Where at_mesh = at.child("mesh");
      part.mesh = read_mesh(root["mesh"], at_mesh);
    }
    return part;
  }

 private:
  // ---- Reporting ----

  /// Throws with the position of the value at `at`.
  [[noreturn]] void fail(const Where& at, const std::string& message) const {
    const std::optional<loc::Span> span = loc::locate_value(text_, at.path());
    fail_at(text_, source_, span ? span->begin : 0, message);
  }

  /// Throws with the position of the key named by the last step of `at`.
  [[noreturn]] void fail_key(const Where& at, const std::string& message) const {
    const std::optional<std::size_t> offset = loc::locate_key(text_, at.path());
    fail_at(text_, source_, offset.value_or(0), message);
  }

  /// The value as written in the file (`1.5`, `"1"`, `null`), or its kind for a container.
  std::string found(const json& value, const Where& at) const {
    if (value.is_structured()) return kind_of(value);
    const std::optional<loc::Span> span = loc::locate_value(text_, at.path());
    if (!span) return kind_of(value);
    std::string literal(text_.substr(span->begin, span->end - span->begin));
    if (literal.size() > kMaxQuotedLiteral) literal = literal.substr(0, kMaxQuotedLiteral) + "...";
    return literal;
  }

  // ---- Objects and keys ----

  void check_keys(const json& object, const Where& at, const KnownKeys& known) const {
    for (const auto& item : object.items()) {
      const std::string& key = item.key();
      const auto is_key = [&](const char* k) { return key == k; };
      if (std::any_of(known.begin(), known.end(), is_key)) continue;
      std::string list;
      const char* closest = nullptr;
      std::size_t closest_distance = 3;  // suggest near misses only: typos, not other words
      for (const char* k : known) {
        list += (list.empty() ? "" : ", ") + std::string(k);
        const std::size_t distance = edit_distance(key, k);
        if (distance < closest_distance) {
          closest = k;
          closest_distance = distance;
        }
      }
      const std::string suggestion =
          closest != nullptr ? " (did you mean " + in_quotes(closest) + "?)" : "";
      fail_key(at.child(key.c_str()), "unknown key " + in_quotes(key) + " in " + at.name() +
                                          suggestion + "; the known keys are: " + list);
    }
  }

  /// The value of a required key; `what` says what it holds, for the message when it is absent.
  const json& require(const json& object,
                      const Where& at,
                      const char* key,
                      const std::string& what) const {
    const auto it = object.find(key);
    if (it == object.end()) {
      fail(at, "missing required key " + in_quotes(key) + " in " + at.name() + " (" + what + ")");
    }
    return *it;
  }

  void check_tag(const json& root, const Where& at) const {
    const std::string expected = "\"laytracks\": " + in_quotes(kFormatTag);
    const auto it = root.find("laytracks");
    if (it == root.end()) {
      fail(at, "not a laytracks part: the key \"laytracks\" is missing (a part file holds " +
                   expected + ")");
    }
    const Where at_tag = at.child("laytracks");
    if (!it->is_string()) {
      fail(at_tag, "expected the string " + in_quotes(kFormatTag) + " for laytracks, found " +
                       found(*it, at_tag));
    }
    if (it->get_ref<const std::string&>() != kFormatTag) {
      fail(at_tag, "unsupported format " + found(*it, at_tag) +
                       " in laytracks: this version of laytracks reads " + in_quotes(kFormatTag));
    }
  }

  std::string read_units(const json& value, const Where& at) const {
    if (!value.is_string()) fail(at, "expected a string for units, found " + found(value, at));
    return value.get<std::string>();
  }

  // ---- Numbers and indices ----

  double read_coordinate(const json& value, const Where& at) const {
    if (!value.is_number()) {
      fail(at, "expected a number for " + at.name() + ", found " + found(value, at));
    }
    const double x = value.get<double>();
    if (!std::isfinite(x)) fail(at, "non-finite number for " + at.name());
    if (std::fabs(x) > kMaxCoordinate) {
      char limit[32];
      std::snprintf(limit, sizeof limit, "%g", kMaxCoordinate);
      fail(at, "absurd coordinate " + found(value, at) + " for " + at.name() +
                   ": coordinates are limited to a magnitude of " + limit);
    }
    return x;
  }

  /// An [x, y, z] array of 3 finite numbers within the coordinate limit.
  Vec3 read_point(const json& value, const Where& at) const {
    if (!value.is_array() || value.size() != 3) {
      fail(at, "expected an array of 3 numbers for " + at.name() + ", found " + found(value, at));
    }
    const Where at_x = at.child(std::size_t{0});
    const Where at_y = at.child(std::size_t{1});
    const Where at_z = at.child(std::size_t{2});
    return {read_coordinate(value[0], at_x), read_coordinate(value[1], at_y),
            read_coordinate(value[2], at_z)};
  }

  /// A JSON integer in [0, count) indexing `nouns` ("vertices" or "patches"): `noun` is the
  /// singular, for the message. 2.0 and 1e0 are refused (written as floats); -0 is index 0.
  std::int64_t read_index(const json& value,
                          const Where& at,
                          std::size_t count,
                          const std::string& noun,
                          const std::string& nouns) const {
    if (value.is_number_unsigned() ||
        (value.is_number_integer() && value.get<std::int64_t>() >= 0)) {
      const std::uint64_t i = value.get<std::uint64_t>();
      if (i < count) return static_cast<std::int64_t>(i);
      fail_index_range(value, at, count, noun, nouns);
    }
    // nlohmann reads an integer beyond 64 bits as a float: it is still an integer, out of range.
    const bool huge_integer = value.is_number_float() && is_integer_literal(found(value, at));
    if (value.is_number_integer() || (huge_integer && value.get<double>() < 0.0)) {
      fail(at, "negative " + noun + " index " + found(value, at) + " for " + at.name() +
                   ": indices start at 0");
    }
    if (huge_integer) fail_index_range(value, at, count, noun, nouns);
    fail(at, "expected a " + noun + " index (an integer from 0) for " + at.name() + ", found " +
                 found(value, at));
  }

  [[noreturn]] void fail_index_range(const json& value,
                                     const Where& at,
                                     std::size_t count,
                                     const std::string& noun,
                                     const std::string& nouns) const {
    const std::string range = count == 0
                                  ? "no " + nouns
                                  : std::to_string(count) + " " + (count == 1 ? noun : nouns) +
                                        ", so indices run from 0 to " + std::to_string(count - 1);
    fail(at, noun + " index " + found(value, at) + " for " + at.name() +
                 " is out of range: the part has " + range);
  }

  // ---- The sections of a part ----

  std::vector<Vec3> read_vertices(const json& value, const Where& at) const {
    if (!value.is_array()) {
      fail(at, "expected an array of [x, y, z] points for vertices, found " + found(value, at));
    }
    std::vector<Vec3> vertices;
    vertices.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      const Where at_vertex = at.child(i);
      vertices.push_back(read_point(value[i], at_vertex));
    }
    return vertices;
  }

  std::vector<RawPatch> read_patches(const json& value,
                                     const Where& at,
                                     std::size_t vertex_count) const {
    if (!value.is_array()) {
      fail(at, "expected an array of patches for patches, found " + found(value, at));
    }
    if (value.empty()) fail(at, "patches is empty: a part needs at least one patch");
    std::vector<RawPatch> patches;
    patches.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      const Where at_patch = at.child(i);
      patches.push_back(read_patch(value[i], at_patch, vertex_count));
    }
    check_unique_names(patches, at);
    return patches;
  }

  /// The spec: a patch name, when given, is unique in the file. Quadratic only in the rare
  /// case of a clash; the search itself is a sort.
  void check_unique_names(const std::vector<RawPatch>& patches, const Where& at) const {
    std::vector<std::pair<std::string_view, std::size_t>> named;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      if (patches[i].name) named.emplace_back(*patches[i].name, i);
    }
    std::sort(named.begin(), named.end());
    for (std::size_t k = 1; k < named.size(); ++k) {
      if (named[k].first != named[k - 1].first) continue;
      const Where at_patch = at.child(named[k].second);
      const Where at_name = at_patch.child("name");
      fail(at_name, "patch name " + in_quotes(named[k].first) + " of " + at_patch.name() +
                        " is already the name of patches[" + std::to_string(named[k - 1].second) +
                        "]; names must be unique");
    }
  }

  RawPatch read_patch(const json& value, const Where& at, std::size_t vertex_count) const {
    if (!value.is_object()) {
      fail(at, "expected an object {\"name\": ..., \"loops\": [...]} for " + at.name() +
                   ", found " + found(value, at));
    }
    check_keys(value, at, kPatchKeys);
    RawPatch patch;
    if (value.contains("name")) {
      const json& name = value["name"];
      const Where at_name = at.child("name");
      if (!name.is_string() || name.get_ref<const std::string&>().empty()) {
        fail(at_name, "expected a non-empty string for " + at_name.name() + ", found " +
                          found(name, at_name));
      }
      patch.name = name.get<std::string>();
    }
    const json& loops = require(value, at, "loops", "an array of loops of vertex indices");
    const Where at_loops = at.child("loops");
    if (!loops.is_array()) {
      fail(at_loops, "expected an array of loops for " + at_loops.name() + ", found " +
                         found(loops, at_loops));
    }
    if (loops.empty()) {
      fail(at_loops, at_loops.name() + " is empty: a patch needs at least its outer loop");
    }
    patch.loops.reserve(loops.size());
    for (std::size_t l = 0; l < loops.size(); ++l) {
      const Where at_loop = at_loops.child(l);
      patch.loops.push_back(read_loop(loops[l], at_loop, vertex_count));
    }
    return patch;
  }

  std::vector<std::int64_t> read_loop(const json& value,
                                      const Where& at,
                                      std::size_t vertex_count) const {
    if (!value.is_array()) {
      fail(at,
           "expected an array of vertex indices for " + at.name() + ", found " + found(value, at));
    }
    std::vector<std::int64_t> loop;
    loop.reserve(value.size());
    for (std::size_t k = 0; k < value.size(); ++k) {
      const Where at_index = at.child(k);
      loop.push_back(read_index(value[k], at_index, vertex_count, "vertex", "vertices"));
    }
    return loop;
  }

  std::vector<RawArc> read_arcs(const json& value,
                                const Where& at,
                                std::size_t vertex_count) const {
    if (!value.is_array()) {
      fail(at, "expected an array of arcs for arcs, found " + found(value, at));
    }
    std::vector<RawArc> arcs;
    arcs.reserve(value.size());
    for (std::size_t i = 0; i < value.size(); ++i) {
      const Where at_arc = at.child(i);
      arcs.push_back(read_arc(value[i], at_arc, vertex_count));
    }
    return arcs;
  }

  RawArc read_arc(const json& value, const Where& at, std::size_t vertex_count) const {
    if (!value.is_object()) {
      fail(at, "expected an object {\"from\": a, \"to\": b, \"via\": [x, y, z]} for " + at.name() +
                   ", found " + found(value, at));
    }
    check_keys(value, at, kArcKeys);
    const json& from = require(value, at, "from", "the index of the arc's first vertex");
    const json& to = require(value, at, "to", "the index of the arc's last vertex");
    const json& via = require(value, at, "via", "a point [x, y, z] on the arc");
    const Where at_from = at.child("from");
    const Where at_to = at.child("to");
    const Where at_via = at.child("via");
    RawArc arc;
    arc.from = read_index(from, at_from, vertex_count, "vertex", "vertices");
    arc.to = read_index(to, at_to, vertex_count, "vertex", "vertices");
    arc.via = read_point(via, at_via);
    return arc;
  }

  std::vector<std::array<std::int64_t, 2>> read_dual_graph(const json& value,
                                                           const Where& at,
                                                           std::size_t patch_count) const {
    if (!value.is_array()) {
      fail(at, "expected an array of [i, j] patch index pairs for dual_graph, found " +
                   found(value, at));
    }
    std::vector<std::array<std::int64_t, 2>> pairs;
    pairs.reserve(value.size());
    for (std::size_t k = 0; k < value.size(); ++k) {
      const json& pair = value[k];
      const Where at_pair = at.child(k);
      if (!pair.is_array() || pair.size() != 2) {
        fail(at_pair, "expected a pair [i, j] of patch indices for " + at_pair.name() + ", found " +
                          found(pair, at_pair));
      }
      const Where at_i = at_pair.child(std::size_t{0});
      const Where at_j = at_pair.child(std::size_t{1});
      const std::int64_t i = read_index(pair[0], at_i, patch_count, "patch", "patches");
      const std::int64_t j = read_index(pair[1], at_j, patch_count, "patch", "patches");
      if (i == j) {
        fail(at_pair, at_pair.name() + " pairs patch " + std::to_string(i) +
                          " with itself: a neighbour pair needs two different patches");
      }
      pairs.push_back({i, j});
    }
    return pairs;
  }

  RawMeshParams read_mesh(const json& value, const Where& at) const {
    if (!value.is_object()) {
      fail(at, "expected an object for mesh, found " + found(value, at));
    }
    check_keys(value, at, kMeshKeys);
    RawMeshParams mesh;
    if (value.contains("size")) {
      const json& size = value["size"];
      const Where at_size = at.child("size");
      if (!size.is_number() || !(size.get<double>() > 0.0) || !std::isfinite(size.get<double>())) {
        fail(at_size, "expected a positive number for mesh.size (the target element size), found " +
                          found(size, at_size));
      }
      mesh.size = size.get<double>();
    }
    if (value.contains("mode")) {
      const json& mode = value["mode"];
      const Where at_mode = at.child("mode");
      if (mode == "uniform") {
        mesh.mode = MeshMode::Uniform;
      } else if (mode == "adaptive") {
        mesh.mode = MeshMode::Adaptive;
      } else {
        fail(at_mode,
             "expected \"uniform\" or \"adaptive\" for mesh.mode, found " + found(mode, at_mode));
      }
    }
    if (value.contains("dtheta_deg")) {
      const json& angle = value["dtheta_deg"];
      const Where at_angle = at.child("dtheta_deg");
      if (!angle.is_number() || !(angle.get<double>() > 0.0 && angle.get<double>() <= 90.0)) {
        fail(at_angle, "expected an angle in degrees in (0, 90] for mesh.dtheta_deg, found " +
                           found(angle, at_angle));
      }
      mesh.dtheta_deg = angle.get<double>();
    }
    return mesh;
  }

  std::string_view text_;
  const std::string& source_;
};

// ---- The stages before the DOM is checked ----

void check_not_empty(const std::string& text, const std::string& source) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    fail_at(text, source, 0, "empty file");
  }
}

void check_nesting(const std::string& text, const std::string& source) {
  if (const auto offset = loc::find_excess_nesting(text, kMaxJsonDepth)) {
    fail_at(text, source, *offset,
            "arrays and objects nested deeper than " + std::to_string(kMaxJsonDepth) +
                " levels (a laytracks part needs 4)");
  }
}

/// nlohmann's message without its "[json.exception...] parse error at ...: " prefix.
std::string bare_message(const nlohmann::json::exception& e) {
  std::string message = e.what();
  const std::size_t colon = message.find(": ");
  const std::size_t bracket = message.find("] ");
  if (colon != std::string::npos) return message.substr(colon + 2);
  if (bracket != std::string::npos) return message.substr(bracket + 2);
  return message;
}

/// The DOM of the text, or InputError at the first syntax error. nlohmann reports where it
/// stopped reading, which is not always where the mistake is (the start of a bad number, an
/// unclosed string), so the text is scanned again to say what and where.
json parse_document(const std::string& text, const std::string& source) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    if (const auto error = loc::find_syntax_error(text)) {
      fail_at(text, source, error->offset, error->message);
    }
    // The scanner found nothing: fall back on nlohmann's own position and words.
    const auto* parse_error = dynamic_cast<const json::parse_error*>(&e);
    const std::size_t offset =
        parse_error != nullptr && parse_error->byte > 0 ? parse_error->byte - 1 : 0;
    fail_at(text, source, offset, "malformed JSON: " + bare_message(e));
  }
}

void check_duplicate_keys(const std::string& text, const std::string& source) {
  if (const auto duplicate = loc::find_duplicate_key(text)) {
    const loc::TextPosition first = loc::position_of(text, duplicate->first);
    const std::string object =
        duplicate->object.empty() ? "the root object" : loc::to_string(duplicate->object);
    fail_at(text, source, duplicate->second,
            "duplicate key " + in_quotes(duplicate->key) + " in " + object +
                " (first given at line " + std::to_string(first.line) + ", column " +
                std::to_string(first.column) + "); a key may appear only once");
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

// Order of the checks: emptiness, nesting (before nlohmann recurses), syntax, duplicate keys
// (nlohmann keeps the last silently), then the format's types and values on the DOM.
RawPart parse_brep_json(const std::string& text, const std::string& source) {
  check_not_empty(text, source);
  check_nesting(text, source);
  const json root = parse_document(text, source);
  check_duplicate_keys(text, source);
  return PartReader(text, source).read(root);
}

// Reads in binary so that offsets in messages are byte offsets of the file as it is.
RawPart read_brep_json(const std::string& path) {
  errno = 0;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw InputError("cannot read " + path + ": " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) text.append(buffer, n);
  if (std::ferror(file.get()) != 0) {
    throw InputError("cannot read " + path + ": " + std::strerror(errno));
  }
  return parse_brep_json(text, path);
}

}  // namespace laytracks
