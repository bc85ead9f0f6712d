// The B-Rep JSON reader: every shared case parses, RawPart is filled exactly, and every refusal
// names what is wrong at the right line and column.
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include "laytracks/brep/error.hpp"
#include "laytracks/io/brep_json.hpp"
#include "test_support.hpp"

namespace laytracks {
namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

/// The message of the InputError thrown for `text` read as "part.json"; "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_brep_json(text, "part.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

/// A valid part with three vertices and one patch; `extra` is spliced in as more root keys.
std::string small_part(const std::string& extra = "") {
  return R"({"laytracks": "brep/1", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
 "patches": [{"loops": [[0, 1, 2]]}])" +
         extra + "}";
}

std::vector<std::string> shared_case_files() {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(test::cases_dir())) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

// ---- Valid input ----

TEST_CASE("every shared case parses", "[io][brep_json]") {
  const std::vector<std::string> files = shared_case_files();
  REQUIRE(files.size() >= 17);  // 9 parts and 8 external ones when this test was written
  for (const std::string& file : files) {
    INFO(file);
    const RawPart part = read_brep_json(file);
    CHECK(part.source == file);
    CHECK(!part.vertices.empty());
    CHECK(!part.patches.empty());
  }
}

TEST_CASE("shared cases: spot checks of counts and parameters", "[io][brep_json]") {
  const RawPart cube = read_brep_json(test::cases_dir() + "/closed_cube.json");
  CHECK(cube.vertices.size() == 8);
  CHECK(cube.patches.size() == 6);
  CHECK(cube.arcs.empty());
  CHECK(cube.units == "mm");

  const RawPart annulus = read_brep_json(test::cases_dir() + "/annulus.json");
  CHECK(annulus.vertices.size() == 12);
  CHECK(annulus.arcs.size() == 12);
  CHECK(annulus.patches.size() == 1);
  CHECK(annulus.patches[0].loops.size() == 2);
  REQUIRE(annulus.mesh.size);
  CHECK(*annulus.mesh.size == 1.0);

  const RawPart star = read_brep_json(test::cases_dir() + "/star_5.json");
  REQUIRE(star.mesh.mode);
  CHECK(*star.mesh.mode == MeshMode::Adaptive);
  REQUIRE(star.mesh.dtheta_deg);
  CHECK(*star.mesh.dtheta_deg == 12.0);
  CHECK(!star.mesh.size);

  const RawPart t = read_brep_json(test::cases_dir() + "/t_junction.json");
  CHECK(t.patches.size() == 3);
  CHECK(!t.dual_graph);
}

TEST_CASE("the spec's example fills RawPart exactly", "[io][brep_json]") {
  const std::string text = R"({
  "laytracks": "brep/1",
  "units": "in",
  "vertices": [[0,0,0], [40,0,0], [40,20,0], [0,20,0], [40,0,15], [40,20,15],
               [10,8,0], [12,10,0], [10,12,0], [8,10,0]],
  "patches": [
    {"name": "floor", "loops": [[0,1,2,3], [6,9,8,7]]},
    {"loops": [[1,4,5,2]]}
  ],
  "arcs": [{"from": 6, "to": 7, "via": [11.5, 8.5, 0]}],
  "dual_graph": [[0, 1]],
  "mesh": {"size": 2.0, "mode": "uniform", "dtheta_deg": 90}
})";
  const RawPart part = parse_brep_json(text, "example.json");
  CHECK(part.source == "example.json");
  CHECK(part.units == "in");
  REQUIRE(part.vertices.size() == 10);
  CHECK(part.vertices[4] == Vec3{40, 0, 15});
  CHECK(part.vertices[9] == Vec3{8, 10, 0});
  REQUIRE(part.patches.size() == 2);
  CHECK(part.patches[0].name == std::optional<std::string>("floor"));
  CHECK(!part.patches[1].name);
  CHECK(part.patches[0].loops ==
        std::vector<std::vector<std::int64_t>>{{0, 1, 2, 3}, {6, 9, 8, 7}});
  CHECK(part.patches[1].loops == std::vector<std::vector<std::int64_t>>{{1, 4, 5, 2}});
  REQUIRE(part.arcs.size() == 1);
  CHECK(part.arcs[0].from == 6);
  CHECK(part.arcs[0].to == 7);
  CHECK(part.arcs[0].via == Vec3{11.5, 8.5, 0});
  REQUIRE(part.dual_graph);
  REQUIRE(part.dual_graph->size() == 1);
  CHECK((*part.dual_graph)[0] == std::array<std::int64_t, 2>{0, 1});
  CHECK(part.mesh.size == std::optional<double>(2.0));
  CHECK(part.mesh.mode == std::optional<MeshMode>(MeshMode::Uniform));
  CHECK(part.mesh.dtheta_deg == std::optional<double>(90.0));
}

