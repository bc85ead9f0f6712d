// `laytracks batch` and `laytracks draw --stage mesh`, run as a user runs them: which files are
// written and which are not, the table and the report, exit statuses, and output that does not
// depend on the number of threads.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "run_cli.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using laytracks::test::cases_dir;
using laytracks::test::fresh_dir;
using laytracks::test::q;
using laytracks::test::Run;
using laytracks::test::run;
using laytracks::test::slurp;
using laytracks::test::test_data_dir;

namespace {

/// The names of the files in a folder, sorted.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// The report without what depends on timing and threads ("seconds", "threads").
nlohmann::json timeless(nlohmann::json report) {
  report.erase("threads");
  report["totals"].erase("seconds");
  for (auto& p : report["parts"]) p.erase("seconds");
  return report;
}

/// The number of quads `laytracks mesh` makes of the part (from its last line).
std::size_t quads_of(const fs::path& part, const fs::path& scratch) {
  const Run r = run("mesh " + q(part) + " -o " + q(scratch / "count.msh"));
  REQUIRE(r.status == 0);
  const auto colon = r.out.find(": ");
  REQUIRE(colon != std::string::npos);
  return std::stoul(r.out.substr(colon + 2));
}

}  // namespace

TEST_CASE("batch meshes a folder, goes on past a malformed part, and reports every part",
          "[cli][batch]") {
  const fs::path d = fresh_dir("batch-folder");
  fs::create_directories(d / "in" / "sub");
  fs::copy_file(cases_dir() + "/rect_10x4.json", d / "in" / "rect_10x4.json");
  fs::copy_file(cases_dir() + "/l_shape.json", d / "in" / "l_shape.json");
  fs::copy_file(cases_dir() + "/closed_cube.json", d / "in" / "sub" / "closed_cube.json");
  fs::copy_file(test_data_dir() + "/invalid/non_planar.json", d / "in" / "non_planar.json");
  std::ofstream(d / "in" / "notes.md") << "not a part: only *.json is taken from a folder\n";

  const Run r = run("batch " + q(d / "in") + " -o " + q(d / "out") + " -j 2");
  INFO(r.out << r.err);
  CHECK(r.status == 1);  // a part refused, none failed
  // Every good part is written and reads back valid; nothing for the malformed one.
  CHECK(listing(d / "out") == std::vector<std::string>{"batch-report.json", "closed_cube.msh",
                                                       "l_shape.msh", "rect_10x4.msh"});
  for (const char* name : {"rect_10x4", "l_shape", "sub/closed_cube"}) {
    CAPTURE(name);
    const Run rated = run("quality " + q(d / "in" / (std::string(name) + ".json")) + " " +
                          q(d / "out" / (fs::path(name).filename().string() + ".msh")));
    CHECK(rated.status == 0);
    CHECK_THAT(rated.out, Catch::Contains("valid by quality.md: yes"));
  }
  // The table: one row per part, in path order, the refused part with its message.
  const auto at = [&](const std::string& s) { return r.out.find("\n" + s + " "); };
  REQUIRE(at("l_shape") != std::string::npos);
  CHECK(at("l_shape") < at("non_planar"));
  CHECK(at("non_planar") < at("rect_10x4"));
  CHECK(at("rect_10x4") < at("closed_cube"));
  const std::string bad_row = r.out.substr(at("non_planar") + 1);
  CHECK_THAT(bad_row.substr(0, bad_row.find('\n')),
             Catch::Contains("refused") && Catch::Contains("is not planar"));
  CHECK_THAT(r.out, Catch::Contains("4 parts: 3 ok, 1 refused, 0 failed"));
  // stderr is not a terminal here: one progress line per finished part.
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 4);
  CHECK_THAT(r.err, Catch::Contains("/4] non_planar: refused: "));
  // The report holds the same rows.
  const auto report = nlohmann::json::parse(slurp(d / "out" / "batch-report.json"));
  REQUIRE(report["parts"].size() == 4);
  std::size_t quads = 0;
  for (const auto& p : report["parts"]) {
    CAPTURE(p.dump());
    if (p["part"] == "non_planar") {
      CHECK(p["status"] == "refused");
      CHECK(p["output"].is_null());
      CHECK_THAT(p["error"].get<std::string>(), Catch::Contains("is not planar"));
    } else {
      CHECK(p["status"] == "ok");
      CHECK(fs::exists(p["output"].get<std::string>()));
      CHECK(p["min_scaled_jacobian"].get<double>() > 0.2);
      quads += p["quads"].get<std::size_t>();
    }
  }
  CHECK(report["parts"][0]["part"] == "l_shape");
  CHECK(report["totals"]["ok"] == 3);
  CHECK(report["totals"]["refused"] == 1);
  CHECK(report["totals"]["quads"] == quads);
  // Run again on the folder holding both: what is inside OUTDIR (the report) is no part.
  const Run again = run("batch " + q(d) + " -o " + q(d / "out") + " -j 2 --quiet");
  CHECK(again.status == 1);
  CHECK_THAT(again.out, Catch::Contains("4 parts: 3 ok, 1 refused, 0 failed"));
}

