// The medial axis on shapes whose axis is known in closed form.
#include <algorithm>
#include <catch2/catch.hpp>
#include <ostream>

#include "medial_test_util.hpp"

using namespace laytracks;
using Catch::Matchers::WithinAbs;
using laytracks::test::polygon;
using laytracks::test::regular;
using laytracks::test::structure;

namespace {

bool has_vertex_near(const MedialAxis& ma, Vec2 p, double tol, double* radius = nullptr) {
  for (const auto& v : ma.vertices()) {
    if (distance(v.position, p) <= tol) {
      if (radius) *radius = v.radius;
      return true;
    }
  }
  return false;
}

}  // namespace

TEST_CASE("rectangle 10x4: two branch points of radius 2 and four corner branches", "[medial]") {
  const MedialAxis ma = compute_medial_axis(polygon({{{0, 0}, {10, 0}, {10, 4}, {0, 4}}}));
  const auto branches = ma.branch_points();
  REQUIRE(branches.size() == 2);
  std::vector<Vec2> pts;
  for (auto b : branches) {
    pts.push_back(ma.vertex(b).position);
    CHECK_THAT(ma.vertex(b).radius, WithinAbs(2.0, 1e-12));
    CHECK(ma.vertex(b).degree == 3);
    CHECK(ma.touching_points(b).size() == 3);
  }
  std::sort(pts.begin(), pts.end(), [](Vec2 a, Vec2 b) { return a.x < b.x; });
  CHECK_THAT(pts[0].x, WithinAbs(2.0, 1e-12));
  CHECK_THAT(pts[0].y, WithinAbs(2.0, 1e-12));
  CHECK_THAT(pts[1].x, WithinAbs(8.0, 1e-12));
  CHECK_THAT(pts[1].y, WithinAbs(2.0, 1e-12));
  CHECK(ma.edges().size() == 5);
  std::size_t corners = 0;
  for (const auto& v : ma.vertices()) {
    if (v.corner) {
      ++corners;
      CHECK(v.degree == 1);
      CHECK(v.radius == 0.0);
    }
  }
  CHECK(corners == 4);
  CHECK(ma.validate().empty());
}

TEST_CASE("L-shape: one parabolic arc, at the reflex corner", "[medial]") {
  const MedialAxis ma =
      compute_medial_axis(polygon({{{0, 0}, {20, 0}, {20, 6}, {6, 6}, {6, 14}, {0, 14}}}));
  // The arc around the reflex corner (6, 6) is one curve in two Voronoi edges: the corner
  // against the bottom side and against the left side, meeting at the branch point that also
  // touches both sides, (t, t) with t = 6 (2 - sqrt 2).
  std::vector<MaEdge> parabolas;
  for (const auto& e : ma.edges()) {
    if (e.kind != MaEdgeKind::Parabola) continue;
    parabolas.push_back(e);
    const BoundarySite& corner = e.left.kind == BoundarySite::Kind::Corner ? e.left : e.right;
    CHECK(corner.index == 3);
  }
  REQUIRE(parabolas.size() == 2);
  const auto shared = [&](MaVertexId v) { return v == parabolas[1].a || v == parabolas[1].b; };
  const MaVertexId joint = shared(parabolas[0].a) ? parabolas[0].a : parabolas[0].b;
  REQUIRE(shared(joint));
  const double tj = 6.0 * (2.0 - std::sqrt(2.0));
  CHECK(distance(ma.vertex(joint).position, {tj, tj}) < 1e-9);
  CHECK(ma.vertex(joint).degree == 3);
  // Points of the parabola are equidistant from the corner and from the opposite side.
  for (std::size_t i = 0; i < ma.edges().size(); ++i) {
    if (ma.edges()[i].kind != MaEdgeKind::Parabola) continue;
    for (double t : {0.1, 0.5, 0.9}) {
      const MaPoint p = ma.point_on_edge(MaEdgeId(i), t);
      CHECK_THAT(distance(p.position, {6, 6}), WithinAbs(p.radius, 1e-9));
    }
  }
  CHECK(ma.validate().empty());
}

TEST_CASE("square with a square hole: a single cycle around the hole", "[medial]") {
  const MedialAxis ma = compute_medial_axis(
      polygon({{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{3, 3}, {3, 7}, {7, 7}, {7, 3}}}));
  const auto s = structure(ma);
  CHECK(s.components == 1);
  CHECK(s.cycles == 1);
  CHECK(s.leaves == 4);  // the outer corners
  // The hole's corners are reflex: the axis keeps a distance 1.5 from the hole's sides and
  // bends around its corners with parabolas.
  std::size_t parabolas = 0;
  for (const auto& e : ma.edges()) parabolas += e.kind == MaEdgeKind::Parabola ? 1 : 0;
  CHECK(parabolas == 8);
  CHECK(ma.validate().empty());
}

TEST_CASE("regular polygon: one branch point at the centre", "[medial]") {
  for (std::size_t n : {3u, 5u, 6u, 12u}) {
    CAPTURE(n);
    const MedialAxis ma = compute_medial_axis(polygon({regular(n, 5.0, {1, -2})}));
    const auto b = ma.branch_points();
    REQUIRE(b.size() == 1);
    CHECK(distance(ma.vertex(b[0]).position, {1, -2}) < 1e-9);
    CHECK(ma.vertex(b[0]).degree == n);
    CHECK_THAT(ma.vertex(b[0]).radius,
               WithinAbs(5.0 * std::cos(M_PI / static_cast<double>(n)), 1e-9));
    CHECK(ma.edges().size() == n);
  }
}

