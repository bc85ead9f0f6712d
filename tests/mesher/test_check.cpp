// check_mesh on structured meshes of the case parts: valid meshes pass every rule, and each
// rule broken on purpose is reported with its number and its place. Plus a 1M-quad timing.
#include <catch2/catch.hpp>
#include <chrono>
#include <iostream>
#include <map>
#include <random>

#include "../../mesher/src/node_grid.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/mesher/check.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/quality.hpp"
#include "mesh_builder.hpp"
#include "test_support.hpp"

using Catch::Matchers::Contains;
using namespace laytracks;
using namespace laytracks::test;

namespace {

std::string case_path(const std::string& name) { return cases_dir() + "/" + name + ".json"; }

/// The failure sentences of one rule.
std::vector<std::string> messages(const MeshCheck& c, int rule) {
  std::vector<std::string> out;
  for (const MeshFailure& f : c.failures) {
    if (f.rule == rule) out.push_back(f.message);
  }
  return out;
}

/// Every failure sentence, uncapped.
MeshCheck check_all(const Part& part, const QuadMesh& mesh) {
  MeshCheckOptions options;
  options.max_messages_per_rule = 1000000;
  return check_mesh(part, mesh, options);
}

/// True when some failure of `rule` contains every one of `parts`.
bool reported(const MeshCheck& c, int rule, const std::vector<std::string>& parts) {
  for (const std::string& m : messages(c, rule)) {
    bool all = m.rfind("rule " + std::to_string(rule) + ": ", 0) == 0;
    for (const std::string& p : parts) all = all && m.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

std::string el(std::size_t i) { return "element " + std::to_string(i) + " "; }
std::string nd(std::uint32_t i) { return "node " + std::to_string(i) + " "; }

struct Case {
  const char* name;
  double h;
};
const Case kCases[] = {
    {"rect_10x4", 0.5}, {"closed_cube", 1.0}, {"open_box", 1.5}, {"t_junction", 1.0}};

}  // namespace

TEST_CASE("structured meshes of the case parts are valid", "[check]") {
  for (const Case& c : kCases) {
    for (const double scale : {1.0, 0.7, 3.1}) {
      INFO(c.name << " at element size " << c.h * scale);
      const Part part = load_part(case_path(c.name));
      const GridMesh g = grid_mesh(part, c.h * scale);
      const MeshCheck check = check_mesh(part, g.mesh);
      INFO(check.report());
      CHECK(check.valid());
      CHECK(check.failures.empty());
      CHECK(check.elements == g.mesh.elements.size());
      CHECK(check.quads == g.mesh.elements.size());
      CHECK(check.triangles == 0);
      CHECK(check.unused_nodes == 0);
    }
  }
}

TEST_CASE("valid meshes stay valid when the part is moved, turned, mirrored or scaled", "[check]") {
  const Transform moves[] = {
      compose(translation({100.0, -40.0, 7.0}), rotation({1.0, 2.0, 3.0}, 0.9)),
      mirror_x(),
      scaling(1e-3),
      compose(scaling(1e4), rotation({0.0, 1.0, 1.0}, 2.5)),
  };
  for (const Case& c : kCases) {
    const RawPart raw = read_brep_json(case_path(c.name));
    const std::size_t count = grid_mesh(load_part(case_path(c.name)), c.h).mesh.elements.size();
    for (const Transform& t : moves) {
      INFO(c.name);
      const Part part = build_part(transformed(raw, t));
      const double scale =
          std::cbrt(std::fabs(t.m[0][0] * (t.m[1][1] * t.m[2][2] - t.m[1][2] * t.m[2][1]) -
                              t.m[0][1] * (t.m[1][0] * t.m[2][2] - t.m[1][2] * t.m[2][0]) +
                              t.m[0][2] * (t.m[1][0] * t.m[2][1] - t.m[1][1] * t.m[2][0])));
      const GridMesh g = grid_mesh(part, c.h * scale);
      CHECK(g.mesh.elements.size() == count);
      const MeshCheck check = check_mesh(part, g.mesh);
      INFO(check.report());
      CHECK(check.valid());
    }
  }
}

TEST_CASE("rule 1: a quad split into two triangles", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const std::size_t k = g.grids[0].element(3, 2);
  MeshElement& e = g.mesh.elements[k];
  MeshElement second = e;
  second.nodes = {e.nodes[0], e.nodes[2], e.nodes[3], MeshElement::kNoNode};
  e.nodes[3] = MeshElement::kNoNode;
  g.mesh.elements.push_back(second);
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.triangles == 2);
  CHECK(check.counts[1] == 2);
  CHECK(reported(
      check, 1,
      {el(k), "patch \"plate\" (index 0)", "triangle", "at (1.833333333, 1.166666667, 0)"}));
  // The two triangles cover the quad conformally: nothing else is wrong.
  for (int r = 2; r <= 6; ++r) CHECK(check.counts[static_cast<std::size_t>(r)] == 0);
}

TEST_CASE("rule 1: node and patch ids out of range are malformed, not a crash", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  g.mesh.elements[5].nodes[2] = 100000;
  g.mesh.elements[6].patch = PatchId(7);
  const MeshCheck check = check_mesh(part, g.mesh);
  CHECK(check.malformed == 2);
  CHECK(reported(check, 1, {el(5), "node id is out of range"}));
  CHECK(reported(check, 1, {el(6), "patch index 7 (out of range)", "patch id is out of range"}));
  CHECK_FALSE(check.valid());
}

TEST_CASE("rule 2: an interior node pushed past its neighbours inverts quads", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const PatchGrid& grid = g.grids[0];
  g.mesh.nodes[grid.node(4, 4)] = {2.6, 2.6,
                                   0.0};  // beyond (2.5, 2.5), the far corner of quad (4, 4)
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.counts[2] >= 1);
  CHECK(reported(check, 2,
                 {el(grid.element(4, 4)), "patch \"plate\" (index 0)", "inverted or degenerate",
                  "scaled Jacobian"}));
  // Moving an interior node keeps the mesh conformal and the signed areas' sum.
  CHECK(check.counts[1] == 0);
  CHECK(check.counts[3] == 0);
  CHECK(check.counts[4] == 0);
  CHECK(check.counts[5] == 0);
  CHECK(check.counts[6] == 0);
}