TEST_CASE("absent optional keys stay empty, units default to mm", "[io][brep_json]") {
  const RawPart part = parse_brep_json(small_part(), "p.json");
  CHECK(part.units == "mm");
  CHECK(part.arcs.empty());
  CHECK(!part.dual_graph);
  CHECK(!part.mesh.size);
  CHECK(!part.mesh.mode);
  CHECK(!part.mesh.dtheta_deg);
  CHECK(!part.patches[0].name);
}

TEST_CASE("numbers in every valid JSON form are accepted as coordinates", "[io][brep_json]") {
  const std::string text = R"({"laytracks": "brep/1",
 "vertices": [[1e3, -0.0, 7], [0.5e-3, 1E+2, -12], [1e12, -1e12, 0]],
 "patches": [{"loops": [[0, 1, 2]]}]})";
  const RawPart part = parse_brep_json(text, "p.json");
  CHECK(part.vertices[0] == Vec3{1000, 0, 7});
  CHECK(std::signbit(part.vertices[0].y));
  CHECK(part.vertices[1] == Vec3{0.0005, 100, -12});
  CHECK(part.vertices[2] == Vec3{1e12, -1e12, 0});
}

TEST_CASE("a UTF-8 byte order mark is skipped and not counted in columns", "[io][brep_json]") {
  CHECK(parse_brep_json("\xEF\xBB\xBF" + small_part(), "p.json").vertices.size() == 3);
  CHECK_THAT(error_of("\xEF\xBB\xBF{\"laytracks\": 1}"), StartsWith("part.json:1:15: "));
}

TEST_CASE("100,000 vertices parse in well under a second", "[io][brep_json][performance]") {
  const std::size_t n = 100000;
  std::string text = "{\"laytracks\": \"brep/1\",\n \"vertices\": [\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 6.283185307179586 * static_cast<double>(i) / static_cast<double>(n);
    text += "  [" + std::to_string(100.0 * std::cos(a)) + ", " +
            std::to_string(100.0 * std::sin(a)) + ", 0.0]" + (i + 1 < n ? ",\n" : "\n");
  }
  text += " ],\n \"patches\": [{\"name\": \"disc\", \"loops\": [[";
  for (std::size_t i = 0; i < n; ++i) text += (i > 0 ? "," : "") + std::to_string(i);
  text += "]]}]\n}\n";

  const auto start = std::chrono::steady_clock::now();
  const RawPart part = parse_brep_json(text, "big.json");
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  std::cout << "parse_brep_json: " << n << " vertices (" << text.size() / 1024 << " KiB) in "
            << elapsed.count() * 1000.0 << " ms\n";
  CHECK(part.vertices.size() == n);
  CHECK(part.patches[0].loops[0].size() == n);
  CHECK(elapsed.count() < 2.0);
}

// ---- Refusals before the DOM: emptiness, nesting, syntax, duplicate keys ----

TEST_CASE("an empty file is refused at 1:1", "[io][brep_json][errors]") {
  CHECK(error_of("") == "part.json:1:1: empty file");
  CHECK(error_of(" \n\t\r\n") == "part.json:1:1: empty file");
}

