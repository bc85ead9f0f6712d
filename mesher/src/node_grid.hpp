// A uniform grid of hashed cells over the nodes of a mesh: finds the nodes near a point or a
// segment, and the pairs of nodes closer than a distance, in expected linear time.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::detail {

class NodeGrid {
 public:
  /// Indexes the finite points of `points` in cubic cells of side about `cell` (enlarged when
  /// the points would need more than 2^21 cells along an axis). `cell` must be > 0.
  NodeGrid(const std::vector<Vec3>& points, double cell) : points_(points) {
    Box3 box;
    for (const Vec3& p : points) {
      if (is_finite(p)) box.add(p);
    }
    if (box.empty()) return;
    const double extent = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
    h_ = std::max(cell, extent / static_cast<double>(kAxisCells - 8));
    if (!(h_ > 0.0)) h_ = 1.0;
    // Shift the origin by odd fractions of a cell so that the nodes of a structured mesh with
    // round coordinates do not sit on cell faces.
    origin_ = {box.lo.x - (2.0 - 0.381966011250105) * h_, box.lo.y - (2.0 - 0.276393202250021) * h_,
               box.lo.z - (2.0 - 0.145898033750315) * h_};
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
    keyed.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (is_finite(points[i]))
        keyed.emplace_back(key(cell_of(points[i])), static_cast<std::uint32_t>(i));
    }
    std::sort(keyed.begin(), keyed.end());
    items_.resize(keyed.size());
    for (std::size_t i = 0; i < keyed.size(); ++i) {
      items_[i] = keyed[i].second;
      if (i == 0 || keyed[i].first != keyed[i - 1].first) {
        cell_keys_.push_back(keyed[i].first);
        cell_start_.push_back(static_cast<std::uint32_t>(i));
      }
    }
    cell_start_.push_back(static_cast<std::uint32_t>(keyed.size()));
    std::size_t capacity = 16;
    bits_ = 4;
    while (capacity < 2 * cell_keys_.size()) {
      capacity *= 2;
      ++bits_;
    }
    slots_.assign(capacity, 0);
    for (std::size_t c = 0; c < cell_keys_.size(); ++c) {
      std::size_t s = slot(cell_keys_[c]);
      while (slots_[s] != 0) s = (s + 1) & (slots_.size() - 1);
      slots_[s] = static_cast<std::uint32_t>(c + 1);
    }
  }

  double cell() const { return h_; }

  /// Calls f(i) for every indexed point i in a cell that meets the box [lo, hi] (a superset of
  /// the points in the box).
  template <class F>
  void for_each_in_box(Vec3 lo, Vec3 hi, F&& f) const {
    if (cell_keys_.empty()) return;
    const Cell a = cell_of(lo);
    const Cell b = cell_of(hi);
    for (std::int64_t x = a.x; x <= b.x; ++x) {
      for (std::int64_t y = a.y; y <= b.y; ++y) {
        for (std::int64_t z = a.z; z <= b.z; ++z) visit_cell({x, y, z}, f);
      }
    }
  }

  /// Calls f(i), once each, for a superset of the indexed points within r <= cell()/2 of the
  /// segment ab.
  template <class F>
  void for_each_near_segment(Vec3 a, Vec3 b, double r, F&& f) const {
    if (cell_keys_.empty()) return;
    const Vec3 lo{std::fmin(a.x, b.x) - r, std::fmin(a.y, b.y) - r, std::fmin(a.z, b.z) - r};
    const Vec3 hi{std::fmax(a.x, b.x) + r, std::fmax(a.y, b.y) + r, std::fmax(a.z, b.z) + r};
    const Cell cl = cell_of(lo);
    const Cell ch = cell_of(hi);
    const std::int64_t box = (ch.x - cl.x + 1) * (ch.y - cl.y + 1) * (ch.z - cl.z + 1);
    if (box <= 27) {
      for_each_in_box(lo, hi, f);
      return;
    }
    // A long segment: walk it in steps of half a cell and visit the 27 cells around each step.
    // A point within r of the segment is within r + h/4 <= h of some step, so in one of them.
    const double length = distance(a, b);
    const auto steps = static_cast<std::int64_t>(std::ceil(length / (0.5 * h_)));
    std::vector<std::uint64_t> cells;
    for (std::int64_t s = 0; s <= steps; ++s) {
      const double t = steps == 0 ? 0.0 : static_cast<double>(s) / static_cast<double>(steps);
      const Cell c = cell_of(a + t * (b - a));
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          for (std::int64_t dz = -1; dz <= 1; ++dz)
            cells.push_back(key({c.x + dx, c.y + dy, c.z + dz}));
        }
      }
    }
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    for (std::uint64_t k : cells) visit_key(k, f);
  }

  /// Every pair (i, j), i < j, of indexed points closer than r (r < cell()), sorted.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> close_pairs(double r) const {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    const double r2 = r * r;
    auto test = [&](std::uint32_t i, std::uint32_t j) {
      const Vec3 d = points_[i] - points_[j];
      if (dot(d, d) < r2) pairs.emplace_back(std::min(i, j), std::max(i, j));
    };
    for (std::size_t c = 0; c < cell_keys_.size(); ++c) {
      const Cell cc = unkey(cell_keys_[c]);
      for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const std::uint32_t i = items_[k];
        for (std::uint32_t m = k + 1; m < cell_start_[c + 1]; ++m) test(i, items_[m]);
        // Neighbour cells, only across the faces the point is within r of, and only those
        // after this cell in key order: a pair in two cells is then seen once.
        const Vec3 p = points_[i];
        const Vec3 low{origin_.x + static_cast<double>(cc.x) * h_,
                       origin_.y + static_cast<double>(cc.y) * h_,
                       origin_.z + static_cast<double>(cc.z) * h_};
        const int lx = p.x - low.x < r ? -1 : 0;
        const int ux = low.x + h_ - p.x < r ? 1 : 0;
        const int ly = p.y - low.y < r ? -1 : 0;
        const int uy = low.y + h_ - p.y < r ? 1 : 0;
        const int lz = p.z - low.z < r ? -1 : 0;
        const int uz = low.z + h_ - p.z < r ? 1 : 0;
        if (lx == 0 && ux == 0 && ly == 0 && uy == 0 && lz == 0 && uz == 0) continue;
        for (int dx = lx; dx <= ux; ++dx) {
          for (int dy = ly; dy <= uy; ++dy) {
            for (int dz = lz; dz <= uz; ++dz) {
              const std::uint64_t nk = key({cc.x + dx, cc.y + dy, cc.z + dz});
              if (nk <= cell_keys_[c]) continue;
              visit_key(nk, [&](std::uint32_t j) { test(i, j); });
            }
          }
        }
      }
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
  }

 private:
  static constexpr std::int64_t kAxisCells = std::int64_t{1} << 21;

  struct Cell {
    std::int64_t x;
    std::int64_t y;
    std::int64_t z;
  };

  Cell cell_of(Vec3 p) const {
    auto axis = [&](double v, double o) {
      const double c = std::floor((v - o) / h_);
      return static_cast<std::int64_t>(std::clamp(c, 0.0, static_cast<double>(kAxisCells - 1)));
    };
    return {axis(p.x, origin_.x), axis(p.y, origin_.y), axis(p.z, origin_.z)};
  }
  static std::uint64_t key(Cell c) {
    auto u = [](std::int64_t v) {
      return static_cast<std::uint64_t>(std::clamp<std::int64_t>(v, 0, kAxisCells - 1));
    };
    return (u(c.x) << 42) | (u(c.y) << 21) | u(c.z);
  }
  static Cell unkey(std::uint64_t k) {
    const std::uint64_t m = static_cast<std::uint64_t>(kAxisCells - 1);
    return {static_cast<std::int64_t>(k >> 42), static_cast<std::int64_t>((k >> 21) & m),
            static_cast<std::int64_t>(k & m)};
  }
  std::size_t slot(std::uint64_t k) const {
    return static_cast<std::size_t>((k * 0x9E3779B97F4A7C15ull) >> (64 - bits_));
  }
  template <class F>
  void visit_cell(Cell c, F&& f) const {
    visit_key(key(c), f);
  }
  template <class F>
  void visit_key(std::uint64_t k, F&& f) const {
    std::size_t s = slot(k);
    while (slots_[s] != 0) {
      const std::size_t c = slots_[s] - 1;
      if (cell_keys_[c] == k) {
        for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) f(items_[i]);
        return;
      }
      s = (s + 1) & (slots_.size() - 1);
    }
  }

  const std::vector<Vec3>& points_;
  double h_ = 1.0;
  Vec3 origin_;
  std::vector<std::uint32_t> items_;       ///< point ids, grouped by cell
  std::vector<std::uint64_t> cell_keys_;   ///< ascending
  std::vector<std::uint32_t> cell_start_;  ///< cell c holds items_[start[c], start[c + 1])
  std::vector<std::uint32_t> slots_;       ///< open addressing: cell index + 1, 0 = empty
  unsigned bits_ = 4;
};

}  // namespace laytracks::detail
