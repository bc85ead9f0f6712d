// The two-way mapping boundary -> MA -> other boundary, tested directly.
#include <catch2/catch.hpp>

#include "medial_test_util.hpp"

using namespace laytracks;
using Catch::Matchers::WithinAbs;
using laytracks::test::polygon;

namespace {

BoundaryPoint on_segment(const Polygon2& p, std::uint32_t loop, std::uint32_t seg, double s) {
  BoundaryPoint bp;
  bp.site = {BoundarySite::Kind::Segment, loop, seg};
  bp.s = s;
  const auto& l = p.loops[loop];
  bp.position = lerp(l[seg], l[(seg + 1) % l.size()], s);
  return bp;
}

}  // namespace

TEST_CASE("rectangle: a point on the long side maps to the MA at its perpendicular, then opposite",
          "[medial][mapping]") {
  const Polygon2 rect = polygon({{{0, 0}, {10, 0}, {10, 4}, {0, 4}}});
  const MedialAxis ma = compute_medial_axis(rect);
  for (double x : {2.5, 4.0, 5.0, 7.9}) {
    CAPTURE(x);
    const BoundaryPoint p = on_segment(rect, 0, 0, x / 10.0);  // (x, 0) on the bottom side
    const auto m = ma.project(p);
    REQUIRE(m);
    CHECK_THAT(m->position.x, WithinAbs(x, 1e-12));
    CHECK_THAT(m->position.y, WithinAbs(2.0, 1e-12));
    CHECK_THAT(m->radius, WithinAbs(2.0, 1e-12));
    const auto q = ma.opposite(p);
    REQUIRE(q);
    CHECK(q->site == BoundarySite{BoundarySite::Kind::Segment, 0, 2});  // the top side
    CHECK_THAT(q->position.x, WithinAbs(x, 1e-12));
    CHECK_THAT(q->position.y, WithinAbs(4.0, 1e-12));
  }
  // Near the short side the disk touches the end: (1, 0) maps onto the corner branch.
  const auto m = ma.project(on_segment(rect, 0, 0, 0.1));
  REQUIRE(m);
  CHECK_THAT(m->position.x, WithinAbs(1.0, 1e-12));
  CHECK_THAT(m->position.y, WithinAbs(1.0, 1e-12));
  const auto q = ma.opposite(on_segment(rect, 0, 0, 0.1));
  REQUIRE(q);
  CHECK(q->site == BoundarySite{BoundarySite::Kind::Segment, 0, 3});  // the left side
  CHECK_THAT(q->position.y, WithinAbs(1.0, 1e-12));
}

TEST_CASE("the mapping goes both ways: MA point -> touching points -> the same MA point",
          "[medial][mapping]") {
  const Polygon2 p = polygon({{{0, 0}, {20, 0}, {20, 6}, {6, 6}, {6, 14}, {0, 14}}});
  const MedialAxis ma = compute_medial_axis(p);
  for (std::size_t i = 0; i < ma.edges().size(); ++i) {
    for (double t : {0.25, 0.5, 0.75}) {
      const MaPoint m = ma.point_on_edge(MaEdgeId(i), t);
      for (Side side : {Side::Left, Side::Right}) {
        const BoundaryPoint b = ma.touching_point(m, side);
        CHECK_THAT(distance(b.position, m.position), WithinAbs(m.radius, 1e-9));
        if (b.site.kind != BoundarySite::Kind::Segment) continue;
        const auto back = ma.project(b);
        REQUIRE(back);
        CHECK(distance(back->position, m.position) < 1e-9);
      }
    }
  }
}

TEST_CASE("a reflex corner maps to a fan of MA points", "[medial][mapping]") {
  const Polygon2 p = polygon({{{0, 0}, {20, 0}, {20, 6}, {6, 6}, {6, 14}, {0, 14}}});
  const MedialAxis ma = compute_medial_axis(p);
  Vec2 previous{};
  for (int k = 0; k <= 4; ++k) {
    const double w = k / 4.0;
    const auto m = ma.project_corner(0, 3, w);
    REQUIRE(m);
    CHECK_THAT(distance(m->position, {6, 6}), WithinAbs(m->radius, 1e-9));
    if (k > 0) CHECK(distance(m->position, previous) > 1e-3);
    previous = m->position;
  }
  CHECK_FALSE(ma.project_corner(0, 0, 0.5));  // a convex corner has no fan
}
