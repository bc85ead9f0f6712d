// measure_quad on quads whose measures are known by hand (../shared/spec/quality.md), and
// its invariance under rotation, translation and scaling.
#include <catch2/catch.hpp>
#include <cmath>

#include "laytracks/mesher/quality.hpp"
#include "test_support.hpp"

using namespace laytracks;
using namespace laytracks::test;

namespace {

const Vec3 kZ{0.0, 0.0, 1.0};

std::array<Vec3, 4> quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return {Vec3{a.x, a.y, 0.0}, Vec3{b.x, b.y, 0.0}, Vec3{c.x, c.y, 0.0}, Vec3{d.x, d.y, 0.0}};
}

void check_same(const QuadQuality& a, const QuadQuality& b) {
  const double e = 1e-9;
  CHECK(a.skew_deg == Approx(b.skew_deg).margin(e));
  CHECK(a.aspect_ratio == Approx(b.aspect_ratio).margin(e));
  CHECK(a.taper == Approx(b.taper).margin(e));
  CHECK(a.warp_deg == Approx(b.warp_deg).margin(e));
  CHECK(a.min_angle_deg == Approx(b.min_angle_deg).margin(e));
  CHECK(a.max_angle_deg == Approx(b.max_angle_deg).margin(e));
  CHECK(a.scaled_jacobian == Approx(b.scaled_jacobian).margin(e));
  CHECK(a.edge_ratio == Approx(b.edge_ratio).margin(e));
  CHECK(a.inverted == b.inverted);
}

}  // namespace

TEST_CASE("the unit square is ideal", "[quality]") {
  const QuadQuality q = measure_quad(quad({0, 0}, {1, 0}, {1, 1}, {0, 1}), kZ);
  CHECK(q.skew_deg == Approx(0.0).margin(1e-12));
  CHECK(q.aspect_ratio == 1.0);
  CHECK(q.taper == 1.0);
  CHECK(q.warp_deg == 0.0);
  CHECK(q.min_angle_deg == Approx(90.0));
  CHECK(q.max_angle_deg == Approx(90.0));
  CHECK(q.scaled_jacobian == 1.0);
  CHECK(q.edge_ratio == 1.0);
  CHECK_FALSE(q.inverted);
}

TEST_CASE("a 2x1 rectangle has aspect and edge ratio 2", "[quality]") {
  const QuadQuality q = measure_quad(quad({0, 0}, {2, 0}, {2, 1}, {0, 1}), kZ);
  CHECK(q.aspect_ratio == Approx(2.0));
  CHECK(q.edge_ratio == Approx(2.0));
  CHECK(q.skew_deg == Approx(0.0).margin(1e-12));
  CHECK(q.taper == Approx(1.0));
  CHECK(q.scaled_jacobian == Approx(1.0));
  CHECK_FALSE(q.inverted);
}

TEST_CASE("a 60/120 degree rhombus has skew 30 and scaled Jacobian sin 60", "[quality]") {
  const double h = std::sqrt(3.0) / 2.0;
  const QuadQuality q = measure_quad(quad({0, 0}, {1, 0}, {1.5, h}, {0.5, h}), kZ);
  CHECK(q.skew_deg == Approx(30.0));
  CHECK(q.scaled_jacobian == Approx(std::sin(kPi / 3.0)));
  CHECK(q.min_angle_deg == Approx(60.0));
  CHECK(q.max_angle_deg == Approx(120.0));
  CHECK(q.aspect_ratio == Approx(1.0));
  CHECK(q.edge_ratio == Approx(1.0));
  CHECK(q.taper == Approx(1.0));
  CHECK_FALSE(q.inverted);
}

TEST_CASE("a trapezoid's taper is min(Ai) / mean(Ai)", "[quality]") {
  // Corner triangles of (0,0) (4,0) (3,2) (1,2): areas 4, 4, 2, 2, mean 3, so taper 2/3.
  const QuadQuality q = measure_quad(quad({0, 0}, {4, 0}, {3, 2}, {1, 2}), kZ);
  CHECK(q.taper == Approx(2.0 / 3.0));
  // Midlines: d1 = M23 - M41 = (3.5, 1) - (0.5, 1), d2 = M34 - M12 = (2, 2) - (2, 0).
  CHECK(q.aspect_ratio == Approx(1.5));
  CHECK(q.skew_deg == Approx(0.0).margin(1e-12));
  CHECK(q.edge_ratio == Approx(2.0));  // edges 4, sqrt 5, 2, sqrt 5
  CHECK(q.min_angle_deg == Approx(std::atan2(2.0, 1.0) * 180.0 / kPi));
  CHECK_FALSE(q.inverted);
}

TEST_CASE("lifting one corner warps the quad", "[quality]") {
  const double lift = 0.1;
  std::array<Vec3, 4> c = quad({0, 0}, {1, 0}, {1, 1}, {0, 1});
  c[2].z = lift;
  const QuadQuality q = measure_quad(c, kZ);
  // Across P1P3 the normals are (0, -h, 1) and (-h, 0, 1); across P2P4, (-h, -h, 1) and z.
  const double a13 = std::acos(1.0 / (1.0 + lift * lift));
  const double a24 = std::acos(1.0 / std::sqrt(1.0 + 2.0 * lift * lift));
  CHECK(q.warp_deg == Approx(std::max(a13, a24) * 180.0 / kPi));
  CHECK(q.warp_deg > 0.0);
  // Projected on the plane, it is the unit square again.
  CHECK(q.scaled_jacobian == Approx(1.0));
  CHECK_FALSE(q.inverted);
}