TEST_CASE("batch reports a part it cannot write as failed, and the others go on",
          "[cli][batch]") {
  const fs::path d = fresh_dir("batch-unwritable");
  // A folder where l_shape's mesh should go: that write fails, rect_10x4's does not.
  fs::create_directories(d / "out" / "l_shape.msh");
  const Run r = run("batch " + q(cases_dir() + "/rect_10x4.json") + " " +
                    q(cases_dir() + "/l_shape.json") + " -o " + q(d / "out") + " --quiet");
  INFO(r.out << r.err);
  CHECK(r.status == 4);
  CHECK(r.err.empty());  // --quiet: no progress
  CHECK(fs::is_directory(d / "out" / "l_shape.msh"));
  CHECK(fs::is_regular_file(d / "out" / "rect_10x4.msh"));
  const std::string row = r.out.substr(r.out.find("\nl_shape ") + 1);
  CHECK_THAT(row.substr(0, row.find('\n')), Catch::Contains("failed"));
  CHECK_THAT(r.out, Catch::Contains("2 parts: 1 ok, 0 refused, 1 failed"));
}

TEST_CASE("batch output does not depend on the number of threads", "[cli][batch][determinism]") {
  const fs::path d = fresh_dir("batch-threads");
  const std::string inputs =
      q(cases_dir() + "/rect_10x4.json") + " " + q(cases_dir() + "/l_shape.json") + " " +
      q(cases_dir() + "/t_junction.json") + " " + q(cases_dir() + "/closed_cube.json");
  for (const char* format : {"msh", "obj"}) {
    CAPTURE(format);
    for (const char* jobs : {"1", "2"}) {
      const Run r = run("batch " + inputs + " -o " + q(d / (std::string(format) + jobs)) +
                        " --format " + format + " -j " + jobs + " --quiet");
      INFO(r.out << r.err);
      REQUIRE(r.status == 0);
    }
    const fs::path one = d / (std::string(format) + "1");
    const fs::path two = d / (std::string(format) + "2");
    REQUIRE(listing(one) == listing(two));
    CHECK(listing(one).size() == 5);
    for (const std::string& name : listing(one)) {
      CAPTURE(name);
      if (name == "batch-report.json") {
        const auto a = nlohmann::json::parse(slurp(one / name));
        const auto b = nlohmann::json::parse(slurp(two / name));
        CHECK(a["threads"] == 1);
        CHECK(b["threads"] == 2);
        // Same rows in the same order; only the paths of the outputs and the times differ.
        auto ta = timeless(a);
        auto tb = timeless(b);
        for (auto* t : {&ta, &tb}) {
          for (auto& p : (*t)["parts"]) p.erase("output");
        }
        CHECK(ta == tb);
      } else {
        CHECK(slurp(one / name) == slurp(two / name));
      }
    }
  }
}

