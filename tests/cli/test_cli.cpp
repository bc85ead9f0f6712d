// The laytracks executable, run as a user runs it: exit statuses, messages, files written or
// not, and byte-identical output from run to run.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_cli.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using laytracks::test::fresh_dir;
using laytracks::test::q;
using laytracks::test::Run;
using laytracks::test::run;
using laytracks::test::samples_dir;
using laytracks::test::slurp;
using laytracks::test::test_data_dir;

TEST_CASE("medial writes JSON and SVG for a sample part", "[cli]") {
  const fs::path d = fresh_dir("medial");
  const Run r = run("medial " + q(samples_dir() + "/bracket.json") + " --json " + q(d / "m.json") +
                    " --svg " + q(d / "m.svg"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("6 patches, 1 shells") != std::string::npos);
  const auto doc = nlohmann::json::parse(slurp(d / "m.json"));
  REQUIRE(doc["patches"].size() == 6);
  for (const auto& p : doc["patches"]) {
    CHECK(p["name"].is_string());
    std::vector<int> degree(p["vertices"].size(), 0);
    for (const auto& e : p["edges"]) {
      ++degree.at(e[0].get<std::size_t>());
      ++degree.at(e[1].get<std::size_t>());
    }
    for (std::size_t i = 0; i < degree.size(); ++i) {
      const auto& v = p["vertices"][i];
      CHECK(v["xyz"].size() == 3);
      CHECK(v["radius"].get<double>() >= 0.0);
      CHECK(v["degree"].get<int>() == degree[i]);
    }
  }
  const std::string svg = slurp(d / "m.svg");
  CHECK(svg.rfind("<?xml", 0) == 0);
  CHECK(svg.find("upright_top") != std::string::npos);
  CHECK(svg.find("</svg>") != std::string::npos);
}

TEST_CASE("output is byte-identical from run to run", "[cli][determinism]") {
  const fs::path d = fresh_dir("determinism");
  for (const char* name : {"a", "b"}) {
    const Run r =
        run("medial " + q(samples_dir() + "/tray_ribs.json") + " --quiet --json " +
            q(d / (std::string(name) + ".json")) + " --svg " + q(d / (std::string(name) + ".svg")));
    REQUIRE(r.status == 0);
    CHECK(r.out.empty());
  }
  CHECK(slurp(d / "a.json") == slurp(d / "b.json"));
  CHECK(slurp(d / "a.svg") == slurp(d / "b.svg"));
}

TEST_CASE("every malformed part is refused with its message, and nothing is written",
          "[cli][invalid]") {
  const fs::path d = fresh_dir("invalid");
  std::ifstream table(test_data_dir() + "/invalid/expected.tsv");
  REQUIRE(table);
  std::string line;
  std::size_t cases = 0;
  while (std::getline(table, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    const std::string file = line.substr(0, tab);
    const std::string expected = line.substr(tab + 1);
    CAPTURE(file);
    // An existing output stays exactly as it was; a new one is never created.
    std::ofstream(d / "old.json") << "previous content";
    const Run r = run("medial " + q(test_data_dir() + "/invalid/" + file) + " --json " +
                      q(d / "old.json") + " --svg " + q(d / "new.svg"));
    CHECK(r.status == 1);
    CHECK(r.err.rfind("laytracks: error: ", 0) == 0);
    CHECK_THAT(r.err, Catch::Contains(expected));
    CHECK(slurp(d / "old.json") == "previous content");
    CHECK_FALSE(fs::exists(d / "new.svg"));
    CHECK(std::distance(fs::directory_iterator(d), fs::directory_iterator()) == 1);
    ++cases;
  }
  CHECK(cases >= 28);
}

TEST_CASE("command-line mistakes exit with status 2 and say what is wrong", "[cli][usage]") {
  const std::string part = q(samples_dir() + "/cover_bosses.json");
  struct Case {
    std::string args;
    std::string message;
  };
  for (const Case& c :
       {Case{"frobnicate", "unknown command \"frobnicate\""},
        Case{"medial", "medial needs exactly one PART.json"},
        Case{"medial " + part + " --chord-tol -1", "--chord-tol needs a positive number"},
        Case{"medial " + part + " --colour red", "unknown option --colour"},
        Case{"medial " + part + " --json", "option --json needs a value"}}) {
    CAPTURE(c.args);
    const Run r = run(c.args);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains(c.message));
  }
  const Run missing = run("medial /nonexistent/part.json");
  CHECK(missing.status == 1);
  CHECK_THAT(missing.err, Catch::Contains("cannot read /nonexistent/part.json"));
}

TEST_CASE("check-loops reports the cube's loops as JSON, and draw writes pictures", "[cli]") {
  const fs::path d = fresh_dir("check-loops");
  const std::string cube = q(laytracks::test::cases_dir() + "/closed_cube.json");
  const Run r = run("check-loops " + cube + " --json " + q(d / "loops.json"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("32 loops"));
  const auto doc = nlohmann::json::parse(slurp(d / "loops.json"));
  CHECK(doc["ok"] == true);
  CHECK(doc["loops"] == 32);
  CHECK(doc["max_closure_gap"].get<double>() <= 1e-9 * 17.32);
  std::size_t loops = 0;
  for (const auto& rail : doc["rails"]) loops += rail["end"] == "loop" ? 1u : 0u;
  CHECK(loops == 32);
  CHECK(doc["deleted_rails"] == 0);
  CHECK(doc["narrow_rounds"] == 0);
  // A part with narrow corridors: the rails deleted and the rounds that deleted them.
  const Run narrow = run("check-loops " + q(laytracks::test::cases_dir() +
                                            "/external/cgal_complex_1.json") +
                         " --json " + q(d / "narrow.json"));
  REQUIRE(narrow.status == 0);
  const auto nd = nlohmann::json::parse(slurp(d / "narrow.json"));
  CHECK(nd["narrow_rounds"].get<int>() > 0);
  CHECK(nd["narrow_rounds"].get<int>() <= nd["deleted_rails"].get<int>());
  // Each deleted rail's point and each rail's ends, in the part's frame (complex_1 lies in
  // z = 0 within its bounding box), to compare the rails of two poses.
  REQUIRE(nd["deleted"].size() == nd["deleted_rails"].get<std::size_t>());
  for (const auto& del : nd["deleted"]) {
    CHECK(del["at"].size() == 3);
    CHECK(del["at"][2].get<double>() == 0.0);
    CHECK(del["corridor_width"].get<double>() > 0.0);
    CHECK(del["patch"] == "complex_1");
  }
  std::size_t ended = 0;
  for (const auto& rail : nd["rails"]) {
    CHECK(rail["points"].get<std::size_t>() >= 1);
    if (!rail.contains("from")) continue;
    ++ended;
    for (const char* end : {"from", "to"}) {
      CHECK(rail[end][0].get<double>() > 4.7);
      CHECK(rail[end][0].get<double>() < 5.4);
      CHECK(rail[end][1].get<double>() > 61.6);
      CHECK(rail[end][1].get<double>() < 62.1);
    }
  }
  CHECK(ended == nd["rails"].size());
  CHECK_THAT(narrow.out, Catch::Contains("rounds)"));
  for (const char* stage : {"medial", "corridors", "tracks"}) {
    const fs::path svg = d / (std::string(stage) + ".svg");
    const Run draw = run("draw " + cube + " --stage " + stage + " -o " + q(svg));
    CHECK(draw.status == 0);
    CHECK(slurp(svg).find("</svg>") != std::string::npos);
  }
  const Run oblique = run("draw " + cube + " --stage tracks --view oblique -o " + q(d / "o.svg"));
  CHECK(oblique.status == 0);
  CHECK(slurp(d / "o.svg").find("oblique view") != std::string::npos);
  const Run bad_view = run("draw " + cube + " --stage tracks --view top -o " + q(d / "y.svg"));
  CHECK(bad_view.status == 2);
  CHECK_FALSE(fs::exists(d / "y.svg"));
  const Run bad = run("draw " + cube + " --stage quads -o " + q(d / "x.svg"));
  CHECK(bad.status == 2);
  CHECK_FALSE(fs::exists(d / "x.svg"));
}

TEST_CASE("quality rates a Gmsh mesh with nodes on the true circle of an arc as valid",
          "[cli][quality][arcs]") {
  // plate_with_hole: a 30 x 20 plate with a hole of radius 4 round (12, 10), four arcs. Gmsh
  // puts its nodes on the circle and its chords differ from our discretisation: rule 4 compares
  // with the patch cut by the mesh's own chords, rule 6 wants the nodes on the circle.
  const fs::path d = fresh_dir("quality-arcs");
  std::ofstream(d / "p.geo")
      << "lc = 0.8;\n"
         "Point(1)={0,0,0,lc}; Point(2)={30,0,0,lc}; Point(3)={30,20,0,lc}; Point(4)={0,20,0,lc};\n"
         "Point(5)={12,6,0,lc}; Point(6)={8,10,0,lc}; Point(7)={12,14,0,lc}; Point(8)={16,10,0,lc};\n"
         "Point(9)={12,10,0,lc};\n"
         "Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};\n"
         "Circle(5)={5,9,6}; Circle(6)={6,9,7}; Circle(7)={7,9,8}; Circle(8)={8,9,5};\n"
         "Curve Loop(1)={1,2,3,4}; Curve Loop(2)={5,6,7,8}; Plane Surface(1)={1,2};\n"
         "Mesh.Algorithm=6; Mesh.RecombineAll=1; Mesh.RecombinationAlgorithm=1;\n"
         "Mesh.SubdivisionAlgorithm=1;\n";
  const std::string gmsh =
      "gmsh " + q(d / "p.geo") + " -2 -format msh41 -o " + q(d / "p.msh") + " > /dev/null 2>&1";
  REQUIRE(std::system(gmsh.c_str()) == 0);
  const Run r = run("quality " + q(laytracks::test::cases_dir() + "/plate_with_hole.json") + " " +
                    q(d / "p.msh") + " --json " + q(d / "q.json"));
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("valid by quality.md: yes"));
  const auto doc = nlohmann::ordered_json::parse(slurp(d / "q.json"));
  CHECK(doc["triangles"] == 0);
  // The check sits after the summary: valid, the count per rule, the failures (none).
  std::vector<std::string> keys;
  for (const auto& item : doc.items()) keys.push_back(item.key());
  REQUIRE(keys.size() >= 3);
  CHECK(keys.front() == "elements");
  CHECK(std::vector<std::string>(keys.end() - 3, keys.end()) ==
        std::vector<std::string>{"valid", "failure_counts", "failures"});
  CHECK(doc["valid"] == true);
  CHECK(doc["failures"].empty());
  for (const char* rule : {"1", "2", "3", "4", "5", "6"}) CHECK(doc["failure_counts"][rule] == 0);

  // One node of the hole moved 1e-3 towards the centre: rules 4 (areas) and 6 (boundary
  // following) fail, and the JSON names them with their rule numbers.
  std::istringstream in(slurp(d / "p.msh"));
  std::ostringstream moved;
  bool in_nodes = false, done = false;
  for (std::string line; std::getline(in, line);) {
    if (line == "$Nodes") in_nodes = true;
    if (line == "$EndNodes") in_nodes = false;
    std::istringstream words(line);
    double x = 0.0, y = 0.0, z = 0.0;
    std::string rest;
    if (in_nodes && !done && (words >> x >> y >> z) && !(words >> rest) &&
        std::abs(std::hypot(x - 12.0, y - 10.0) - 4.0) < 1e-9) {
      const double f = 1.0 - 1e-3 / 4.0;
      char buf[96];
      std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", 12.0 + f * (x - 12.0),
                    10.0 + f * (y - 10.0), z);
      line = buf;
      done = true;
    }
    moved << line << "\n";
  }
  REQUIRE(done);
  std::ofstream(d / "moved.msh") << moved.str();
  const std::string rate_moved = "quality " +
                                 q(laytracks::test::cases_dir() + "/plate_with_hole.json") + " " +
                                 q(d / "moved.msh") + " --quiet --json ";
  const Run bad = run(rate_moved + q(d / "bad.json"));
  INFO(bad.err);
  CHECK(bad.status == 5);
  const std::string text = slurp(d / "bad.json");
  const auto b = nlohmann::ordered_json::parse(text);
  CHECK(b["valid"] == false);
  CHECK(b["quads"] == doc["quads"]);
  CHECK(b["failure_counts"]["4"].get<int>() > 0);
  CHECK(b["failure_counts"]["6"].get<int>() > 0);
  REQUIRE_FALSE(b["failures"].empty());
  std::array<int, 7> listed{};
  int last_rule = 0;
  for (const auto& f : b["failures"]) {
    const int rule = f["rule"].get<int>();
    REQUIRE(rule >= 1);
    REQUIRE(rule <= 6);
    ++listed[static_cast<std::size_t>(rule)];
    CHECK(rule >= last_rule);  // in rule order
    last_rule = rule;
    CHECK_THAT(f["message"].get<std::string>(),
               Catch::StartsWith("rule " + std::to_string(rule) + ": "));
    // The same sentences as on stderr.
    CHECK_THAT(bad.err, Catch::Contains(f["message"].get<std::string>()));
  }
  CHECK(listed[4] > 0);
  CHECK(listed[6] > 0);
  for (std::size_t rule = 1; rule <= 6; ++rule)
    CHECK(listed[rule] <= b["failure_counts"][std::to_string(rule)].get<int>());
  // Deterministic: rating again writes the same bytes.
  const Run again = run(rate_moved + q(d / "bad2.json"));
  CHECK(again.status == 5);
  CHECK(slurp(d / "bad2.json") == text);
}

