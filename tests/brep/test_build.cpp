// Parts that build: the spec's example, frames, round trips, hole orientation, shared arcs,
// metamorphic invariance, and every part in ../shared/cases.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "parts.hpp"
#include "test_support.hpp"

using Catch::Matchers::Contains;
using namespace laytracks;
using namespace laytracks::test;

namespace {

/// Counts that a similarity transform of the input must not change.
struct Counts {
  std::size_t vertices = 0;
  std::size_t edges = 0;
  std::size_t smooth = 0;
  std::size_t shells = 0;
  std::size_t reversed = 0;
  bool operator==(const Counts& o) const {
    return vertices == o.vertices && edges == o.edges && smooth == o.smooth && shells == o.shells &&
           reversed == o.reversed;
  }
};

Counts counts(const Part& part) {
  Counts c{part.vertices.size(), part.edges.size(), 0, part.shell_count, 0};
  for (const Patch& p : part.patches) {
    for (const Loop& l : p.loops) {
      c.smooth += static_cast<std::size_t>(std::count(l.smooth.begin(), l.smooth.end(), true));
      c.reversed += l.reversed ? 1 : 0;
    }
  }
  return c;
}

double total_area(const Part& part) {
  double a = 0.0;
  for (const Patch& p : part.patches) a += p.area;
  return a;
}

/// Checks that every frame is orthonormal and right-handed.
void check_frames(const Part& part) {
  for (const Patch& p : part.patches) {
    const Frame& f = p.frame;
    CHECK(norm(f.u) == Approx(1.0).epsilon(1e-14));
    CHECK(norm(f.v) == Approx(1.0).epsilon(1e-14));
    CHECK(norm(f.n) == Approx(1.0).epsilon(1e-14));
    CHECK(std::fabs(dot(f.u, f.v)) < 1e-14);
    CHECK(std::fabs(dot(f.u, f.n)) < 1e-14);
    CHECK(std::fabs(dot(f.v, f.n)) < 1e-14);
    CHECK(dot(cross(f.u, f.v), f.n) == Approx(1.0).epsilon(1e-14));
  }
}

}  // namespace

TEST_CASE("the spec's example builds: shared arc points, smooth flags, edges", "[brep][build]") {
  const Part part = build_part(spec_example());
  REQUIRE(part.patches.size() == 2);
  CHECK(part.vertices.size() == 10 + 12);
  CHECK(part.edges.size() == 4 + 16 + 4 - 1);
  CHECK(part.shell_count == 1);
  const Patch& floor = part.patches[0];
  REQUIRE(floor.loops.size() == 2);
  CHECK(floor.loops[0].smooth == std::vector<bool>(4, false));  // rectangle corners
  CHECK(floor.loops[1].vertices.size() == 16);
  // Every point of the round hole is smooth: arc points, and the joints between the arcs.
  CHECK(floor.loops[1].smooth == std::vector<bool>(16, true));
  for (std::size_t i = 0; i < 16; ++i) {
    const BrepVertex& v = part.vertices[floor.loops[1].vertices[i].index()];
    CHECK(v.from_arc == (v.source_index < 0));
  }
  CHECK(floor.area == Approx(800.0 - 16 * 0.5 * 4.0 * std::sin(2 * 3.14159265358979 / 16)));
  const Patch& wall = part.patches[1];
  CHECK(wall.area == Approx(300.0));
  CHECK(wall.loops[0].smooth == std::vector<bool>(4, false));
  int shared = 0;
  for (const BrepEdge& e : part.edges) {
    if (e.patches.size() == 2) {
      ++shared;
      CHECK(e.a == VertexId(1));
      CHECK(e.b == VertexId(2));
    }
  }
  CHECK(shared == 1);
  check_frames(part);
}

TEST_CASE("two patches share the points of one arc, in opposite orders", "[brep][build]") {
  const Part part = build_part(shared_arc());
  const Loop& left = part.patches[0].loops[0];
  const Loop& right = part.patches[1].loops[0];
  std::vector<VertexId> left_points, right_points;
  for (VertexId v : left.vertices) {
    if (part.vertices[v.index()].from_arc) left_points.push_back(v);
  }
  for (VertexId v : right.vertices) {
    if (part.vertices[v.index()].from_arc) right_points.push_back(v);
  }
  REQUIRE(left_points.size() >= 1);
  std::reverse(right_points.begin(), right_points.end());
  CHECK(left_points == right_points);
  std::size_t arc_edges = 0;
  for (const BrepEdge& e : part.edges) {
    if (e.arc >= 0) {
      ++arc_edges;
      CHECK(e.patches == std::vector<PatchId>{PatchId(0), PatchId(1)});
    }
  }
  CHECK(arc_edges == left_points.size() + 1);
  // Smooth at the arc points only, not where the arc meets the straight edges.
  for (std::size_t i = 0; i < left.vertices.size(); ++i) {
    CHECK(left.smooth[i] == part.vertices[left.vertices[i].index()].from_arc);
  }
  CHECK(part.shell_count == 1);
}