TEST_CASE("batch reads list files and names parts that share a name after their folder",
          "[cli][batch]") {
  const fs::path d = fresh_dir("batch-list");
  fs::create_directories(d / "lists");
  fs::create_directories(d / "a");
  fs::create_directories(d / "b");
  fs::copy_file(cases_dir() + "/rect_10x4.json", d / "a" / "part.json");
  fs::copy_file(cases_dir() + "/l_shape.json", d / "b" / "part.json");
  fs::copy_file(cases_dir() + "/t_junction.json", d / "b" / "t.json");
  std::ofstream(d / "lists" / "parts.list")
      << "# parts to mesh\n"
      << "\n"
      << "../a/part.json\n"                                   // relative to the list's folder
      << "   " << (d / "b" / "part.json").string() << "  \n"  // absolute, padded
      << "  # the folder too: part.json again is meshed once\n"
      << "../b\n";
  const Run r = run("batch " + q(d / "lists" / "parts.list") + " -o " + q(d / "out"));
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK(listing(d / "out") ==
        std::vector<std::string>{"batch-report.json", "part-a.msh", "part-b.msh", "t.msh"});
  CHECK_THAT(r.out, Catch::Contains("3 parts: 3 ok, 0 refused, 0 failed"));
  const auto report = nlohmann::json::parse(slurp(d / "out" / "batch-report.json"));
  REQUIRE(report["parts"].size() == 3);
  CHECK(report["parts"][0]["part"] == "part-a");
  CHECK(report["parts"][1]["part"] == "part-b");
  CHECK(report["parts"][2]["part"] == "t");
  // The same rectangle as `laytracks mesh` writes it.
  const Run mesh =
      run("mesh " + q(d / "a" / "part.json") + " -o " + q(d / "rect.msh") + " --quiet");
  REQUIRE(mesh.status == 0);
  CHECK(slurp(d / "rect.msh") == slurp(d / "out" / "part-a.msh"));
}

TEST_CASE("batch refuses a missing input or a wrong option before any work", "[cli][batch]") {
  const fs::path d = fresh_dir("batch-usage");
  const std::string good = q(cases_dir() + "/rect_10x4.json");
  std::ofstream(d / "bad.list") << "# one entry is missing\n"
                                << cases_dir() + "/l_shape.json\n"
                                << "nowhere.json\n";
  struct Case {
    std::string args;
    std::string message;
  };
  for (const Case& c : {
           Case{good + " /nonexistent/x.json", "no such input: \"/nonexistent/x.json\""},
           Case{good + " " + q(d / "bad.list"), "bad.list:3: \"" + (d / "nowhere.json").string()},
           Case{good + " --format stl", "--format is one of msh vtu bdf inp obj off"},
           Case{good + " -j 0", "option -j needs a whole number from 1"},
           Case{good + " --size -2", "--size needs a positive number"},
           Case{"", "batch needs at least one input"},
       }) {
    CAPTURE(c.args);
    const Run r = run("batch " + c.args + " -o " + q(d / "out"));
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains(c.message));
    CHECK(r.out.empty());
    CHECK_FALSE(fs::exists(d / "out"));
  }
  const Run no_out = run("batch " + good);
  CHECK(no_out.status == 2);
  CHECK_THAT(no_out.err, Catch::Contains("batch needs -o OUTDIR"));
  const Run help = run("help batch");
  CHECK(help.status == 0);
  CHECK_THAT(help.out, Catch::Contains("-j N") && Catch::Contains("<name>-<folder>"));
  CHECK_THAT(run("--help").out, Catch::Contains("batch INPUTS -o DIR"));
}

TEST_CASE("draw --stage mesh writes well-formed SVG, one polygon per quad", "[cli][draw]") {
  const fs::path d = fresh_dir("draw-mesh");
  struct Case {
    std::string part;
    std::string view;  // "" for the default
    std::string expect;
  };
  for (const Case& c : {Case{cases_dir() + "/l_shape.json", "", "unfolded view"},
                        Case{cases_dir() + "/closed_cube.json", "", "oblique view"},
                        Case{cases_dir() + "/closed_cube.json", "unfolded", "unfolded view"}}) {
    CAPTURE(c.part, c.view);
    const std::size_t quads = quads_of(c.part, d);
    const fs::path svg = d / "mesh.svg";
    const Run r = run("draw " + q(c.part) + " --stage mesh -o " + q(svg) +
                      (c.view.empty() ? "" : " --view " + c.view));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const std::string text = slurp(svg);
    CHECK(text.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0) == 0);
    CHECK(text.size() > 7);
    CHECK(text.substr(text.size() - 7) == "</svg>\n");
    std::size_t polygons = 0;
    for (auto at = text.find("<polygon "); at != std::string::npos;
         at = text.find("<polygon ", at + 1)) {
      ++polygons;
    }
    CHECK(polygons == quads);
    CHECK_THAT(text, Catch::Contains(c.expect) && Catch::Contains("scaled Jacobian") &&
                         Catch::Contains(std::to_string(quads) + " quads"));
    // An independent XML parser reads it.
    const std::string parse =
        "python3 -c 'import sys, xml.etree.ElementTree as E; "
        "sys.exit(E.parse(sys.argv[1]).getroot().tag != "
        "\"{http://www.w3.org/2000/svg}svg\")' " +
        q(svg);
    CHECK(std::system(parse.c_str()) == 0);
    fs::remove(svg);
  }
}