TEST_CASE("quality rates a Gmsh mesh of a part: quads valid, triangles refused", "[cli][quality]") {
  const fs::path d = fresh_dir("quality");
  for (const bool recombine : {true, false}) {
    CAPTURE(recombine);
    std::ofstream(d / "r.geo")
        << "Point(1)={0,0,0,0.5}; Point(2)={10,0,0,0.5}; Point(3)={10,4,0,0.5};\n"
           "Point(4)={0,4,0,0.5}; Line(1)={1,2}; Line(2)={2,3}; Line(3)={3,4}; Line(4)={4,1};\n"
           "Curve Loop(1)={1,2,3,4}; Plane Surface(1)={1}; Mesh.Algorithm=6;\n"
        << (recombine ? "Mesh.RecombineAll=1; Mesh.RecombinationAlgorithm=1;\n" : "");
    const std::string gmsh =
        "gmsh " + q(d / "r.geo") + " -2 -format msh41 -o " + q(d / "r.msh") + " > /dev/null 2>&1";
    REQUIRE(std::system(gmsh.c_str()) == 0);
    const Run r = run("quality " + q(laytracks::test::cases_dir() + "/rect_10x4.json") + " " +
                      q(d / "r.msh") + " --json " + q(d / "q.json"));
    const auto doc = nlohmann::json::parse(slurp(d / "q.json"));
    if (recombine) {
      CHECK(r.status == 0);
      CHECK_THAT(r.out, Catch::Contains("valid by quality.md: yes"));
      CHECK(doc["triangles"] == 0);
      CHECK(doc["quads"].get<int>() > 100);
    } else {
      CHECK(r.status == 5);
      CHECK_THAT(r.err, Catch::Contains("rule 1"));
      CHECK(doc["triangles"].get<int>() > 100);
    }
  }
}

