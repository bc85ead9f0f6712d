// The quality summary of a mesh and its JSON: counts, statistics, histograms, key order and
// determinism.
#include <catch2/catch.hpp>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>

#include "laytracks/mesher/check.hpp"
#include "mesh_builder.hpp"
#include "test_support.hpp"

using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
using namespace laytracks;
using namespace laytracks::test;

namespace {

std::string case_path(const std::string& name) { return cases_dir() + "/" + name + ".json"; }

std::string json_of(const QualitySummary& s, bool histograms) {
  std::ostringstream out;
  write_quality_json(out, s, histograms);
  return out.str();
}

}  // namespace

TEST_CASE("the size grading is the worst size ratio of two quads sharing an edge",
          "[summary]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  // x -> x^2 / 10: column k (from 0.5 k to 0.5 (k + 1)) becomes 0.025 (2k + 1) wide, so the
  // sizes sqrt(width x 0.5) of columns 0 and 1 differ by sqrt(3), the worst neighbours.
  for (Vec3& x : g.mesh.nodes) x.x = x.x * x.x / 10.0;
  const QualitySummary s = summarize(part, g.mesh);
  CHECK(s.min_size == Approx(std::sqrt(0.025 * 0.5)));
  CHECK(s.max_size == Approx(std::sqrt(0.025 * 39 * 0.5)));
  CHECK(s.worst_neighbour_ratio == Approx(std::sqrt(3.0)));
  CHECK(s.p95_neighbour_ratio < s.worst_neighbour_ratio);
  // 20 columns of 8 quads: columns 0-1 and 18-19 hold the finest and coarsest tenths (16
  // quads each), widths 0.025 (1, 3) and 0.025 (37, 39).
  const auto col = [](int k) { return std::sqrt(0.025 * (2 * k + 1) * 0.5); };
  CHECK(s.fine_coarse_ratio == Approx((col(0) + col(1)) / (col(18) + col(19))));
  CHECK(s.p95_neighbour_ratio > 1.0);
}

TEST_CASE("a grid of squares is ideal in every measure", "[summary]") {
  const Part part = load_part(case_path("rect_10x4"));
  const GridMesh g = grid_mesh(part, 0.5);
  const QualitySummary s = summarize(part, g.mesh);
  CHECK(s.elements == 160);
  CHECK(s.quads == 160);
  CHECK(s.measured == 160);
  CHECK(s.nodes == 21 * 9);
  CHECK(s.triangles == 0);
  CHECK(s.invalid_elements == 0);
  CHECK(s.bad_angle_percent == 0.0);
  const double ideal[] = {0.0, 1.0, 1.0, 0.0, 90.0, 90.0, 1.0, 1.0};
  const char* names[] = {"skew_deg",      "aspect_ratio",  "taper",           "warp_deg",
                         "min_angle_deg", "max_angle_deg", "scaled_jacobian", "edge_ratio"};
  for (std::size_t m = 0; m < 8; ++m) {
    const MeasureSummary& ms = s.measures[m];
    INFO(ms.name);
    CHECK(ms.name == names[m]);
    CHECK(ms.mean == Approx(ideal[m]).margin(1e-9));
    CHECK(ms.worst == Approx(ideal[m]).margin(1e-9));
    CHECK(ms.p5 == Approx(ideal[m]).margin(1e-9));
    CHECK(ms.p95 == Approx(ideal[m]).margin(1e-9));
    CHECK(ms.bad_percent == 0.0);
    CHECK(ms.histogram.counts.size() == ms.histogram.lower_bounds.size());
    CHECK(std::accumulate(ms.histogram.counts.begin(), ms.histogram.counts.end(), std::size_t{0}) ==
          160);
  }
  CHECK(s.min_size == Approx(0.5));
  CHECK(s.max_size == Approx(0.5));
  CHECK(s.worst_neighbour_ratio == Approx(1.0));
  CHECK(s.p95_neighbour_ratio == Approx(1.0));
  CHECK(s.fine_coarse_ratio == Approx(1.0));
  // The ideal values land in the bins that start at them (the scaled Jacobian in the last).
  CHECK(s.measures[0].histogram.counts[0] == 160);
  CHECK(s.measures[4].histogram.counts[18] == 160);  // [90, 95)
  CHECK(s.measures[6].histogram.counts.back() == 160);
}

TEST_CASE("bad quads, triangles and malformed elements are counted", "[summary]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const PatchGrid& grid = g.grids[0];
  g.mesh.nodes[grid.node(4, 4)] = {2.6, 2.6, 0.0};                      // inverts quad (4, 4)
  g.mesh.elements[grid.element(0, 0)].nodes[3] = MeshElement::kNoNode;  // a triangle
  g.mesh.elements[grid.element(19, 7)].nodes[1] = 99999;                // malformed
  const QualitySummary s = summarize(part, g.mesh);
  CHECK(s.triangles == 1);
  CHECK(s.quads == 159);
  CHECK(s.measured == 158);
  // The inverted quads around the moved node, the triangle and the malformed quad.
  std::size_t inverted = 0;
  for (const MeshCheck& c : {check_mesh(part, g.mesh)}) inverted = c.inverted;
  CHECK(s.invalid_elements == inverted + 2);
  CHECK(s.measures[6].worst <= 0.0);  // scaled Jacobian
  CHECK(s.measures[6].bad_percent > 0.0);
  CHECK(s.bad_angle_percent > 0.0);
}