TEST_CASE("3D -> 2D -> 3D round trips to 1e-12 of the part size", "[brep][build]") {
  for (const RawPart& raw : {spec_example(), cube(),
                             transformed(spec_example(), compose(translation({1e4, -3e3, 7e3}),
                                                                 rotation({1, 2, 3}, 0.7)))}) {
    const Part part = build_part(raw);
    check_frames(part);
    for (const Patch& p : part.patches) {
      const Frame& f = p.frame;
      for (double a : {-3.0, 0.0, 1.5, 40.0}) {
        for (double b : {-7.0, 0.25, 22.0}) {
          const Vec3 q = f.origin + a * f.u + b * f.v;
          const Vec2 q2 = f.to_2d(q);
          CHECK(distance(f.to_3d(q2), q) <= 1e-12 * part.size);
          CHECK(distance(q2, Vec2{a, b}) <= 1e-12 * part.size);
        }
      }
      // The polygon is the loops, projected.
      for (std::size_t l = 0; l < p.loops.size(); ++l) {
        for (std::size_t i = 0; i < p.loops[l].vertices.size(); ++i) {
          const Vec3 v = part.vertices[p.loops[l].vertices[i].index()].position;
          CHECK(distance(f.to_3d(p.polygon.loops[l][i]), v) <= 1e-6 * part.size);
        }
      }
    }
  }
}

TEST_CASE("holes are turned clockwise, the outer loop counter-clockwise", "[brep][build]") {
  const RawPart cw = square_with_holes({{2, 2, 0}, {4, 2, 0}, {4, 4, 0}}, {{4, 6, 5}});
  const RawPart ccw = square_with_holes({{2, 2, 0}, {4, 2, 0}, {4, 4, 0}}, {{4, 5, 6}});
  const Part a = build_part(cw);
  const Part b = build_part(ccw);
  CHECK_FALSE(a.patches[0].loops[1].reversed);
  CHECK(b.patches[0].loops[1].reversed);
  CHECK(b.patches[0].loops[1].vertices ==
        std::vector<VertexId>{VertexId(4), VertexId(6), VertexId(5)});
  for (const Part* part : {&a, &b}) {
    const Polygon2& poly = part->patches[0].polygon;
    CHECK(twice_signed_area(poly.loops[0]) > 0.0);
    CHECK(twice_signed_area(poly.loops[1]) < 0.0);
    CHECK(part->patches[0].area == Approx(100.0 - 2.0));
    // The edges follow the final order.
    const Loop& hole = part->patches[0].loops[1];
    for (std::size_t i = 0; i < 3; ++i) {
      const BrepEdge& e = part->edges[hole.edges[i].index()];
      const std::set<VertexId> ends{e.a, e.b};
      CHECK(ends == std::set<VertexId>{hole.vertices[i], hole.vertices[(i + 1) % 3]});
    }
  }
  // A clockwise outer loop keeps its order; the normal turns instead.
  RawPart flipped = cw;
  flipped.patches[0].loops[0] = {3, 2, 1, 0};
  const Part c = build_part(flipped);
  CHECK_FALSE(c.patches[0].loops[0].reversed);
  CHECK(c.patches[0].frame.n.z == Approx(-1.0));
  CHECK(twice_signed_area(c.patches[0].polygon.loops[0]) > 0.0);
  CHECK(twice_signed_area(c.patches[0].polygon.loops[1]) < 0.0);
}

TEST_CASE("a triangle with an extra collinear vertex is smooth there", "[brep][build]") {
  const Part part = build_part(
      make_part({{0, 0, 0}, {4, 0, 0}, {6, 0, 0}, {3, 5, 0}}, {patch("tri", {{0, 1, 2, 3}})}));
  CHECK(part.patches[0].loops[0].smooth == std::vector<bool>{false, true, false, false});
  CHECK(part.patches[0].area == Approx(15.0));
}

