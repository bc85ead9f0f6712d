// Times build_part() on one patch with about 100,000 edges: a wiggly star outline (radial, so
// simple) with a few polygonal holes, tilted out of the coordinate planes and moved away from
// the origin. Prints the edge count and the best and median time of several runs.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "laytracks/brep/build.hpp"

namespace {

/// Maps plane coordinates onto a tilted plane far from the origin.
laytracks::Vec3 place(double x, double y) {
  const laytracks::Vec3 o{1000.0, -2000.0, 500.0};
  const laytracks::Vec3 u = laytracks::normalized({1.0, 0.3, 0.2});
  const laytracks::Vec3 v = laytracks::normalized(laytracks::cross({0.1, -0.2, 1.0}, u));
  return o + x * u + y * v;
}

/// Appends a closed loop of n points around (cx, cy) at radius r(theta); returns its indices.
template <class Radius>
std::vector<std::int64_t> add_loop(
    laytracks::RawPart& raw, std::size_t n, double cx, double cy, Radius radius, bool clockwise) {
  std::vector<std::int64_t> loop;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2.0 * laytracks::kPi * static_cast<double>(i) / static_cast<double>(n);
    const double a = clockwise ? -t : t;
    const double r = radius(a);
    loop.push_back(static_cast<std::int64_t>(raw.vertices.size()));
    raw.vertices.push_back(place(cx + r * std::cos(a), cy + r * std::sin(a)));
  }
  return loop;
}

/// The benchmark part: `outer` outline edges plus `holes` holes of `hole_edges` edges each.
laytracks::RawPart make_part(std::size_t outer, std::size_t holes, std::size_t hole_edges) {
  laytracks::RawPart raw;
  laytracks::RawPatch patch;
  patch.name = "star";
  patch.loops.push_back(add_loop(
      raw, outer, 0.0, 0.0,
      [](double a) {
        return 100.0 * (1.0 + 0.25 * std::sin(40.0 * a) + 0.02 * std::sin(2000.0 * a));
      },
      false));
  for (std::size_t h = 0; h < holes; ++h) {
    const double a = 2.0 * laytracks::kPi * static_cast<double>(h) / static_cast<double>(holes);
    patch.loops.push_back(add_loop(
        raw, hole_edges, 35.0 * std::cos(a), 35.0 * std::sin(a),
        [](double t) { return 10.0 + 2.0 * std::sin(7.0 * t); }, true));
  }
  raw.patches.push_back(patch);
  return raw;
}

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  const laytracks::RawPart raw = make_part(98000, 4, 500);
  std::vector<double> seconds;
  std::size_t edges = 0;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const laytracks::Part part = laytracks::build_part(raw);
    const auto t1 = std::chrono::steady_clock::now();
    edges = part.edges.size();
    seconds.push_back(std::chrono::duration<double>(t1 - t0).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("build_part: 1 patch, %zu edges, 5 loops: best %.3f s, median %.3f s (%d runs)\n",
              edges, seconds.front(), seconds[seconds.size() / 2], runs);
  return 0;
}