TEST_CASE("nesting deeper than kMaxJsonDepth is refused at the bracket that exceeds it",
          "[io][brep_json][errors]") {
  const std::string deep =
      std::string(kMaxJsonDepth + 1, '[') + std::string(kMaxJsonDepth + 1, ']');
  const std::string message = error_of(deep);
  CHECK_THAT(message, StartsWith("part.json:1:" + std::to_string(kMaxJsonDepth + 1) + ": "));
  CHECK_THAT(message, Contains("nested deeper than " + std::to_string(kMaxJsonDepth)));

  // On line 3, after a string full of brackets and an escaped quote, which do not count.
  const std::string text = "{\"laytracks\": \"brep/1\",\n \"units\": \"\\\"[[[[{{{{\",\n \"x\": " +
                           std::string(kMaxJsonDepth, '[') + std::string(kMaxJsonDepth, ']') + "}";
  CHECK_THAT(error_of(text),
             StartsWith("part.json:3:" + std::to_string(7 + kMaxJsonDepth - 1) + ": ") &&
                 Contains("nested deeper"));

  // Exactly kMaxJsonDepth levels is not a nesting error (it fails later, on the unknown key).
  const std::string limit =
      "{\"laytracks\": \"brep/1\", \"x\": " + std::string(kMaxJsonDepth - 1, '[') +
      std::string(kMaxJsonDepth - 1, ']') + "}";
  CHECK_THAT(error_of(limit), Contains("unknown key \"x\""));
}

TEST_CASE("malformed JSON is refused with its position and clean words",
          "[io][brep_json][errors]") {
  SECTION("an unexpected closing brace") {
    CHECK(error_of("{\n  \"laytracks\": \"brep/1\",\n  \"units\": }") ==
          "part.json:3:12: malformed JSON: unexpected '}', expected a value");
  }
  SECTION("the end of input inside an array names the unclosed array") {
    CHECK(error_of("{\n  \"vertices\": [[0, 0, 0]") ==
          "part.json:2:25: malformed JSON: unexpected end of input: the array opened at line 2, "
          "column 15 is not closed");
  }
  SECTION("an invalid number, at its first character") {
    CHECK_THAT(error_of("{\"vertices\": [[0, 1., 0]]}"),
               StartsWith("part.json:1:19: malformed JSON: invalid number '1.'"));
    CHECK_THAT(error_of("[\n 01]"),
               StartsWith("part.json:2:2: malformed JSON: invalid number '01'"));
  }
  SECTION("a missing comma") {
    CHECK(error_of("{\"vertices\": [[0, 0 0]]}") ==
          "part.json:1:21: malformed JSON: unexpected '0', expected ',' or ']'");
  }
  SECTION("a trailing comma") {
    CHECK_THAT(error_of("{\"vertices\": [[0, 0, 0],\n]}"),
               StartsWith("part.json:2:1: malformed JSON: unexpected ']' after ','"));
    CHECK_THAT(error_of("{\"units\": \"mm\",}"),
               StartsWith("part.json:1:16: malformed JSON: unexpected '}' after ','"));
  }
  SECTION("a missing colon") {
    CHECK(error_of("{\"units\" \"mm\"}") ==
          "part.json:1:10: malformed JSON: unexpected '\"', expected ':' after the key");
  }
  SECTION("an unquoted key, a comment, single quotes") {
    CHECK_THAT(error_of("{units: 1}"),
               StartsWith("part.json:1:2: malformed JSON: unexpected 'u', expected a key"));
    CHECK_THAT(error_of("{\n// the part\n}"),
               StartsWith("part.json:2:1: ") && Contains("comments are not allowed"));
    CHECK_THAT(error_of("{\"units\": 'mm'}"),
               StartsWith("part.json:1:11: ") && Contains("strings need double quotes"));
  }
  SECTION("invalid literals: a typo, NaN, Infinity") {
    CHECK_THAT(error_of("{\"units\": tru}"),
               StartsWith("part.json:1:11: malformed JSON: invalid literal 'tru'"));
    CHECK_THAT(error_of("[[0, NaN, 0]]"),
               StartsWith("part.json:1:6: malformed JSON: invalid literal 'NaN'"));
    CHECK_THAT(error_of("[[0, -Infinity, 0]]"),
               StartsWith("part.json:1:6: malformed JSON: invalid number '-'"));
  }
  SECTION("strings: unterminated, broken by a newline, bad escape, bad UTF-8") {
    CHECK(error_of("{\"units\": \"mm") ==
          "part.json:1:11: malformed JSON: unterminated string: missing closing quote");
    CHECK(error_of("{\"units\": \"mm,\n \"vertices\": []}") ==
          "part.json:1:11: malformed JSON: string not closed before the end of the line");
    CHECK(error_of("{\"units\": \"m\\m\"}") ==
          "part.json:1:13: malformed JSON: invalid escape '\\m' in a string");
    CHECK_THAT(error_of("{\"units\": \"\\ud800\"}"),
               StartsWith("part.json:1:12: malformed JSON: invalid \\u escape"));
    CHECK_THAT(error_of("{\"units\": \"m\xFFm\"}"),
               StartsWith("part.json:1:13: malformed JSON: invalid UTF-8"));
  }
  SECTION("text after the document") {
    CHECK_THAT(error_of("{}\n}"),
               StartsWith("part.json:2:1: malformed JSON: unexpected '}' after the end"));
  }
  SECTION("columns count characters, not bytes") {
    CHECK_THAT(error_of("{\"units\": \"\xC2\xB5m\" x}"),
               StartsWith("part.json:1:16: malformed JSON: unexpected 'x'"));
  }
}