TEST_CASE("rotated, mirrored, moved and scaled parts build alike", "[brep][build][metamorphic]") {
  const std::vector<std::pair<const char*, RawPart>> parts = {
      {"spec example", spec_example()},
      {"cube", cube()},
      {"t junction", t_junction()},
      {"shared arc", shared_arc()},
      {"holes",
       square_with_holes({{2, 2, 0}, {4, 2, 0}, {4, 4, 0}, {6, 6, 0}, {8, 6, 0}, {8, 8, 0}},
                         {{4, 5, 6}, {7, 9, 8}})}};
  const std::vector<std::pair<const char*, Transform>> transforms = {
      {"rotation", rotation({1, 2, 3}, 0.7)},
      {"mirror", mirror_x()},
      {"translation", translation({1e5, -2e5, 3e5})},
      {"scale 1e-3", scaling(1e-3)},
      {"scale 1e3", scaling(1e3)},
      {"all", compose(translation({-50, 20, 1e3}),
                      compose(scaling(1e3), compose(mirror_x(), rotation({0, 1, 1}, 2.0))))}};
  for (const auto& [name, raw] : parts) {
    const Part base = build_part(raw);
    for (const auto& [tname, t] : transforms) {
      INFO(name << " after " << tname);
      const double scale =
          std::cbrt(std::fabs(t.m[0][0] * (t.m[1][1] * t.m[2][2] - t.m[1][2] * t.m[2][1]) -
                              t.m[0][1] * (t.m[1][0] * t.m[2][2] - t.m[1][2] * t.m[2][0]) +
                              t.m[0][2] * (t.m[1][0] * t.m[2][1] - t.m[1][1] * t.m[2][0])));
      // The size is a bbox diagonal, which a rotation changes: fix the chord tolerance so that
      // arcs are cut alike.
      BuildOptions options;
      options.chord_tol = base.chord_tol * scale;
      const Part moved = build_part(transformed(raw, t), options);
      const Counts a = counts(moved), b = counts(base);
      INFO("vertices " << a.vertices << " vs " << b.vertices << ", edges " << a.edges << " vs "
                       << b.edges << ", smooth " << a.smooth << " vs " << b.smooth << ", shells "
                       << a.shells << " vs " << b.shells << ", reversed " << a.reversed << " vs "
                       << b.reversed);
      CHECK(a == b);
      CHECK(total_area(moved) == Approx(total_area(base) * scale * scale).epsilon(1e-9));
      check_frames(moved);
    }
  }
}

TEST_CASE("every part in the shared cases builds", "[brep][build][cases]") {
  const std::vector<std::string> files = all_case_files();
  REQUIRE(files.size() >= 17);
  for (const std::string& file : files) {
    INFO(file);
    Part part;
    REQUIRE_NOTHROW(part = load_part(file));
    CHECK(part.shell_count >= 1);
    CHECK(part.size > 0.0);
    check_frames(part);
  }
}

TEST_CASE("spot checks on the shared cases", "[brep][build][cases]") {
  const std::string dir = cases_dir();
  SECTION("closed_cube: 6 patches, 12 edges each shared by 2, one shell") {
    const Part part = load_part(dir + "/closed_cube.json");
    CHECK(part.patches.size() == 6);
    CHECK(part.edges.size() == 12);
    for (const BrepEdge& e : part.edges) CHECK(e.patches.size() == 2);
    CHECK(part.shell_count == 1);
  }
  SECTION("t_junction: an edge with three patches") {
    const Part part = load_part(dir + "/t_junction.json");
    const auto n = std::count_if(part.edges.begin(), part.edges.end(),
                                 [](const BrepEdge& e) { return e.patches.size() == 3; });
    CHECK(n == 1);
  }
  SECTION("open_box: free edges along the top") {
    const Part part = load_part(dir + "/open_box.json");
    const auto free = std::count_if(part.edges.begin(), part.edges.end(),
                                    [](const BrepEdge& e) { return e.patches.size() == 1; });
    CHECK(free == 4);
    CHECK(part.shell_count == 1);
  }
  SECTION("plate_with_hole and annulus: holes of arc points, all smooth") {
    for (const char* name : {"/plate_with_hole.json", "/annulus.json"}) {
      const Part part = load_part(dir + name);
      const Loop& hole = part.patches[0].loops.at(1);
      CHECK(std::all_of(hole.smooth.begin(), hole.smooth.end(), [](bool b) { return b; }));
    }
  }
}