TEST_CASE("draw --stage mesh --measure colours the quads by another measure", "[cli][draw]") {
  const fs::path d = fresh_dir("draw-measure");
  const std::string part = cases_dir() + "/plate_with_hole.json";
  const std::size_t quads = quads_of(part, d);
  struct Case {
    std::string measure, legend;
  };
  for (const Case& c : {Case{"taper", "taper (bad &lt;= 0.8, red): smallest "},
                        Case{"skew", "skew [deg] (bad &gt;= 30, red): largest "},
                        Case{"aspect", "aspect ratio (bad &gt;= 5, red): largest "},
                        Case{"edge-ratio", "edge ratio (bad &gt;= 5, red): largest "},
                        Case{"jacobian", "scaled Jacobian (bad &lt;= 0.2, red): smallest "}}) {
    CAPTURE(c.measure);
    const fs::path svg = d / (c.measure + ".svg");
    const Run r = run("draw " + q(part) + " --stage mesh --measure " + c.measure + " -o " + q(svg));
    INFO(r.err);
    REQUIRE(r.status == 0);
    const std::string text = slurp(svg);
    CHECK_THAT(text, Catch::Contains(c.legend));
    std::size_t polygons = 0;
    for (auto at = text.find("<polygon "); at != std::string::npos;
         at = text.find("<polygon ", at + 1)) {
      ++polygons;
    }
    CHECK(polygons == quads);
  }
  // The default is the scaled Jacobian, byte for byte.
  REQUIRE(run("draw " + q(part) + " --stage mesh -o " + q(d / "default.svg")).status == 0);
  CHECK(slurp(d / "default.svg") == slurp(d / "jacobian.svg"));
  // Taper and the Jacobian colour the same quads differently.
  CHECK(slurp(d / "taper.svg") != slurp(d / "jacobian.svg"));
  // A measure it does not know, or one for another stage: usage errors, nothing written.
  const fs::path e = fresh_dir("draw-measure-bad");
  const Run bogus = run("draw " + q(part) + " --stage mesh --measure warp -o " + q(e / "a.svg"));
  CHECK(bogus.status == 2);
  CHECK_THAT(bogus.err, Catch::Contains("--measure is jacobian, taper, skew, aspect or edge-ratio"));
  const Run stage = run("draw " + q(part) + " --stage tracks --measure taper -o " + q(e / "b.svg"));
  CHECK(stage.status == 2);
  CHECK_THAT(stage.err, Catch::Contains("--measure is for --stage mesh only"));
  CHECK(listing(e).empty());
}

TEST_CASE("draw --stage mesh writes nothing for a part it cannot mesh", "[cli][draw]") {
  const fs::path d = fresh_dir("draw-mesh-refused");
  const Run malformed = run("draw " + q(test_data_dir() + "/invalid/non_planar.json") +
                            " --stage mesh -o " + q(d / "a.svg"));
  CHECK(malformed.status == 1);
  CHECK_THAT(malformed.err, Catch::Contains("is not planar"));
  const Run smooth = run("draw " + q(cases_dir() + "/l_shape.json") +
                         " --stage tracks --smooth 3 -o " + q(d / "b.svg"));
  CHECK(smooth.status == 2);
  CHECK(listing(d).empty());
}