TEST_CASE("help describes the commands and exits 0", "[cli]") {
  const Run help = run("--help");
  CHECK(help.status == 0);
  CHECK_THAT(help.out, Catch::Contains("medial PART.json"));
  const Run medial_help = run("medial --help");
  CHECK(medial_help.status == 0);
  CHECK_THAT(medial_help.out, Catch::Contains("--chord-tol"));
}

TEST_CASE("mesh writes a valid all-quad mesh in every format, byte-identical run to run",
          "[cli][mesh]") {
  const fs::path d = fresh_dir("mesh");
  const std::string part = q(samples_dir() + "/tray_ribs.json");
  for (const char* ext : {".msh", ".vtu", ".bdf", ".inp", ".obj", ".off"}) {
    CAPTURE(ext);
    const Run r = run("mesh " + part + " -o " + q(d / (std::string("a") + ext)) + " --quiet");
    REQUIRE(r.status == 0);
    CHECK(r.out.empty());
    REQUIRE(fs::exists(d / (std::string("a") + ext)));
  }
  const Run again = run("mesh " + part + " -o " + q(d / "b.msh") + " --report " +
                        q(d / "report.json"));
  REQUIRE(again.status == 0);
  CHECK_THAT(again.out, Catch::Contains("quads") && Catch::Contains("min scaled Jacobian"));
  CHECK_THAT(again.err, Catch::Contains("quads   ..."));  // progress per stage
  CHECK(slurp(d / "a.msh") == slurp(d / "b.msh"));
  const std::string report = slurp(d / "report.json");
  CHECK_THAT(report, Catch::Contains("\"quality_before_smoothing\"") &&
                         Catch::Contains("\"seconds\"") && Catch::Contains("\"triangles\": 0"));
  // The independent check: our own reader and checker on the written file.
  const Run rated = run("quality " + part + " " + q(d / "a.msh"));
  CHECK(rated.status == 0);
  CHECK_THAT(rated.out, Catch::Contains("valid by quality.md: yes"));
}

