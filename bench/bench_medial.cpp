// Benchmark: medial axis of one patch of growing size (a wiggly outline with holes).
// Prints the time per stage and segments per second. Not a test: run it by hand,
//   build/bench/bench_medial [max_segments]
// and record the figures in bench/README.md.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "laytracks/medial/medial_axis.hpp"

using namespace laytracks;

namespace {

/// A closed outline r(a) = 100 (1 + 0.15 sin(7a) + 0.05 sin(53a)) with n vertices, plus four
/// circular holes of n/20 vertices each (clockwise).
Polygon2 wiggly(std::size_t n) {
  Polygon2 p;
  std::vector<Vec2> outer;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    const double r = 100.0 * (1.0 + 0.15 * std::sin(7 * a) + 0.05 * std::sin(53 * a));
    outer.push_back({r * std::cos(a), r * std::sin(a)});
  }
  p.loops.push_back(outer);
  const std::size_t m = std::max<std::size_t>(8, n / 20);
  const int holes = std::getenv("NOHOLES") ? 0 : 4;
  for (int h = 0; h < holes; ++h) {
    const Vec2 c{35.0 * std::cos(h * M_PI / 2), 35.0 * std::sin(h * M_PI / 2)};
    std::vector<Vec2> hole;
    for (std::size_t i = 0; i < m; ++i) {
      const double a = -2.0 * M_PI * static_cast<double>(i) / static_cast<double>(m);
      hole.push_back({c.x + 10.0 * std::cos(a), c.y + 10.0 * std::sin(a)});
    }
    p.loops.push_back(hole);
  }
  for (const auto& l : p.loops) p.smooth.emplace_back(l.size(), false);
  return p;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t max_n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 100000;
  std::printf("%10s %10s %10s %10s %12s %14s\n", "segments", "MA verts", "MA edges", "branches",
              "medial [s]", "segments/s");
  for (std::size_t n = 1000; n <= max_n; n *= 10) {
    const Polygon2 poly = wiggly(n);
    const auto t0 = std::chrono::steady_clock::now();
    const MedialAxis ma = compute_medial_axis(poly);
    const double t = seconds_since(t0);
    std::printf("%10zu %10zu %10zu %10zu %12.3f %14.0f\n", poly.segment_count(),
                ma.vertices().size(), ma.edges().size(), ma.branch_points().size(), t,
                static_cast<double>(poly.segment_count()) / t);
  }
  return 0;
}
