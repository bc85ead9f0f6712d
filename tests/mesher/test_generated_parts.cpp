// Parts nobody drew: plates with random outlines (convex-ish polygons, L shapes, stars), random
// round holes (arcs, radius 0.1 to 2 element sizes and more), and folded brackets with a
// hole, from a fixed seed. Every one must mesh to a valid all-quad mesh, at
// three sizes and in a turned and scaled pose. This is the check the sample parts cannot give:
// that the mesher has no refusal waiting for shapes it was not tuned on.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "laytracks/brep/build.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "test_support.hpp"

using namespace laytracks;
using namespace laytracks::test;

namespace {

using Pt = std::pair<double, double>;

bool inside(const std::vector<Pt>& poly, double x, double y) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto [xi, yi] = poly[i];
    const auto [xj, yj] = poly[j];
    if ((yi > y) != (yj > y) && x < xi + (y - yi) * (xj - xi) / (yj - yi)) in = !in;
  }
  return in;
}

double edge_distance(const std::vector<Pt>& poly, double x, double y) {
  double best = 1e300;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto [x1, y1] = poly[i];
    const auto [x2, y2] = poly[(i + 1) % poly.size()];
    const double dx = x2 - x1, dy = y2 - y1;
    const double t = std::clamp(((x - x1) * dx + (y - y1) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
    best = std::min(best, std::hypot(x - x1 - t * dx, y - y1 - t * dy));
  }
  return best;
}

/// A hole of three arcs round (cx, cy) in the plane z = 0, appended to `raw` and `loops`.
void add_round_hole(RawPart& raw, std::vector<std::vector<std::int64_t>>& loops, double cx,
                    double cy, double r) {
  const auto b = static_cast<std::int64_t>(raw.vertices.size());
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * kPi * k / 3.0;
    raw.vertices.push_back({cx + r * std::cos(a), cy + r * std::sin(a), 0.0});
  }
  loops.push_back({b, b + 2, b + 1});
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * kPi * (k + 0.5) / 3.0;
    raw.arcs.push_back({b + k, b + (k + 1) % 3, {cx + r * std::cos(a), cy + r * std::sin(a), 0.0}});
  }
}

RawPart random_plate(std::mt19937& rng, int kind) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Pt> outer;
  if (kind == 0) {  // a polygon round the origin
    const int n = 5 + static_cast<int>(rng() % 5);
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * kPi * k / n + 0.4 * (u(rng) - 0.5);
      const double r = 50.0 * (0.6 + 0.4 * u(rng));
      outer.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  } else if (kind == 1) {  // an L
    const double w = 60.0 + 60.0 * u(rng), h = 40.0 + 40.0 * u(rng), c = 0.3 + 0.4 * u(rng);
    outer = {{0, 0}, {w, 0}, {w, h * c}, {w * c, h * c}, {w * c, h}, {0, h}};
    for (auto& [x, y] : outer) x -= w / 2, y -= h / 2;
  } else {  // a star
    const int n = 4 + static_cast<int>(rng() % 5);
    for (int k = 0; k < 2 * n; ++k) {
      const double a = kPi * k / n;
      const double r = k % 2 == 0 ? 50.0 : 15.0 + 15.0 * u(rng);
      outer.emplace_back(r * std::cos(a), r * std::sin(a));
    }
  }
  RawPart raw;
  std::vector<std::vector<std::int64_t>> loops(1);
  for (const auto& [x, y] : outer) {
    loops[0].push_back(static_cast<std::int64_t>(raw.vertices.size()));
    raw.vertices.push_back({x, y, 0.0});
  }
  // Holes from tiny (a fraction of an element) to large, away from the edges and each other.
  std::vector<std::array<double, 3>> holes;
  const int wanted = static_cast<int>(rng() % 4);
  for (int h = 0; h < wanted; ++h) {
    for (int attempt = 0; attempt < 100; ++attempt) {
      const double r = std::array<double, 5>{0.3, 0.8, 1.5, 3.0, 6.0}[rng() % 5];
      const double cx = 40.0 * (u(rng) - 0.5), cy = 20.0 * (u(rng) - 0.5);
      bool ok = inside(outer, cx, cy) && edge_distance(outer, cx, cy) > r + 2.0;
      for (const auto& o : holes) ok = ok && std::hypot(cx - o[0], cy - o[1]) > r + o[2] + 2.0;
      if (ok) {
        holes.push_back({cx, cy, r});
        break;
      }
    }
  }
  for (const auto& [cx, cy, r] : holes) add_round_hole(raw, loops, cx, cy, r);
  raw.patches.push_back({std::string("plate"), loops});
  return raw;
}

/// Two legs folded along x at an angle, a round hole in the first.
RawPart random_bracket(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double w = 20.0 + 40.0 * u(rng), l1 = 20.0 + 40.0 * u(rng), l2 = 20.0 + 40.0 * u(rng);
  const double fold = (60.0 + 90.0 * u(rng)) * kPi / 180.0;
  RawPart raw;
  raw.vertices = {{0, 0, 0}, {w, 0, 0}, {w, l1, 0}, {0, l1, 0}};
  const double dy = std::cos(kPi - fold) * l2, dz = std::sin(kPi - fold) * l2;
  raw.vertices.push_back({w, l1 + dy, dz});
  raw.vertices.push_back({0, l1 + dy, dz});
  std::vector<std::vector<std::int64_t>> leg1{{0, 1, 2, 3}};
  add_round_hole(raw, leg1, w / 2, l1 / 2, std::min(w, l1) * (0.1 + 0.15 * u(rng)));
  raw.patches.push_back({std::string("leg1"), leg1});
  raw.patches.push_back({std::string("leg2"), {{3, 2, 4, 5}}});
  return raw;
}