TEST_CASE("mesh writes the same bytes on one thread as on several", "[cli][determinism]") {
  // The faces of a patch are filled, and a one-patch part's re-fill attempts evaluated, in
  // parallel (the attempts speculatively, in batches against the mesh before the batch, each
  // evaluated again when an earlier one of its batch changed what it read); the patches of a
  // part are re-filled and smoothed in parallel. None of it may change a bit of the output.
  const fs::path d = fresh_dir("threads");
  for (const std::string& part : {laytracks::test::cases_dir() + "/external/cgal_wiggly_03_cgal.json",
                                 samples_dir() + "/tray_ribs.json"}) {
    CAPTURE(part);
    std::vector<std::string> outputs;
    for (const char* threads : {"1", "4"}) {
      ::setenv("LAYTRACKS_THREADS", threads, 1);
      const Run r = run("mesh " + q(part) + " -o " + q(d / "m.msh") + " --quiet --report " +
                        q(d / "r.json"));
      ::unsetenv("LAYTRACKS_THREADS");
      REQUIRE(r.status == 0);
      outputs.push_back(slurp(d / "m.msh"));
      // Re-fills were made (the parallel attempts had something to decide).
      CHECK(nlohmann::json::parse(slurp(d / "r.json"))["cavity_refills"].get<int>() > 0);
    }
    CHECK(outputs[0] == outputs[1]);
  }
}