TEST_CASE("concave and collapsed quads are inverted", "[quality]") {
  SECTION("an arrow: a reflex corner") {
    const QuadQuality q = measure_quad(quad({0, 0}, {2, 1}, {0, 2}, {0.5, 1}), kZ);
    CHECK(q.inverted);
    CHECK(q.scaled_jacobian < 0.0);
    CHECK(q.max_angle_deg > 180.0);
    CHECK(q.taper < 0.0);
  }
  SECTION("a zero-length edge") {
    const QuadQuality q = measure_quad(quad({0, 0}, {1, 0}, {1, 0}, {0, 1}), kZ);
    CHECK(q.inverted);
    CHECK(q.scaled_jacobian == 0.0);
    CHECK(std::isinf(q.edge_ratio));
    CHECK(q.min_angle_deg == 0.0);
  }
  SECTION("a quad collapsed to a segment") {
    const QuadQuality q = measure_quad(quad({0, 0}, {1, 0}, {2, 0}, {3, 0}), kZ);
    CHECK(q.inverted);
    CHECK(std::isinf(q.aspect_ratio));
    CHECK(q.skew_deg == 90.0);
    CHECK(std::isinf(q.taper));
  }
  SECTION("a corner of exactly 180 degrees") {
    const QuadQuality q = measure_quad(quad({0, 0}, {1, 0}, {2, 0}, {1, 1}), kZ);
    CHECK(q.inverted);
    CHECK(q.max_angle_deg == Approx(180.0));
  }
  SECTION("a square turning clockwise about the normal") {
    const QuadQuality q = measure_quad(quad({0, 0}, {0, 1}, {1, 1}, {1, 0}), kZ);
    CHECK(q.inverted);
    CHECK(q.scaled_jacobian == -1.0);
    CHECK(q.min_angle_deg == Approx(270.0));
  }
  SECTION("a non-finite corner") {
    std::array<Vec3, 4> c = quad({0, 0}, {1, 0}, {1, 1}, {0, 1});
    c[1].x = std::nan("");
    CHECK(measure_quad(c, kZ).inverted);
  }
}

TEST_CASE("an off-plane quad is measured on its projection", "[quality]") {
  // The 2x1 rectangle seen by a patch tilted about x: the projection is a 2 x cos(t) rectangle.
  const double t = 0.3;
  const Vec3 n{0.0, -std::sin(t), std::cos(t)};
  const QuadQuality q = measure_quad(quad({0, 0}, {2, 0}, {2, 1}, {0, 1}), n);
  CHECK(q.aspect_ratio == Approx(2.0 / std::cos(t)));
  CHECK(q.scaled_jacobian == Approx(1.0));
  // The normal's length does not matter.
  check_same(measure_quad(quad({0, 0}, {2, 0}, {2, 1}, {0, 1}), 7.0 * n), q);
}

TEST_CASE("every measure is invariant under rotation, translation and scaling", "[quality]") {
  std::array<Vec3, 4> base = quad({0.1, -0.2}, {3.0, 0.3}, {2.2, 1.9}, {-0.4, 1.1});
  base[2].z = 0.35;  // warped as well
  const std::array<std::array<Vec3, 4>, 3> quads{base, quad({0, 0}, {2, 1}, {0, 2}, {0.5, 1}),
                                                 quad({0, 0}, {4, 0}, {3, 2}, {1, 2})};
  const Transform moves[] = {
      rotation({1.0, 2.0, 3.0}, 0.7),
      compose(translation({5.0, -3.0, 11.0}), rotation({0.0, 1.0, 0.0}, 2.1)),
      scaling(1e-3),
      compose(scaling(250.0), rotation({-1.0, 0.5, 0.2}, 4.0)),
  };
  for (const auto& corners : quads) {
    const QuadQuality ref = measure_quad(corners, kZ);
    for (const Transform& m : moves) {
      std::array<Vec3, 4> moved{};
      for (std::size_t i = 0; i < 4; ++i) moved[i] = m.apply(corners[i]);
      const Vec3 n = normalized(m.apply(kZ) - m.apply(Vec3{}));
      check_same(measure_quad(moved, n), ref);
    }
  }
}

TEST_CASE("a mirrored quad measures the same with the mirrored normal", "[quality]") {
  const std::array<Vec3, 4> c = quad({0.1, -0.2}, {3.0, 0.3}, {2.2, 1.9}, {-0.4, 1.1});
  // A mirror turns a counter-clockwise quad clockwise about z: reverse the order back.
  std::array<Vec3, 4> m{};
  for (std::size_t i = 0; i < 4; ++i) m[i] = {-c[3 - i].x, c[3 - i].y, c[3 - i].z};
  const QuadQuality a = measure_quad(c, kZ);
  const QuadQuality b = measure_quad(m, kZ);
  CHECK(a.aspect_ratio == Approx(b.aspect_ratio));
  CHECK(a.skew_deg == Approx(b.skew_deg));
  CHECK(a.taper == Approx(b.taper));
  CHECK(a.scaled_jacobian == Approx(b.scaled_jacobian));
  CHECK(a.edge_ratio == Approx(b.edge_ratio));
  CHECK(a.min_angle_deg == Approx(b.min_angle_deg));
  CHECK(a.max_angle_deg == Approx(b.max_angle_deg));
}