/// Part i of the sequence the seed generates (kinds 0, 1, 2 plates, 3 a bracket, by i % 4).
RawPart generated_part(unsigned seed, int index) {
  std::mt19937 rng(seed);
  RawPart raw;
  for (int i = 0; i <= index; ++i) raw = i % 4 == 3 ? random_bracket(rng) : random_plate(rng, i % 4);
  return raw;
}

}  // namespace

TEST_CASE("generated parts mesh valid at three sizes and in another pose", "[mesh][generated]") {
  std::mt19937 rng(2026);
  int meshed = 0;
  for (int i = 0; i < 24; ++i) {
    const RawPart raw = i % 4 == 3 ? random_bracket(rng) : random_plate(rng, i % 4);
    const Part part = build_part(raw);
    const double h = default_element_size(part);
    for (const double factor : {2.0, 1.0, 0.5}) {
      INFO("part " << i << ", size " << factor << " x default");
      MeshPartOptions options;
      options.size = h * factor;
      MeshPartResult r;
      REQUIRE_NOTHROW(r = mesh_part(part, options));
      CHECK(r.check.valid());
      CHECK(r.quality.triangles == 0);
      ++meshed;
    }
    // Turned, moved and scaled by 1e-3: valid too, with as many quads.
    const Transform pose = compose(scaling(1e-3), compose(translation({5, -3, 2}), rotation({1, 1, 2}, 1.1)));
    MeshPartOptions base, moved;
    base.size = h;
    moved.size = h * 1e-3;
    const MeshPartResult a = mesh_part(part, base);
    const MeshPartResult b = mesh_part(build_part(transformed(raw, pose)), moved);
    CHECK(b.check.valid());
    CHECK(b.mesh.elements.size() == a.mesh.elements.size());
  }
  CHECK(meshed == 72);
}

TEST_CASE("generated parts mesh valid in adaptive mode at two angles and in another pose",
          "[mesh][generated][adaptive]") {
  std::mt19937 rng(2027);
  int meshed = 0;
  for (int i = 0; i < 24; ++i) {
    const RawPart raw = i % 4 == 3 ? random_bracket(rng) : random_plate(rng, i % 4);
    const Part part = build_part(raw);
    for (const double dtheta : {20.0, 10.0}) {
      INFO("part " << i << ", dtheta " << dtheta);
      MeshPartOptions options;
      options.adaptive = true;
      options.dtheta_deg = dtheta;
      MeshPartResult r;
      REQUIRE_NOTHROW(r = mesh_part(part, options));
      CHECK(r.check.valid());
      CHECK(r.quality.triangles == 0);
      ++meshed;
    }
    const Transform pose =
        compose(scaling(1e3), compose(translation({5, -3, 2}), rotation({2, -1, 1}, 2.3)));
    MeshPartOptions options;
    options.adaptive = true;
    const MeshPartResult a = mesh_part(part, options);
    const MeshPartResult b = mesh_part(build_part(transformed(raw, pose)), options);
    INFO("part " << i << " turned, moved and scaled by 1e3");
    CHECK(b.check.valid());
    CHECK(b.mesh.elements.size() == a.mesh.elements.size());
  }
  CHECK(meshed == 48);
}

namespace {

/// Meshes the part as given and in `pose` (scaled by `scale`; uniform mode at the default size,
/// scaled too, or adaptive mode): both valid, and as many quads.
void check_same_in_pose(const RawPart& raw, const Transform& pose, double scale, bool adaptive) {
  const Part part = build_part(raw);
  MeshPartOptions base, moved;
  if (adaptive) {
    base.adaptive = moved.adaptive = true;
  } else {
    base.size = default_element_size(part);
    moved.size = *base.size * scale;
  }
  const MeshPartResult a = mesh_part(part, base);
  const MeshPartResult b = mesh_part(build_part(transformed(raw, pose)), moved);
  CHECK(a.check.valid());
  CHECK(b.check.valid());
  CHECK(b.mesh.elements.size() == a.mesh.elements.size());
}

}  // namespace

// Parts of longer runs of other seeds whose meshes once differed between poses: each a bracket
// whose second leg is a near-square rectangle; a face there had rails along one straight line
// through two MA points, exactly collinear in one pose and collinear but for rounding in the
// other, and the pairs template's triangulation kept a diagonal along that line in one pose
// only (649 quads against 586; adaptive 1066 against 1044).
TEST_CASE("generated parts of other seeds mesh to as many quads in another pose",
          "[mesh][generated]") {
  const Transform small =
      compose(scaling(1e-3), compose(translation({5, -3, 2}), rotation({1, 1, 2}, 1.1)));
  SECTION("seed 4242, part 103, uniform, turned and scaled by 1e-3") {
    check_same_in_pose(generated_part(4242, 103), small, 1e-3, false);
  }
  // Plates of seed 1 with a face of 50 nodes meshed by split or pairs: the pairs template's
  // midpoints on its diagonals make flat corners whose scaled Jacobians are +-1e-17 by pose,
  // and the smoothing's `after >= before` took a move in one pose only; the relaxed worst
  // corner then fell either side of a kChoiceStep (part 4: 0.154 against 0.142, 963 quads
  // against 954; part 120: 0.143 against 0.164, 1095 against 1093).
  for (const int index : {4, 120}) {
    SECTION("seed 1, part " + std::to_string(index) + ", uniform, turned and scaled by 1e-3") {
      check_same_in_pose(generated_part(1, index), small, 1e-3, false);
    }
  }
  SECTION("seed 777, part 119, adaptive, turned and scaled by 1e3") {
    check_same_in_pose(
        generated_part(777, 119),
        compose(scaling(1e3), compose(translation({5, -3, 2}), rotation({2, -1, 1}, 2.3))), 1e3,
        true);
  }
}