TEST_CASE("mesh reports a hub meshed again, the same bytes every run, with both runs' times",
          "[cli][hub]") {
  // star_5 meshed uniformly: its centre's five rails go in a second run (docs/mesher.md,
  // "Hubs"), which the report counts; the stage times are both runs' added, so they sum to
  // about the total.
  const fs::path d = fresh_dir("hub");
  const std::string part = q(laytracks::test::cases_dir() + "/star_5.json");
  std::vector<std::string> outputs;
  for (int k = 0; k < 2; ++k) {
    const Run r = run("mesh " + part + " --uniform -o " + q(d / "s.msh") + " --quiet --report " +
                      q(d / "r.json"));
    REQUIRE(r.status == 0);
    outputs.push_back(slurp(d / "s.msh"));
    const nlohmann::json report = nlohmann::json::parse(slurp(d / "r.json"));
    CHECK(report["hub_patches"].get<int>() == 1);
    CHECK(report["quality"]["measures"]["taper"]["bad_percent"].get<double>() < 10.4);
    double stages = 0.0;
    for (const char* s : {"medial", "rails", "quads", "refill", "smooth", "check"})
      stages += report["seconds"][s].get<double>();
    CHECK(stages <= report["seconds"]["total"].get<double>() * 1.0001);
    CHECK(stages >= 0.5 * report["seconds"]["total"].get<double>());
  }
  CHECK(outputs[0] == outputs[1]);
}