TEST_CASE("a number that overflows a double is refused as non-finite", "[io][brep_json][errors]") {
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, 1e999, 0]]}") ==
        "part.json:2:19: non-finite number 1e999: it overflows a double");
  CHECK_THAT(error_of("[[-1e400, 0, 0]]"), StartsWith("part.json:1:3: non-finite number -1e400"));
}

TEST_CASE("a key given twice in one object is refused at its second occurrence",
          "[io][brep_json][errors]") {
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n  \"units\": \"mm\",\n  \"units\": \"in\"}") ==
        "part.json:3:3: duplicate key \"units\" in the root object (first given at line 2, "
        "column 3); a key may appear only once");
  CHECK_THAT(error_of(small_part(",\n \"patches\": []")),
             StartsWith("part.json:3:2: duplicate key \"patches\""));
  const std::string in_patch = R"({"laytracks": "brep/1", "vertices": [[0, 0, 0]],
 "patches": [{"loops": [[0]]},
   {"name": "a", "loops": [[0]], "name": "b"}]})";
  CHECK_THAT(error_of(in_patch),
             StartsWith("part.json:3:34: duplicate key \"name\" in patches[1] "));
  // The same key written with an escape is the same key.
  CHECK_THAT(error_of("{\"units\": \"mm\", \"unit\\u0073\": \"in\"}"),
             StartsWith("part.json:1:17: duplicate key \"units\""));
}

// ---- Refusals on the DOM: the format's types and values ----

TEST_CASE("the root must be an object with the laytracks tag", "[io][brep_json][errors]") {
  CHECK(error_of("\n  [1, 2]") ==
        "part.json:2:3: expected an object at the root of a laytracks part, found an array of 2 "
        "values");
  CHECK_THAT(error_of("{\"vertices\": []}"),
             StartsWith("part.json:1:1: not a laytracks part: the key \"laytracks\" is missing"));
  CHECK(error_of("{\n  \"laytracks\": \"brep/2\"}") ==
        "part.json:2:16: unsupported format \"brep/2\" in laytracks: this version of laytracks "
        "reads \"brep/1\"");
  CHECK_THAT(error_of("{\"laytracks\": 1}"),
             StartsWith("part.json:1:15: expected the string \"brep/1\" for laytracks, found 1"));
}

TEST_CASE("unknown keys are refused at the key, with the known ones listed",
          "[io][brep_json][errors]") {
  const std::string root = error_of(R"({"laytracks": "brep/1", "vertices": [],
  "patchs": []})");
  CHECK_THAT(root, StartsWith("part.json:2:3: unknown key \"patchs\" in the root object"));
  CHECK_THAT(root, Contains("did you mean \"patches\"?"));
  CHECK_THAT(root, Contains("laytracks, units, vertices, patches, arcs, dual_graph, mesh"));

  CHECK_THAT(error_of(small_part(", \"colour\": 1")),
             Contains("unknown key \"colour\"") && !Contains("did you mean"));
  CHECK_THAT(
      error_of(R"({"laytracks": "brep/1", "vertices": [[0, 0, 0]],
 "patches": [{"loops": [[0]], "nmae": "x"}]})"),
      StartsWith("part.json:2:31: unknown key \"nmae\" in patches[0] (did you mean \"name\"?)"));
  CHECK_THAT(
      error_of(small_part(", \"arcs\": [{\"from\": 0, \"to\": 1, \"mid\": [0, 0, 0]}]")),
      StartsWith("part.json:2:69: unknown key \"mid\" in arcs[0]") && Contains("from, to, via"));
  CHECK_THAT(error_of(small_part(",\n \"mesh\": {\"sizes\": 1}")),
             StartsWith("part.json:3:11: unknown key \"sizes\" in mesh (did you mean \"size\"?)"));
}