TEST_CASE("nearly flat corners grow no branch: a 24-gon's axis is its centre", "[medial]") {
  // Its corners turn by 15 degrees, less than kFlatCornerTurn: pruned as a polygonised
  // circle's are, so the axis is the deepest vertex. Without the rule, 24 branches.
  const Polygon2 p = polygon({regular(24, 5.0, {1, -2})});
  const MedialAxis flat = compute_medial_axis(p);
  REQUIRE(flat.vertices().size() == 1);
  CHECK(distance(flat.vertices()[0].position, {1, -2}) < 1e-9);
  MedialOptions off;
  off.flat_turn = 0.0;
  CHECK(compute_medial_axis(p, off).edges().size() == 24);
  // A 12-gon's corners turn by 30 degrees: they keep their branches.
  CHECK(compute_medial_axis(polygon({regular(12, 5.0)})).edges().size() == 12);
}

namespace {

/// An annulus whose circles are polygonised with n segments each, all corners smooth.
Polygon2 smooth_annulus(std::size_t n, double outer, double inner) {
  Polygon2 p = polygon({regular(n, outer), regular(n, inner, {}, true)});
  for (auto& s : p.smooth) std::fill(s.begin(), s.end(), true);
  return p;
}

}  // namespace

TEST_CASE("annulus: the axis is a ring of radius 16 with no branch point", "[medial]") {
  for (std::size_t n : {16u, 64u, 256u}) {
    CAPTURE(n);
    const double chord = 20.0 * (1.0 - std::cos(M_PI / static_cast<double>(n)));
    MedialOptions opt;
    opt.chord_tol = chord;
    const MedialAxis ma = compute_medial_axis(smooth_annulus(n, 20.0, 12.0), opt);
    const auto s = structure(ma);
    CHECK(s.branch_points == 0);
    CHECK(s.leaves == 0);
    CHECK(s.cycles == 1);
    CHECK(s.components == 1);
    for (const auto& v : ma.vertices()) CHECK_THAT(norm(v.position), WithinAbs(16.0, 2 * chord));
    CHECK(ma.validate().empty());
  }
}

TEST_CASE("a smooth circle polygonised with 16 or 256 segments has the same structure",
          "[medial]") {
  auto plate_with_hole = [](std::size_t n) {
    Polygon2 p = polygon({{{0, 0}, {30, 0}, {30, 20}, {0, 20}}, regular(n, 3.0, {12, 10}, true)});
    std::fill(p.smooth[1].begin(), p.smooth[1].end(), true);
    return p;
  };
  auto disk = [](std::size_t n) {
    Polygon2 p = polygon({regular(n, 3.0, {12, 10})});
    std::fill(p.smooth[0].begin(), p.smooth[0].end(), true);
    return p;
  };
  MedialOptions opt;
  opt.chord_tol = 3.0 * (1.0 - std::cos(M_PI / 16.0));
  const auto hole16 = structure(compute_medial_axis(plate_with_hole(16), opt));
  const auto hole256 = structure(compute_medial_axis(plate_with_hole(256), opt));
  CHECK(hole16 == hole256);
  CHECK(hole16.cycles == 1);
  CHECK(hole16.leaves == 4);

  const MedialAxis d16 = compute_medial_axis(disk(16), opt);
  const MedialAxis d256 = compute_medial_axis(disk(256), opt);
  CHECK(structure(d16) == structure(d256));
  REQUIRE(d256.vertices().size() == 1);  // the disk's axis is its centre
  CHECK(distance(d256.vertices()[0].position, {12, 10}) < 1e-9);
}

TEST_CASE("stadium with tangent straight sides keeps its middle segment", "[medial]") {
  // Two half circles of radius 2 (centres (0,0) and (10,0)) joined by tangent lines.
  Polygon2 p;
  std::vector<Vec2> loop;
  std::vector<bool> smooth;
  const int n = 32;
  for (int i = 0; i <= n; ++i) {  // right half circle, from bottom to top
    const double a = -M_PI / 2 + M_PI * i / n;
    loop.push_back({10 + 2 * std::cos(a), 2 * std::sin(a)});
    smooth.push_back(true);
  }
  for (int i = 0; i <= n; ++i) {  // left half circle, from top to bottom
    const double a = M_PI / 2 + M_PI * i / n;
    loop.push_back({2 * std::cos(a), 2 * std::sin(a)});
    smooth.push_back(true);
  }
  p.loops = {loop};
  p.smooth = {smooth};
  MedialOptions opt;
  opt.chord_tol = 2.0 * (1.0 - std::cos(M_PI / (2.0 * n)));
  const MedialAxis ma = compute_medial_axis(p, opt);
  const auto s = structure(ma);
  CHECK(s.branch_points == 0);
  CHECK(s.leaves == 2);
  double r = 0.0;
  CHECK(has_vertex_near(ma, {0, 0}, 10 * opt.chord_tol, &r));
  CHECK(has_vertex_near(ma, {10, 0}, 10 * opt.chord_tol, &r));
  CHECK_THAT(r, WithinAbs(2.0, 2 * opt.chord_tol));
}
