// The face templates on their own: every simple polygon with an even node count gets valid
// quads (the cut and pairs templates take what the structured ones cannot), and the faces
// that once made parts fail.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>

#include "fill.hpp"

using namespace laytracks;
using namespace laytracks::mesher_detail;

namespace {

FaceInput one_sided(std::vector<Vec2> cycle) {
  FaceInput f;
  f.cycle = std::move(cycle);
  FaceSide all;
  all.edges = static_cast<std::uint32_t>(f.cycle.size());
  f.sides.push_back(all);
  return f;
}

/// Every quad counter-clockwise with all corners valid, every cycle edge used once, the area
/// of the quads that of the polygon.
void check_fill(const FaceInput& f, const FaceMesh& m) {
  const auto n = static_cast<std::uint32_t>(f.cycle.size());
  auto pos = [&](std::uint32_t i) { return i < n ? f.cycle[i] : m.interior[i - n]; };
  double area = 0.0, poly = 0.0;
  for (std::uint32_t k = 0; k < n; ++k) poly += cross(f.cycle[k], f.cycle[(k + 1) % n]);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const auto& q : m.quads) {
    CHECK(min_scaled_jacobian(pos(q[0]), pos(q[1]), pos(q[2]), pos(q[3])) > kMinValidJacobian);
    for (std::size_t k = 0; k < 4; ++k) {
      area += cross(pos(q[k]), pos(q[(k + 1) % 4]));
      ++edges[{q[k], q[(k + 1) % 4]}];
    }
  }
  CHECK(area == Approx(poly).epsilon(1e-9));
  for (std::uint32_t k = 0; k < n; ++k) CHECK(edges[{k, (k + 1) % n}] == 1);
  for (const auto& [e, count] : edges) {
    CHECK(count == 1);  // each directed edge once: conformal inside, no overlaps
    const bool boundary = e.first < n && e.second < n && (e.first + 1) % n == e.second;
    if (!boundary) CHECK(edges.count({e.second, e.first}) == 1);
  }
}

}  // namespace

TEST_CASE("random star-shaped faces get valid quads", "[fill]") {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> radius(0.5, 1.5), jitter(-0.3, 0.3);
  int done = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const int n = 6 + 2 * static_cast<int>(rng() % 18);  // 6 .. 40 nodes
    std::vector<Vec2> cycle;
    for (int k = 0; k < n; ++k) {
      const double a = 2.0 * kPi * (k + 0.4 * jitter(rng)) / n;
      const double r = radius(rng);
      cycle.push_back({r * std::cos(a), r * std::sin(a)});
    }
    const FaceInput f = one_sided(cycle);
    INFO("trial " << trial << ", " << n << " nodes");
    const FaceMesh m = fill_face(f, "a random face");
    check_fill(f, m);
    ++done;
  }
  CHECK(done == 500);
}

TEST_CASE("faces that once had no template", "[fill]") {
  SECTION("a chevron with a 20-degree spike and a 280-degree corner (cgal_sample_0)") {
    const FaceInput f = one_sided({{0.0905253, 0.0298924}, {0.0887926, 0.0300113},
                                   {0.0870599, 0.0301303}, {0.0865342, 0.0224744},
                                   {0.0790898, 0.0243375}, {0.0843699, 0.0207418},
                                   {0.08965, 0.0171462}, {0.0900876, 0.0235193}});
    check_fill(f, fill_face(f, "face 21"));
  }
}