TEST_CASE("units must be a string", "[io][brep_json][errors]") {
  CHECK_THAT(error_of(small_part(", \"units\": 25.4")),
             StartsWith("part.json:2:48: expected a string for units, found 25.4"));
}

TEST_CASE("vertices must be arrays of 3 finite, sane numbers", "[io][brep_json][errors]") {
  CHECK_THAT(error_of("{\"laytracks\": \"brep/1\",\n \"patches\": []}"),
             StartsWith("part.json:1:1: missing required key \"vertices\" in the root object"));
  CHECK_THAT(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": {\"0\": 1}}"),
             StartsWith("part.json:2:14: expected an array of [x, y, z] points for vertices, "
                        "found an object"));
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, 0, 0],\n    [1, 0]]}") ==
        "part.json:3:5: expected an array of 3 numbers for vertices[1], found an array of 2 "
        "values");
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, 0, 0], 7]}") ==
        "part.json:2:26: expected an array of 3 numbers for vertices[1], found 7");
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, \"1\", 0]]}") ==
        "part.json:2:19: expected a number for vertices[0][1], found \"1\"");
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, 0, null]]}") ==
        "part.json:2:22: expected a number for vertices[0][2], found null");
  CHECK(error_of("{\"laytracks\": \"brep/1\",\n \"vertices\": [[0, 0, 0], [-2.5e13, 0, 0]]}") ==
        "part.json:2:27: absurd coordinate -2.5e13 for vertices[1][0]: coordinates are limited "
        "to a magnitude of 1e+12");
}

TEST_CASE("patches must be a non-empty array of objects with loops", "[io][brep_json][errors]") {
  const std::string head = "{\"laytracks\": \"brep/1\", \"vertices\": [[0, 0, 0], [1, 0, 0]],\n";
  CHECK_THAT(error_of(head + " \"units\": \"mm\"}"),
             StartsWith("part.json:1:1: missing required key \"patches\" in the root object"));
  CHECK(error_of(head + " \"patches\": []}") ==
        "part.json:2:13: patches is empty: a part needs at least one patch");
  CHECK_THAT(
      error_of(head + " \"patches\": {}}"),
      StartsWith("part.json:2:13: expected an array of patches for patches, found an object"));
  CHECK_THAT(error_of(head + " \"patches\": [[0, 1]]}"),
             StartsWith("part.json:2:14: expected an object") &&
                 Contains("for patches[0], found an array of 2 values"));
  CHECK(error_of(head + " \"patches\": [{\"name\": \"\", \"loops\": [[0, 1]]}]}") ==
        "part.json:2:23: expected a non-empty string for patches[0].name, found \"\"");
  CHECK(error_of(head + " \"patches\": [{\"name\": 3, \"loops\": [[0, 1]]}]}") ==
        "part.json:2:23: expected a non-empty string for patches[0].name, found 3");
  CHECK(error_of(head +
                 " \"patches\": [{\"name\": \"a\", \"loops\": [[0]]},\n"
                 "   {\"name\": \"b\", \"loops\": [[0]]}, {\"name\": \"a\", \"loops\": [[1]]}]}") ==
        "part.json:3:44: patch name \"a\" of patches[2] is already the name of patches[0]; names "
        "must be unique");
  CHECK(error_of(head + " \"patches\": [{\"name\": \"a\"}]}") ==
        "part.json:2:14: missing required key \"loops\" in patches[0] (an array of loops of "
        "vertex indices)");
  CHECK(error_of(head + " \"patches\": [{\"loops\": []}]}") ==
        "part.json:2:24: patches[0].loops is empty: a patch needs at least its outer loop");
  CHECK(error_of(head + " \"patches\": [{\"loops\": [0, 1]}]}") ==
        "part.json:2:25: expected an array of vertex indices for patches[0].loops[0], found 0");
}

