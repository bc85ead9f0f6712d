// Benchmark: medial axis of one patch of growing size, with both Voronoi backends, on two
// shapes: a wiggly outline with four circular holes, and a polygon made only of polygonised
// circles (cocircular corners everywhere: the hard case for CGAL's exact arithmetic).
// Prints the time of compute_medial_axis (which includes the self-check), the time of the
// self-check alone, and segments per second. Not a test: run it by hand,
//   build/bench/bench_medial [max_segments] [cgal|boost]
// and record the figures in docs/medial-backends.md. NOHOLES=1 drops the wiggly shape's holes.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "laytracks/medial/medial_axis.hpp"

using namespace laytracks;

namespace {

/// n vertices on a circle of radius r about c, from angle 0; counter-clockwise unless
/// `clockwise`.
std::vector<Vec2> circle(std::size_t n, double r, Vec2 c, bool clockwise) {
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i < n; ++i) {
    double a = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    if (clockwise) a = -a;
    pts.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return pts;
}

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
    p.loops.push_back(circle(m, 10.0, c, true));
  }
  for (const auto& l : p.loops) p.smooth.emplace_back(l.size(), false);
  return p;
}

/// Only polygonised circles, about n segments in all: a disk of radius 100 with n/2 vertices,
/// with four holes of radius 20 (n/16 vertices each) and one of radius 30 at the centre (n/4).
Polygon2 circles(std::size_t n) {
  Polygon2 p;
  p.loops.push_back(circle(n / 2, 100.0, {}, false));
  for (int h = 0; h < 4; ++h) {
    const Vec2 c{62.0 * std::cos(h * M_PI / 2 + M_PI / 4),
                 62.0 * std::sin(h * M_PI / 2 + M_PI / 4)};
    p.loops.push_back(circle(n / 16, 20.0, c, true));
  }
  p.loops.push_back(circle(n / 4, 30.0, {}, true));
  for (const auto& l : p.loops) p.smooth.emplace_back(l.size(), false);
  return p;
}

/// Seconds elapsed since t0.
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// The backend's name in the table.
const char* name_of(VoronoiBackend b) { return b == VoronoiBackend::Cgal ? "cgal" : "boost"; }

/// The axis with a backend, timed. For Boost, first without the fallback to CGAL; if Boost
/// gives up, `note` says why and the time is that of the default (Boost, then CGAL).
MedialAxis timed_axis(const Polygon2& poly,
                      VoronoiBackend backend,
                      double* seconds,
                      std::string* note) {
  MedialOptions options;
  options.backend = backend == VoronoiBackend::Boost ? VoronoiBackend::BoostOnly : backend;
  auto t0 = std::chrono::steady_clock::now();
  try {
    MedialAxis ma = compute_medial_axis(poly, options);
    *seconds = seconds_since(t0);
    return ma;
  } catch (const std::exception& e) {
    if (backend != VoronoiBackend::Boost) throw;
    *note = std::string("  fell back to CGAL: ") + e.what();
  }
  options.backend = VoronoiBackend::Boost;
  t0 = std::chrono::steady_clock::now();
  MedialAxis ma = compute_medial_axis(poly, options);
  *seconds = seconds_since(t0);
  return ma;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t max_n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 100000;
  std::vector<VoronoiBackend> backends = {VoronoiBackend::Cgal, VoronoiBackend::Boost};
  if (argc > 2) {
    backends = {std::strcmp(argv[2], "cgal") == 0 ? VoronoiBackend::Cgal : VoronoiBackend::Boost};
  }
  struct Shape {
    const char* name;
    Polygon2 (*make)(std::size_t);
  };
  const Shape shapes[] = {{"wiggly+holes", wiggly}, {"circles", circles}};
  std::printf("%-13s %-7s %9s %9s %9s %9s %11s %14s %12s\n", "shape", "voronoi", "segments",
              "MA verts", "MA edges", "branches", "medial [s]", "self-check [s]", "segments/s");
  for (const Shape& shape : shapes) {
    for (std::size_t n = 1000; n <= max_n; n *= 10) {
      const Polygon2 poly = shape.make(n);
      for (VoronoiBackend backend : backends) {
        double t = 0.0;
        std::string note;
        const MedialAxis ma = timed_axis(poly, backend, &t, &note);
        // compute_medial_axis ends with the self-check; time it alone to show its share.
        const auto t1 = std::chrono::steady_clock::now();
        const bool valid = ma.validate().empty();
        const double tv = seconds_since(t1);
        std::printf("%-13s %-7s %9zu %9zu %9zu %9zu %11.3f %14.3f %12.0f%s%s\n", shape.name,
                    name_of(backend), poly.segment_count(), ma.vertices().size(), ma.edges().size(),
                    ma.branch_points().size(), t, tv, static_cast<double>(poly.segment_count()) / t,
                    valid ? "" : "  INVALID", note.c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