TEST_CASE("mesh refuses what it cannot mesh, writes nothing, and says where", "[cli][mesh]") {
  const fs::path d = fresh_dir("mesh-refused");
  std::ofstream(d / "old.msh") << "previous content";
  // A malformed part: status 1.
  const Run bad = run("mesh " + q(test_data_dir() + "/invalid/" + "loop_too_short.json") + " -o " +
                      q(d / "old.msh"));
  CHECK(bad.status == 1);
  CHECK(slurp(d / "old.msh") == "previous content");
  // An unknown extension: status 2, before any work.
  const Run ext = run("mesh " + q(samples_dir() + "/bracket.json") + " -o " + q(d / "x.stl"));
  CHECK(ext.status == 2);
  CHECK_THAT(ext.err, Catch::Contains(".msh"));
  CHECK_FALSE(fs::exists(d / "x.stl"));
  // A folder that does not exist, for the mesh or the report: status 4, before any work (no
  // stage begun), nothing written.
  for (const std::string& where :
       {" -o " + q(d / "no" / "x.msh"),
        " -o " + q(d / "old.msh") + " --report " + q(d / "no" / "r.json")}) {
    const Run gone = run("mesh " + q(samples_dir() + "/bracket.json") + where);
    CHECK(gone.status == 4);
    CHECK_THAT(gone.err, Catch::Contains("/no does not exist"));
    CHECK_THAT(gone.err, !Catch::Contains("medial"));
    CHECK(slurp(d / "old.msh") == "previous content");
  }
  const Run folder = run("draw " + q(samples_dir() + "/bracket.json") + " --stage mesh -o " + q(d));
  CHECK(folder.status == 4);
  CHECK_THAT(folder.err, Catch::Contains("it is a folder"));
  // A size that would need more quads than memory holds (1e-10 ran out of memory, 1e-300
  // overflowed to a 6-quad mesh): status 1, before any work, the old file kept.
  for (const char* size : {"1e-300", "1e-10", "0.0005"}) {
    const Run tiny = run("mesh " + q(laytracks::test::cases_dir() + "/rect_10x4.json") + " -o " + q(d / "old.msh") +
                         " --size " + size);
    CHECK(tiny.status == 1);
    CHECK_THAT(tiny.err, Catch::Contains("choose a larger size"));
    CHECK(slurp(d / "old.msh") == "previous content");
  }
  // An outline folded back within a hair of itself that no attempt meshes: status 1, the
  // place named, the old file kept.
  const Run fold = run("mesh " + q(test_data_dir() + "/parts/fold_blob.json") + " -o " +
                       q(d / "old.msh") + " --quiet");
  CHECK(fold.status == 1);
  CHECK_THAT(fold.err, Catch::Contains("laytracks: error: patch \"p0\" (index 0): its boundary "
                                       "comes within"));
  CHECK_THAT(fold.err, Catch::Contains("vertex 60"));
  CHECK(slurp(d / "old.msh") == "previous content");
  CHECK(std::distance(fs::directory_iterator(d), fs::directory_iterator()) == 1);
}

TEST_CASE("mesh lowers a size beyond a quarter of the part's extent, says so, and reports both",
          "[cli][mesh]") {
  // Fuzzed parts whose mesh.size is 4 and 13 times their extent (a slotted strip 7.4 long, a
  // plate of arcs 42 across): at that size every rail got one step, and no template gave
  // valid quads. At a quarter of the extent they mesh.
  const fs::path d = fresh_dir("mesh-huge-size");
  for (const char* name : {"slots_huge_size.json", "arcs_huge_size.json"}) {
    CAPTURE(name);
    const std::string part = q(test_data_dir() + "/parts/" + name);
    const Run r = run("mesh " + part + " -o " + q(d / "m.msh") + " --report " + q(d / "r.json"));
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains("is more than a quarter of the part's extent"));
    const auto doc = nlohmann::json::parse(slurp(d / "r.json"));
    CHECK(doc["valid"].get<bool>());
    const double asked = doc["size_asked"].get<double>();
    const double size = doc["size"].get<double>();
    CHECK(size < asked / 3.9);
    // Asking for the size it used gives the same mesh, without the note.
    std::ostringstream exact;
    exact.precision(17);
    exact << size;
    const Run same = run("mesh " + part + " -o " + q(d / "n.msh") + " --size " + exact.str());
    CHECK(same.status == 0);
    CHECK(same.err.find("quarter") == std::string::npos);
    CHECK(slurp(d / "n.msh") == slurp(d / "m.msh"));
  }
}