TEST_CASE("rule 3: a quad with its nodes in clockwise order", "[check]") {
  const Part part = load_part(case_path("closed_cube"));
  GridMesh g = grid_mesh(part, 1.0);
  const std::size_t k = g.grids[3].element(2, 5);  // on patch "right"
  auto& n = g.mesh.elements[k].nodes;
  n = {n[0], n[3], n[2], n[1]};
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.flipped == 1);
  CHECK(reported(check, 3, {el(k), "patch \"right\" (index 3)", "oriented against", "at (10, "}));
  CHECK(check.counts[2] == 0);
  CHECK(check.counts[4] == 1);  // its area counts negative
  CHECK(check.counts[5] == 0);
}

TEST_CASE("rule 3: a node lifted off its patch's plane", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const std::uint32_t n = g.grids[0].node(6, 3);
  g.mesh.nodes[n].z = 0.01;
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.counts[3] == 4);
  CHECK(reported(check, 3, {"off its patch's plane", nd(n), "patch \"plate\" (index 0)"}));
}

TEST_CASE("rule 3: an element outside its patch", "[check]") {
  // Retag a quad of the cube's top as a quad of its bottom: same normal direction up to sign,
  // but its centroid is not in the bottom's polygon and its nodes are off the bottom's plane.
  const Part part = load_part(case_path("closed_cube"));
  GridMesh g = grid_mesh(part, 1.0);
  const std::size_t k = g.grids[1].element(4, 4);
  g.mesh.elements[k].patch = PatchId(2);  // "front": the plane y = 0
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 3, {el(k), "patch \"front\" (index 2)", "off its patch's plane"}));
}

TEST_CASE("rules 4 and 5: a missing quad", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const std::size_t k = g.grids[0].element(10, 4);
  g.mesh.elements.erase(g.mesh.elements.begin() + static_cast<std::ptrdiff_t>(k));
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.counts[4] == 1);
  CHECK(reported(check, 4, {"patch \"plate\" (index 0)", "cover 39.75", "area 40"}));
  CHECK(check.counts[5] == 4);  // the hole's four edges
  CHECK(reported(check, 5,
                 {"patch \"plate\" (index 0)", "used by one element", "crack", "at (5, 2, 0)"}));
  CHECK(check.counts[1] == 0);
  CHECK(check.counts[2] == 0);
  CHECK(check.counts[3] == 0);
}