TEST_CASE("vertex indices are JSON integers from 0 to the vertex count minus 1",
          "[io][brep_json][errors]") {
  const std::string head = "{\"laytracks\": \"brep/1\", \"vertices\": [[0, 0, 0], [1, 0, 0]],\n";
  const auto loop = [&](const std::string& indices) {
    return error_of(head + " \"patches\": [{\"loops\": [[0, 1],\n   [" + indices + "]]}]}");
  };
  CHECK(loop("0, 1.5") ==
        "part.json:3:8: expected a vertex index (an integer from 0) for patches[0].loops[1][1], "
        "found 1.5");
  CHECK(loop("\"1\"") ==
        "part.json:3:5: expected a vertex index (an integer from 0) for patches[0].loops[1][0], "
        "found \"1\"");
  CHECK_THAT(loop("2.0"),
             StartsWith("part.json:3:5: expected a vertex index") && Contains("found 2.0"));
  CHECK_THAT(loop("1e0"), StartsWith("part.json:3:5: expected a vertex index"));
  CHECK(loop("1, -1") ==
        "part.json:3:8: negative vertex index -1 for patches[0].loops[1][1]: indices start at 0");
  CHECK(loop("0, 1, 2") ==
        "part.json:3:11: vertex index 2 for patches[0].loops[1][2] is out of range: the part has "
        "2 vertices, so indices run from 0 to 1");
  CHECK_THAT(loop("18446744073709551616"),
             StartsWith("part.json:3:5: vertex index 18446744073709551616 for") &&
                 Contains("is out of range"));
  CHECK_THAT(loop("-18446744073709551616"),
             StartsWith("part.json:3:5: negative vertex index -18446744073709551616 for"));
  const RawPart minus_zero = parse_brep_json(head + " \"patches\": [{\"loops\": [[-0, 1]]}]}", "p");
  CHECK(minus_zero.patches[0].loops[0] == std::vector<std::int64_t>{0, 1});
  CHECK_THAT(
      loop("18446744073709551615"),
      StartsWith("part.json:3:5: vertex index 18446744073709551615 ") && Contains("out of range"));
  CHECK_THAT(
      error_of(
          "{\"laytracks\": \"brep/1\", \"vertices\": [],\n \"patches\": [{\"loops\": [[0]]}]}"),
      StartsWith("part.json:2:26: vertex index 0 for patches[0].loops[0][0] is out of "
                 "range: the part has no vertices"));
}

TEST_CASE("arcs have integer from and to, and a via point", "[io][brep_json][errors]") {
  CHECK_THAT(error_of(small_part(",\n \"arcs\": {}")),
             StartsWith("part.json:3:10: expected an array of arcs for arcs, found an object"));
  CHECK_THAT(error_of(small_part(",\n \"arcs\": [[0, 1]]")),
             StartsWith("part.json:3:11: expected an object") && Contains("for arcs[0]"));
  CHECK(error_of(small_part(",\n \"arcs\": [{\"from\": 0, \"to\": 1}]")) ==
        "part.json:3:11: missing required key \"via\" in arcs[0] (a point [x, y, z] on the arc)");
  CHECK(error_of(small_part(",\n \"arcs\": [{\"from\": 0, \"to\": 3, \"via\": [0, 0, 0]}]")) ==
        "part.json:3:29: vertex index 3 for arcs[0].to is out of range: the part has 3 "
        "vertices, so indices run from 0 to 2");
  CHECK(error_of(small_part(",\n \"arcs\": [{\"from\": 0.0, \"to\": 1, \"via\": [0, 0, 0]}]")) ==
        "part.json:3:20: expected a vertex index (an integer from 0) for arcs[0].from, found 0.0");
  CHECK(error_of(small_part(",\n \"arcs\": [{\"from\": 0, \"to\": 1, \"via\": [0, 0]}]")) ==
        "part.json:3:39: expected an array of 3 numbers for arcs[0].via, found an array of 2 "
        "values");
  CHECK_THAT(
      error_of(small_part(",\n \"arcs\": [{\"from\": 0, \"to\": 1, \"via\": [0, 0, 1e13]}]")),
      StartsWith("part.json:3:46: absurd coordinate 1e13 for arcs[0].via[2]"));
}