TEST_CASE("mesh says when no valid mesh came at the size asked, and which it used", "[cli][mesh]") {
  // hugesize_stadium.json at --size 30: no template fills one face; at 0.9 of it the part
  // meshes (test_mesh_parts has the poses).
  const fs::path d = fresh_dir("mesh-retry");
  const std::string part = q(test_data_dir() + "/parts/hugesize_stadium.json");
  const Run r =
      run("mesh " + part + " --size 30 -o " + q(d / "m.msh") + " --report " + q(d / "r.json"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("no valid mesh came (mesher: no template gives valid quads"));
  const auto doc = nlohmann::json::parse(slurp(d / "r.json"));
  CHECK(doc["valid"].get<bool>());
  CHECK(doc["size"].get<double>() == Approx(0.9 * doc["size_asked"].get<double>()));
  CHECK(doc["size_asked"].get<double>() == 30.0);
  CHECK_THAT(doc["size_failed"].get<std::string>(), Catch::Contains("face 6 of patch"));
}

TEST_CASE("mesh --adaptive: the mode from the part or the command line, its report, and its "
          "mistakes", "[cli][adaptive]") {
  const fs::path d = fresh_dir("adaptive");
  // star_5 says mesh.mode "adaptive", dtheta_deg 12: the default; --uniform and --size win.
  const std::string star = q(laytracks::test::cases_dir() + "/star_5.json");
  const Run own = run("mesh " + star + " -o " + q(d / "a.msh") + " --report " + q(d / "a.json"));
  INFO(own.err);
  REQUIRE(own.status == 0);
  CHECK_THAT(own.out, Catch::Contains("worst neighbour ratio"));
  const auto a = nlohmann::json::parse(slurp(d / "a.json"));
  CHECK(a["mode"] == "adaptive");
  CHECK(a["dtheta_deg"].get<double>() == 12.0);
  CHECK(a["quality"]["size"]["worst_neighbour_ratio"].get<double>() >= 1.0);
  CHECK(a["quality"]["size"]["max"].get<double>() > 4.0 * a["quality"]["size"]["min"].get<double>());
  for (const std::string& how : {std::string("--uniform"), std::string("--size 1.5")}) {
    CAPTURE(how);
    const Run u = run("mesh " + star + " -o " + q(d / "u.msh") + " " + how + " --report " +
                      q(d / "u.json"));
    REQUIRE(u.status == 0);
    const auto uj = nlohmann::json::parse(slurp(d / "u.json"));
    CHECK(uj["mode"] == "uniform");
    CHECK(uj["quads"].get<int>() != a["quads"].get<int>());
  }
  // A uniform part made adaptive on the command line, and a finer dtheta giving more quads.
  const std::string plate = q(laytracks::test::cases_dir() + "/plate_with_hole.json");
  int previous = 0;
  for (const char* dtheta : {"20", "10"}) {
    const Run r = run("mesh " + plate + " -o " + q(d / "p.vtu") + " --adaptive --dtheta " +
                      dtheta + " --report " + q(d / "p.json"));
    REQUIRE(r.status == 0);
    const auto pj = nlohmann::json::parse(slurp(d / "p.json"));
    CHECK(pj["mode"] == "adaptive");
    CHECK(pj["quads"].get<int>() > previous);
    previous = pj["quads"].get<int>();
  }
  struct Case {
    std::string args;
    std::string message;
  };
  for (const Case& c :
       {Case{"--adaptive --size 2", "--size is the element size of uniform mode"},
        Case{"--adaptive --uniform", "choose one mode"},
        Case{"--uniform --dtheta 10", "are for adaptive mode"},
        Case{"--adaptive --dtheta 95", "--dtheta is an angle in degrees in (0, 90]"},
        Case{"--adaptive --min-size 2 --max-size 1", "is larger than --max-size"},
        Case{"--adaptive --dtheta -3", "--dtheta needs a positive number"}}) {
    CAPTURE(c.args);
    const Run r = run("mesh " + plate + " -o " + q(d / "bad.msh") + " " + c.args);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains(c.message));
    CHECK(!fs::exists(d / "bad.msh"));
  }
  // batch and draw take the same options.
  const Run b = run("batch " + plate + " " + star + " -o " + q(d / "batch") +
                    " --adaptive --dtheta 15 --quiet");
  REQUIRE(b.status == 0);
  const auto bj = nlohmann::json::parse(slurp(d / "batch" / "batch-report.json"));
  for (const auto& p : bj["parts"]) {
    CHECK(p["mode"] == "adaptive");
    CHECK(p["worst_neighbour_size_ratio"].get<double>() >= 1.0);
  }
  const Run drawn = run("draw " + plate + " --stage tracks --adaptive -o " + q(d / "t.svg"));
  CHECK(drawn.status == 0);
  CHECK(fs::exists(d / "t.svg"));
}