TEST_CASE("rule 5: a duplicated node", "[check]") {
  const Part part = load_part(case_path("open_box"));
  GridMesh g = grid_mesh(part, 1.5);
  const std::uint32_t n = g.grids[0].node(5, 5);  // inside "bottom"
  g.mesh.nodes.push_back(g.mesh.nodes[n]);
  const auto copy = static_cast<std::uint32_t>(g.mesh.nodes.size() - 1);
  auto& e = g.mesh.elements[g.grids[0].element(5, 5)];
  REQUIRE(e.nodes[0] == n);
  e.nodes[0] = copy;
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 5,
                 {nd(n), nd(copy), "closer than", "patch \"bottom\" (index 0)", "at (7.5, 7.69"}));
}

TEST_CASE("rule 5: a hanging node", "[check]") {
  // Split one quad into two by the midpoints of two opposite edges: the midpoints hang on the
  // neighbours' edges.
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const std::size_t k = g.grids[0].element(7, 3);
  const auto nodes = g.mesh.elements[k].nodes;  // (3.5,1.5) (4,1.5) (4,2) (3.5,2)
  const Vec3 m1 = 0.5 * (g.mesh.nodes[nodes[0]] + g.mesh.nodes[nodes[1]]);
  const Vec3 m2 = 0.5 * (g.mesh.nodes[nodes[2]] + g.mesh.nodes[nodes[3]]);
  g.mesh.nodes.push_back(m1);
  g.mesh.nodes.push_back(m2);
  const auto i1 = static_cast<std::uint32_t>(g.mesh.nodes.size() - 2);
  const auto i2 = i1 + 1;
  g.mesh.elements[k].nodes = {nodes[0], i1, i2, nodes[3]};
  MeshElement right = g.mesh.elements[k];
  right.nodes = {i1, nodes[1], nodes[2], i2};
  g.mesh.elements.push_back(right);
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 5,
                 {nd(i1), "(3.75, 1.5, 0)",
                  "hangs inside the mesh edge from node " + std::to_string(nodes[0]) + " to node " +
                      std::to_string(nodes[1]),
                  "patch \"plate\" (index 0)"}));
  CHECK(reported(check, 5, {nd(i2), "hangs inside"}));
  CHECK(check.counts[4] == 0);  // the area is still covered
  CHECK(check.counts[2] == 0);
}

TEST_CASE("rule 5: a non-conformal seam at a three-patch junction", "[check]") {
  const Part part = load_part(case_path("t_junction"));
  const std::size_t rib = 2;
  REQUIRE(part.patches[rib].name == "rib");
  const GridMesh ok = grid_mesh(part, 1.0);
  GridMesh g = grid_mesh(part, 1.0, {{rib, {ok.grids[rib].nu + 1, ok.grids[rib].nv}}});
  const MeshCheck check = check_all(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 5,
                 {"lies on B-Rep edge", "used by 3 patches", "patch \"rib\" (index 2)",
                  "it needs exactly one element of each"}));
  CHECK(reported(check, 5, {"hangs inside"}));
  CHECK(check.counts[1] == 0);
  CHECK(check.counts[2] == 0);
  CHECK(check.counts[3] == 0);
  CHECK(check.counts[4] == 0);
}

TEST_CASE("rule 5: every node hanging on one long edge is found", "[check]") {
  // Fine plates, and a rib of a single quad: the plates' 47 inner nodes along the junction all
  // hang on the rib's 12-long edge, many grid cells long.
  const Part part = load_part(case_path("t_junction"));
  const GridMesh g = grid_mesh(part, 0.25, {{2, {1, 1}}});
  const MeshCheck check = check_all(part, g.mesh);
  std::size_t hanging = 0;
  for (const std::string& m : messages(check, 5)) {
    if (m.find("hangs inside") != std::string::npos) {
      ++hanging;
      CHECK_THAT(m, Contains("patch \"rib\" (index 2)"));
      CHECK_THAT(m, Contains("at (10, "));
    }
  }
  CHECK(hanging == 47);
}

TEST_CASE("an empty mesh fails, without crashing", "[check]") {
  const Part part = load_part(case_path("closed_cube"));
  const MeshCheck check = check_mesh(part, QuadMesh{});
  CHECK_FALSE(check.valid());
  CHECK(check.counts[4] == 6);  // no patch covered
  CHECK(check.counts[6] == 8);  // no corner is a node
  CHECK(reported(check, 6, {"B-Rep vertex 7 at (0, 10, 10)", "is not a mesh node"}));
}