TEST_CASE("dual_graph holds pairs of distinct patch indices", "[io][brep_json][errors]") {
  CHECK(parse_brep_json(small_part(", \"dual_graph\": []"), "p.json").dual_graph ==
        std::optional<std::vector<std::array<std::int64_t, 2>>>(
            std::vector<std::array<std::int64_t, 2>>{}));
  CHECK(error_of(small_part(",\n \"dual_graph\": [[0, 1, 2]]")) ==
        "part.json:3:17: expected a pair [i, j] of patch indices for dual_graph[0], found an "
        "array of 3 values");
  CHECK(error_of(small_part(",\n \"dual_graph\": [[0, 1]]")) ==
        "part.json:3:21: patch index 1 for dual_graph[0][1] is out of range: the part has 1 "
        "patch, so indices run from 0 to 0");
  CHECK(error_of(small_part(",\n \"dual_graph\": [[0, 0]]")) ==
        "part.json:3:17: dual_graph[0] pairs patch 0 with itself: a neighbour pair needs two "
        "different patches");
  CHECK_THAT(error_of(small_part(",\n \"dual_graph\": [[-1, 0]]")),
             StartsWith("part.json:3:18: negative patch index -1 for dual_graph[0][0]"));
}

TEST_CASE("mesh parameters are checked", "[io][brep_json][errors]") {
  CHECK_THAT(error_of(small_part(",\n \"mesh\": 2")),
             StartsWith("part.json:3:10: expected an object for mesh, found 2"));
  CHECK(error_of(small_part(",\n \"mesh\": {\"size\": 0}")) ==
        "part.json:3:19: expected a positive number for mesh.size (the target element size), "
        "found 0");
  CHECK_THAT(error_of(small_part(",\n \"mesh\": {\"size\": -1.5}")),
             StartsWith("part.json:3:19: ") && Contains("found -1.5"));
  CHECK_THAT(error_of(small_part(",\n \"mesh\": {\"size\": \"2\"}")),
             StartsWith("part.json:3:19: ") && Contains("found \"2\""));
  CHECK(error_of(small_part(",\n \"mesh\": {\"mode\": \"fast\"}")) ==
        "part.json:3:19: expected \"uniform\" or \"adaptive\" for mesh.mode, found \"fast\"");
  CHECK(error_of(small_part(",\n \"mesh\": {\"dtheta_deg\": 0}")) ==
        "part.json:3:25: expected an angle in degrees in (0, 90] for mesh.dtheta_deg, found 0");
  CHECK_THAT(error_of(small_part(",\n \"mesh\": {\"dtheta_deg\": 90.5}")),
             StartsWith("part.json:3:25: ") && Contains("found 90.5"));
  const RawPart ok = parse_brep_json(
      small_part(", \"mesh\": {\"size\": 1e-3, \"mode\": \"adaptive\", \"dtheta_deg\": 90}"), "p");
  CHECK(ok.mesh.size == std::optional<double>(1e-3));
  CHECK(ok.mesh.mode == std::optional<MeshMode>(MeshMode::Adaptive));
}

// ---- Files ----

TEST_CASE("read_brep_json names the file in messages", "[io][brep_json][errors]") {
  const std::string dir = test::test_data_dir() + "/json";
  const RawPart part = read_brep_json(dir + "/two_triangles.json");
  CHECK(part.source == dir + "/two_triangles.json");
  CHECK(part.patches.size() == 2);
  CHECK(part.patches[1].name == std::optional<std::string>("right"));

  CHECK_THROWS_WITH(read_brep_json(dir + "/typo_patchs.json"),
                    StartsWith(dir + "/typo_patchs.json:6:3: unknown key \"patchs\""));
  CHECK_THROWS_WITH(read_brep_json(dir + "/no_such_file.json"),
                    "cannot read " + dir + "/no_such_file.json: No such file or directory");
  CHECK_THROWS_WITH(read_brep_json(dir), "cannot read " + dir + ": Is a directory");
}

}  // namespace
}  // namespace laytracks
