// Helpers for the medial-axis tests: polygons built by hand, and the structure of an axis.
#pragma once

#include <cmath>
#include <cstddef>
#include <numeric>
#include <vector>

#include "laytracks/medial/medial_axis.hpp"

namespace laytracks::test {

inline Polygon2 polygon(std::vector<std::vector<Vec2>> loops) {
  Polygon2 p;
  p.loops = std::move(loops);
  for (const auto& l : p.loops) p.smooth.emplace_back(l.size(), false);
  return p;
}

/// A regular n-gon of radius r about c; counter-clockwise unless `clockwise`.
inline std::vector<Vec2> regular(
    std::size_t n, double r, Vec2 c = {}, bool clockwise = false, double phase = 0.0) {
  std::vector<Vec2> pts;
  for (std::size_t i = 0; i < n; ++i) {
    double a = phase + 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    if (clockwise) a = -a;
    pts.push_back({c.x + r * std::cos(a), c.y + r * std::sin(a)});
  }
  return pts;
}

/// Topological summary: what stays the same when a curve is discretised more finely.
struct Structure {
  std::size_t branch_points = 0;  ///< degree >= 3
  std::size_t leaves = 0;         ///< degree 1
  std::size_t components = 0;
  long cycles = 0;  ///< independent cycles: E - V + components
  bool operator==(const Structure& o) const {
    return branch_points == o.branch_points && leaves == o.leaves && components == o.components &&
           cycles == o.cycles;
  }
};

inline Structure structure(const MedialAxis& ma) {
  Structure s;
  const std::size_t n = ma.vertices().size();
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& e : ma.edges()) parent[find(e.a.index())] = find(e.b.index());
  for (std::size_t v = 0; v < n; ++v) {
    if (find(v) == v) ++s.components;
    if (ma.vertices()[v].degree >= 3) ++s.branch_points;
    if (ma.vertices()[v].degree == 1) ++s.leaves;
  }
  s.cycles =
      static_cast<long>(ma.edges().size()) - static_cast<long>(n) + static_cast<long>(s.components);
  return s;
}

inline std::ostream& operator<<(std::ostream& os, const Structure& s) {
  return os << "{branch points " << s.branch_points << ", leaves " << s.leaves << ", components "
            << s.components << ", cycles " << s.cycles << "}";
}

}  // namespace laytracks::test