TEST_CASE("rule 5: a cube face meshed apart from its neighbours", "[check]") {
  // The right face gets its own nodes along its edges: every seam is open.
  const Part part = load_part(case_path("closed_cube"));
  GridMesh g = grid_mesh(part, 1.0);
  const std::size_t right = 3;
  std::map<std::uint32_t, std::uint32_t> copies;
  for (MeshElement& e : g.mesh.elements) {
    if (e.patch.index() != right) continue;
    for (auto& n : e.nodes) {
      const auto [it, fresh] = copies.emplace(n, 0);
      if (fresh) {
        g.mesh.nodes.push_back(g.mesh.nodes[n]);
        it->second = static_cast<std::uint32_t>(g.mesh.nodes.size() - 1);
      }
      n = it->second;
    }
  }
  const MeshCheck check = check_all(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 5, {"used by 2 patches"}));
  CHECK(reported(check, 5, {"closer than"}));
  CHECK(check.unused_nodes > 0);
}

TEST_CASE("rule 6: a boundary node moved off its B-Rep edge", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  const std::uint32_t n = g.grids[0].node(5, 0);  // (2.5, 0, 0) on the bottom edge
  g.mesh.nodes[n] = {2.5, 0.1, 0.0};
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 6,
                 {nd(n), "(2.5, 0.1, 0)", "patch \"plate\" (index 0)", "on no B-Rep edge"}));
  CHECK(check.counts[6] == 1);
}

TEST_CASE("rule 6: a node moved off a fold of the cube", "[check]") {
  const Part part = load_part(case_path("closed_cube"));
  GridMesh g = grid_mesh(part, 1.0);
  const std::uint32_t n = g.grids[0].node(4, 0);  // (0, 4, 0): on the edge between vertices 0, 1
  const Vec3 x = g.mesh.nodes[n];
  REQUIRE(x.x == 0.0);
  REQUIRE(x.z == 0.0);
  g.mesh.nodes[n].x += 0.05;  // into the bottom, off the left face
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(reported(check, 6, {nd(n), "patch \"bottom\" (index 0)", "on no B-Rep edge"}));
  CHECK(reported(check, 3, {"patch \"left\" (index 5)", "off its patch's plane"}));
}

TEST_CASE("rule 6: a B-Rep corner that is not a mesh node", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  g.mesh.nodes[g.grids[0].node(0, 0)] = {0.1, 0.0, 0.0};  // slid along the bottom edge
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(
      reported(check, 6,
               {"B-Rep vertex 0 at (0, 0, 0)", "patch \"plate\" (index 0)", "is not a mesh node"}));
}

TEST_CASE("messages are capped per rule, counts are not", "[check]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 0.5);
  for (MeshElement& e : g.mesh.elements) e.nodes = {e.nodes[0], e.nodes[3], e.nodes[2], e.nodes[1]};
  MeshCheckOptions options;
  options.max_messages_per_rule = 3;
  const MeshCheck check = check_mesh(part, g.mesh, options);
  CHECK(check.counts[3] == g.mesh.elements.size());
  CHECK(messages(check, 3).size() == 3);
  CHECK(check.flipped == g.mesh.elements.size());
}

TEST_CASE("a million quads are checked in seconds", "[check][timing]") {
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
  };
  SECTION("one patch: rect_10x4 at 1600 x 640") {
    const Part part = load_part(case_path("rect_10x4"));
    const GridMesh g = grid_mesh(part, 10.0 / 1600.0);
    REQUIRE(g.mesh.elements.size() == 1024000);
    const auto t0 = Clock::now();
    const MeshCheck check = check_mesh(part, g.mesh);
    const double t = seconds(t0, Clock::now());
    std::cout << "check_mesh: " << g.mesh.elements.size() << " quads of rect_10x4 in " << t
              << " s\n";
    CHECK(check.valid());
    CHECK(t < 30.0);
  }
  SECTION("a closed shell: closed_cube at 6 x 408 x 408") {
    const Part part = load_part(case_path("closed_cube"));
    const GridMesh g = grid_mesh(part, 10.0 / 408.0);
    REQUIRE(g.mesh.elements.size() == 6u * 408u * 408u);
    const auto t0 = Clock::now();
    const MeshCheck check = check_mesh(part, g.mesh);
    const double t = seconds(t0, Clock::now());
    std::cout << "check_mesh: " << g.mesh.elements.size() << " quads of closed_cube in " << t
              << " s\n";
    INFO(check.report());
    CHECK(check.valid());
    CHECK(t < 30.0);
  }
}