TEST_CASE("percentiles interpolate between ranks", "[summary]") {
  // One strip of quads of height 4 across the 10 x 4 plate: widths 2, 1 x 4 and 0.5 x 8, so
  // aspect ratios 2, 4 (x 4) and 8 (x 8).
  const Part part = load_part(case_path("rect_10x4"));
  QuadMesh mesh;
  std::vector<double> xs{0.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  for (int i = 1; i <= 8; ++i) xs.push_back(6.0 + 0.5 * i);
  for (double x : xs) {
    mesh.nodes.push_back({x, 0.0, 0.0});
    mesh.nodes.push_back({x, 4.0, 0.0});
  }
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    MeshElement e;
    const auto a = static_cast<std::uint32_t>(2 * i);
    e.nodes = {a, a + 2, a + 3, a + 1};
    e.patch = PatchId(0);
    mesh.elements.push_back(e);
  }
  const MeshCheck check = check_mesh(part, mesh);
  INFO(check.report());
  REQUIRE(check.valid());
  const QualitySummary s = summarize(part, mesh);
  const MeasureSummary& aspect = s.measures[1];
  CHECK(aspect.mean == Approx(82.0 / 13.0));
  CHECK(aspect.worst == Approx(8.0));
  CHECK(aspect.p5 == Approx(3.2));  // rank 0.6: 2 + 0.6 (4 - 2)
  CHECK(aspect.p95 == Approx(8.0));
  CHECK(aspect.bad_percent == Approx(100.0 * 8.0 / 13.0));
  CHECK(aspect.histogram.counts[4] == 1);  // [2, 3)
  CHECK(aspect.histogram.counts[5] == 4);  // [3, 5)
  CHECK(aspect.histogram.counts[6] == 8);  // [5, 10)
  CHECK(s.measures[7].bad_percent == Approx(100.0 * 8.0 / 13.0));
  CHECK(s.measures[0].bad_percent == 0.0);
}

TEST_CASE("the quality JSON has a fixed key order and is deterministic", "[summary]") {
  const Part part = load_part(case_path("t_junction"));
  const GridMesh g = grid_mesh(part, 0.7);
  const QualitySummary s = summarize(part, g.mesh);
  const std::string with = json_of(s, true);
  const std::string without = json_of(s, false);
  CHECK(with == json_of(summarize(part, g.mesh), true));
  CHECK_THAT(with,
             StartsWith("{\n  \"elements\": " + std::to_string(s.elements) + ",\n  \"nodes\": "));
  CHECK_THAT(with, Contains("\"histogram\""));
  CHECK_THAT(without, !Contains("\"histogram\""));
  const auto j = nlohmann::ordered_json::parse(with);
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  CHECK(keys == std::vector<std::string>{"elements", "nodes", "quads", "triangles",
                                         "invalid_elements", "measured", "bad_angle_percent", "size",
                                         "measures"});
  std::vector<std::string> measures;
  for (const auto& [k, v] : j["measures"].items()) measures.push_back(k);
  CHECK(measures == std::vector<std::string>{"skew_deg", "aspect_ratio", "taper", "warp_deg",
                                             "min_angle_deg", "max_angle_deg", "scaled_jacobian",
                                             "edge_ratio"});
  std::vector<std::string> fields;
  for (const auto& [k, v] : j["measures"]["taper"].items()) fields.push_back(k);
  CHECK(fields == std::vector<std::string>{"bad_when", "mean", "worst", "p5", "p95", "bad_percent",
                                           "histogram"});
  CHECK(j["measures"]["taper"]["bad_when"] == "<= 0.8");
  CHECK(j["measures"]["taper"]["histogram"]["lower_bounds"][3] == 0.3);
}

TEST_CASE("infinite measures are written as null", "[summary]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  auto& n = g.mesh.elements[7].nodes;
  n[2] = n[1];  // a zero-length edge: edge ratio +inf
  const QualitySummary s = summarize(part, g.mesh);
  CHECK(std::isinf(s.measures[7].worst));
  const auto j = nlohmann::json::parse(json_of(s, false));
  CHECK(j["measures"]["edge_ratio"]["worst"].is_null());
  CHECK(s.invalid_elements == 1);
}

TEST_CASE("a million quads are summarised in seconds", "[summary][timing]") {
  const Part part = load_part(case_path("rect_10x4"));
  const GridMesh g = grid_mesh(part, 10.0 / 1600.0);
  const auto t0 = std::chrono::steady_clock::now();
  const QualitySummary s = summarize(part, g.mesh);
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "summarize: " << s.elements << " quads in " << t << " s\n";
  CHECK(s.invalid_elements == 0);
  CHECK(t < 30.0);
}
