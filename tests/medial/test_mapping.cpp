// The two-way mapping boundary -> MA -> other boundary, tested directly.
#include <catch2/catch.hpp>

#include <algorithm>

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

/// The images of the bottom points x = x0, x0 + dx, ... (n of them, across a dip at x = 200 of
/// a box's bottom: segment 0 before it, 1 after) under project(), each checked to map one-to-one
/// both ways: never into the disk, across to the top and back to the same MA
/// point, and from it back to the bottom point itself. The images must be distinct and in the
/// boundary's order: no two rails from the stretch meet. The top is segments top0 to top1.
static std::vector<MaPoint> images_across_dip(const Polygon2& p, const MedialAxis& ma, double x0,
                                              double dx, int n, std::uint32_t top0,
                                              std::uint32_t top1) {
  std::vector<MaPoint> images;
  for (int k = 0; k < n; ++k) {
    const double x = x0 + dx * k;
    CAPTURE(x);
    const BoundaryPoint b = x < 200.0 ? on_segment(p, 0, 0, x / 200.0)
                                      : on_segment(p, 0, 1, (x - 200.0) / 200.0);
    const auto m = ma.project(b);
    REQUIRE(m);
    REQUIRE(m->edge.valid());
    CHECK(distance(b.position, m->position) >= m->radius - 1e-9);
    const Side far = ma.far_side(*m, b);
    const BoundaryPoint q = ma.touching_point(*m, far);
    CHECK(q.site.kind == BoundarySite::Kind::Segment);
    CHECK(q.site.index >= top0);
    CHECK(q.site.index <= top1);
    const auto back = ma.project(q);
    REQUIRE(back);
    CHECK(distance(back->position, m->position) < 1e-9);
    const BoundaryPoint near = ma.touching_point(*m, far == Side::Left ? Side::Right : Side::Left);
    CHECK(distance(near.position, b.position) < 1e-9);
    images.push_back(*m);
  }
  for (std::size_t i = 1; i < images.size(); ++i) {
    CAPTURE(i);
    CHECK(images[i].position.x > images[i - 1].position.x + 0.25);
  }
  return images;
}

TEST_CASE("a nearly flat corner's boundary spreads along the axis, one-to-one both ways",
          "[medial][mapping]") {
  // A 400 x 300 box whose bottom side dips by a 20-degree convex turn at x = 200: the corner is
  // pruned (kFlatCornerTurn), and its stretch of boundary, which every normal misses, would
  // all map to one MA point of radius ~170 (a fan of long rails, each wedge a sliver).
  const double dip = 200.0 * std::tan(10.0 * 3.14159265358979323846 / 180.0);
  const Polygon2 p = polygon({{{0, 0}, {200, -dip}, {400, 0}, {400, 300}, {0, 300}}});
  const MedialAxis ma = compute_medial_axis(p);
  const std::vector<MaPoint> images = images_across_dip(p, ma, 160.0, 2.0, 41, 3, 3);
  CHECK(std::count_if(images.begin(), images.end(), [](const MaPoint& m) { return m.off_normal; }) >
        10);
}

TEST_CASE("a flat corner's zone goes on along the axis where the other side's corners cut it short",
          "[medial][mapping]") {
  // The box of the test above, its top bent up by 0.6 degrees at x = 190 and x = 210: those
  // corners are pruned too, and the axis above the dip gets vertices at about x = 190 and 210
  // (the top's segment changes there). The dip's stretch (about 60 long) would have only the
  // root's two 10-long edges, too short to take it (kMinSpreadImage); the zone goes on through
  // those vertices, where only the top's site changes, towards the branch points.
  const double dip = 200.0 * std::tan(10.0 * 3.14159265358979323846 / 180.0);
  const Polygon2 p =
      polygon({{{0, 0}, {200, -dip}, {400, 0}, {400, 300}, {210, 302}, {190, 302}, {0, 300}}});
  const MedialAxis ma = compute_medial_axis(p);
  const std::vector<MaPoint> images = images_across_dip(p, ma, 170.0, 1.5, 41, 3, 5);
  // More of the axis than the root's two edges (x 190 to 210) could give: spread, not a fan.
  CHECK(images.back().position.x - images.front().position.x > 20.0);
}