// The validator's private spatial index (header-only), against brute force.

TEST_CASE("the node grid finds every point near a segment and every close pair", "[check]") {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < 3000; ++i) pts.push_back({u(rng), u(rng), 0.5 * u(rng)});
  // Points on segments (some long, across many cells) and near-duplicates.
  const Vec3 a{0.3, 0.2, 0.1};
  const Vec3 b{9.7, 8.9, 4.6};
  for (int i = 1; i < 50; ++i) pts.push_back(a + (static_cast<double>(i) / 50.0) * (b - a));
  for (int i = 0; i < 20; ++i)
    pts.push_back(pts[static_cast<std::size_t>(i * 7)] + Vec3{1e-7, 0.0, 0.0});
  pts.push_back({std::nan(""), 0.0, 0.0});  // ignored
  const detail::NodeGrid grid(pts, 0.3);
  const double r = 0.05;
  for (const auto& [p, q] : {std::pair{a, b}, std::pair{Vec3{0, 0, 0}, Vec3{0.1, 0.1, 0.0}},
                             std::pair{Vec3{10, 0, 5}, Vec3{0, 10, 0}}}) {
    std::vector<std::uint32_t> found;
    grid.for_each_near_segment(p, q, r, [&](std::uint32_t i) { found.push_back(i); });
    std::sort(found.begin(), found.end());
    CHECK(std::adjacent_find(found.begin(), found.end()) == found.end());  // once each
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (!is_finite(pts[i])) continue;
      const Vec3 d = q - p;
      const double t = std::clamp(dot(pts[i] - p, d) / dot(d, d), 0.0, 1.0);
      if (distance(pts[i], p + t * d) <= r) {
        CHECK(std::binary_search(found.begin(), found.end(), static_cast<std::uint32_t>(i)));
      }
    }
  }
  const double close = 1e-3;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> brute;
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    for (std::uint32_t j = i + 1; j < pts.size(); ++j) {
      if (is_finite(pts[i]) && is_finite(pts[j]) && distance(pts[i], pts[j]) < close) {
        brute.emplace_back(i, j);
      }
    }
  }
  CHECK(brute.size() >= 20);
  CHECK(grid.close_pairs(close) == brute);
}

namespace {

/// Quads (0, 0) and (1, 0) of patch 0's grid make a 2 x 1 block A M B / D N C; split along A-C
/// instead of M-N, the first quad has a flat corner at boundary node M (scaled Jacobian 0).
void split_along_wrong_diagonal(GridMesh& g) {
  const PatchGrid& p = g.grids[0];
  const std::uint32_t A = p.node(0, 0), M = p.node(1, 0), B = p.node(2, 0);
  const std::uint32_t C = p.node(2, 1), N = p.node(1, 1), D = p.node(0, 1);
  g.mesh.elements[p.element(0, 0)].nodes = {A, M, B, C};
  g.mesh.elements[p.element(1, 0)].nodes = {C, N, D, A};
}

}  // namespace

TEST_CASE("edge flips re-split a pair of quads along their hexagon's best diagonal",
          "[check][flip][refill]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 1.0);
  REQUIRE(check_mesh(part, g.mesh).valid());
  SECTION("a structured grid has nothing to flip, nor to re-fill") {
    const QuadMesh before = g.mesh;
    CHECK(flip_edges(part, g.mesh) == 0);
    CHECK(refill_cavities(part, g.mesh, 10) == 0);
    REQUIRE(g.mesh.elements.size() == before.elements.size());
    CHECK(g.mesh.nodes.size() == before.nodes.size());
    for (std::size_t k = 0; k < before.elements.size(); ++k)
      CHECK(g.mesh.elements[k].nodes == before.elements[k].nodes);
  }
  SECTION("two squares split along the wrong diagonal become two squares again") {
    split_along_wrong_diagonal(g);
    REQUIRE_FALSE(check_mesh(part, g.mesh).valid());  // rule 2: a flat corner
    const std::size_t count = g.mesh.elements.size();
    CHECK(flip_edges(part, g.mesh) == 1);
    CHECK(g.mesh.elements.size() == count);
    const MeshCheck check = check_mesh(part, g.mesh);
    INFO(check.report());
    CHECK(check.valid());
    CHECK(summarize(part, g.mesh).measures[6].worst == Approx(1.0));
  }
}

TEST_CASE("cavity re-fill gives a boundary node that one quad meets flat a second quad",
          "[check][refill]") {
  const Part part = load_part(case_path("rect_10x4"));
  GridMesh g = grid_mesh(part, 1.0);
  // Boundary node M is a corner of one quad only, a flat one: no relaxation can mend that
  // (M stays on the boundary).
  split_along_wrong_diagonal(g);
  const PatchGrid& p = g.grids[0];
  REQUIRE(summarize(part, g.mesh).measures[6].worst < 1e-9);
  // The nodes of the patch boundary, which must all stay where they are.
  std::map<std::pair<double, double>, int> boundary;
  for (int i = 0; i <= p.nu; ++i)
    for (int j = 0; j <= p.nv; ++j)
      if (i == 0 || j == 0 || i == p.nu || j == p.nv) {
        const Vec3 b = g.mesh.nodes[p.node(i, j)];
        boundary[{b.x, b.y}] = 0;
      }
  // Since session 40 the patch, a rectangle, is first filled again whole (a lattice): a
  // regrid; either way the node gets its second quad.
  std::size_t regrids = 0;
  CHECK(refill_cavities(part, g.mesh, 10, kRefillBelowUniform, &regrids) + regrids >= 1);
  const MeshCheck check = check_mesh(part, g.mesh);
  INFO(check.report());
  CHECK(check.valid());
  CHECK(summarize(part, g.mesh).measures[6].worst > 0.5);
  for (const Vec3& n : g.mesh.nodes) {
    const auto it = boundary.find({n.x, n.y});
    if (it != boundary.end()) ++it->second;
  }
  for (const auto& [xy, count] : boundary) CHECK(count == 1);
  // No node is left that no quad uses.
  std::vector<bool> used(g.mesh.nodes.size(), false);
  for (const MeshElement& e : g.mesh.elements)
    for (std::uint32_t n : e.nodes) used[n] = true;
  CHECK(std::count(used.begin(), used.end(), false) == 0);
}

TEST_CASE("the star of a pole of 32 quads is filled again though its boundary has 64 nodes",
          "[check][refill]") {
  // A disk (a 64-gon of radius 2) meshed by hand: ring A of 64 nodes, the even ones at radius
  // 1 and the odd ones at 1.4 between them, 32 kites round the centre with corners of 11.25
  // degrees there (0.195), and 64 quads from ring A to the boundary. The centre's star has 64
  // boundary nodes, over kMaxCavityNodes (48); a pole's star may have kMaxPoleCavityNodes (96).
  constexpr int n = 64;
  RawPart raw;
  std::vector<std::int64_t> loop;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n;
    raw.vertices.push_back({2.0 * std::cos(t), 2.0 * std::sin(t), 0.0});
    loop.push_back(i);
  }
  raw.patches.push_back({std::string("disk"), {loop}});
  const Part part = build_part(raw);
  QuadMesh mesh;
  mesh.nodes = raw.vertices;  // ring B: 0 .. n - 1
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * kPi * i / n, r = i % 2 == 0 ? 1.0 : 1.4;
    mesh.nodes.push_back({r * std::cos(t), r * std::sin(t), 0.0});  // ring A: n .. 2n - 1
  }
  const auto centre = static_cast<std::uint32_t>(mesh.nodes.size());
  mesh.nodes.push_back({0.0, 0.0, 0.0});
  const auto b = [&](int i) { return static_cast<std::uint32_t>(i % n); };
  const auto a = [&](int i) { return static_cast<std::uint32_t>(n + i % n); };
  const auto quad = [&](std::array<std::uint32_t, 4> q) {
    MeshElement e;
    e.nodes = q;
    e.patch = PatchId(0);
    mesh.elements.push_back(e);
  };
  for (int k = 0; k < n / 2; ++k) quad({centre, a(2 * k), a(2 * k + 1), a(2 * k + 2)});
  for (int i = 0; i < n; ++i) quad({a(i), b(i), b(i + 1), a(i + 1)});
  REQUIRE(check_mesh(part, mesh).valid());
  REQUIRE(summarize(part, mesh).measures[6].worst < 0.2);
  CHECK(refill_cavities(part, mesh, 10) >= 1);
  const MeshCheck check = check_mesh(part, mesh);
  INFO(check.report());
  CHECK(check.valid());
  CHECK(summarize(part, mesh).measures[6].worst > 0.3);
}
