// The boundary of one patch in its frame, bucketed in horizontal slabs: point-in-polygon tests
// and "which boundary segments are near this point" in time proportional to a slab's content.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "laytracks/brep/part.hpp"

namespace laytracks::detail {

/// Segment i of loop l of a patch: from loops[l].vertices[i] to the next vertex, on B-Rep edge
/// loops[l].edges[i]; a and b are its ends in the patch frame (Patch::polygon).
struct BoundarySegment {
  Vec2 a;
  Vec2 b;
  VertexId va;
  VertexId vb;
  EdgeId edge;
};

class PatchIndex {
 public:
  explicit PatchIndex(const Patch& patch) {
    for (std::size_t l = 0; l < patch.loops.size(); ++l) {
      const Loop& loop = patch.loops[l];
      const std::vector<Vec2>& pts = patch.polygon.loops[l];
      const std::size_t m = loop.vertices.size();
      for (std::size_t i = 0; i < m; ++i) {
        const std::size_t j = (i + 1) % m;
        segments_.push_back({pts[i], pts[j], loop.vertices[i], loop.vertices[j], loop.edges[i]});
      }
    }
    if (segments_.empty()) return;
    y0_ = segments_[0].a.y;
    double y1 = y0_;
    double total_dy = 0.0;
    for (const BoundarySegment& s : segments_) {
      y0_ = std::fmin(y0_, std::fmin(s.a.y, s.b.y));
      y1 = std::fmax(y1, std::fmax(s.a.y, s.b.y));
      total_dy += std::fabs(s.b.y - s.a.y);
    }
    const double height = y1 - y0_;
    // As many slabs as segments, fewer when long segments would fill too many slabs: each
    // segment goes into every slab it spans, about n + total_dy / slab height entries.
    const double n = static_cast<double>(segments_.size());
    double slabs = n;
    if (total_dy > 0.0 && height > 0.0) slabs = std::min(slabs, 16.0 * n * height / total_dy);
    slabs = std::clamp(slabs, 1.0, 1e6);
    slab_count_ = static_cast<std::size_t>(slabs);
    inv_height_ = height > 0.0 ? static_cast<double>(slab_count_) / height : 0.0;
    std::vector<std::uint32_t> count(slab_count_ + 1, 0);
    for (const BoundarySegment& s : segments_) {
      const auto [lo, hi] = range(s);
      for (std::size_t k = lo; k <= hi; ++k) ++count[k + 1];
    }
    for (std::size_t k = 0; k < slab_count_; ++k) count[k + 1] += count[k];
    start_ = count;
    items_.resize(count.back());
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const auto [lo, hi] = range(segments_[i]);
      for (std::size_t k = lo; k <= hi; ++k) items_[count[k]++] = static_cast<std::uint32_t>(i);
    }
  }

  const std::vector<BoundarySegment>& segments() const { return segments_; }

  /// Even-odd crossing test against every loop (holes included). A point exactly on the
  /// boundary may be reported inside or outside.
  bool contains(Vec2 p) const {
    if (segments_.empty()) return false;
    // Below or above the polygon (or NaN), the end slab holds no segment crossing y = p.y.
    const std::size_t k = slab(p.y);
    bool inside = false;
    for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i) {
      const BoundarySegment& s = segments_[items_[i]];
      if ((s.a.y > p.y) != (s.b.y > p.y)) {
        const double x = s.a.x + (p.y - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
        if (x > p.x) inside = !inside;
      }
    }
    return inside;
  }

  /// Calls f(segment index) for every segment whose bounding box meets the square of half-side
  /// r about p (a superset of the segments within r of p).
  template <class F>
  void for_each_near(Vec2 p, double r, F&& f) const {
    if (segments_.empty()) return;
    const std::size_t lo = slab(p.y - r);
    const std::size_t hi = slab(p.y + r);
    for (std::size_t k = lo; k <= hi; ++k) {
      for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i) {
        const std::uint32_t si = items_[i];
        const BoundarySegment& s = segments_[si];
        // A segment spanning several slabs is met in each: report it in the first one only.
        if (k != lo && slab(std::fmin(s.a.y, s.b.y)) < k) continue;
        if (std::fmin(s.a.x, s.b.x) > p.x + r || std::fmax(s.a.x, s.b.x) < p.x - r) continue;
        if (std::fmin(s.a.y, s.b.y) > p.y + r || std::fmax(s.a.y, s.b.y) < p.y - r) continue;
        f(si);
      }
    }
  }

 private:
  std::size_t slab(double y) const {
    const double k = std::floor((y - y0_) * inv_height_);
    if (!(k > 0.0)) return 0;
    return std::min(static_cast<std::size_t>(std::fmin(k, 1e9)), slab_count_ - 1);
  }
  std::pair<std::size_t, std::size_t> range(const BoundarySegment& s) const {
    return {slab(std::fmin(s.a.y, s.b.y)), slab(std::fmax(s.a.y, s.b.y))};
  }

  std::vector<BoundarySegment> segments_;
  double y0_ = 0.0;
  double inv_height_ = 0.0;
  std::size_t slab_count_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

}  // namespace laytracks::detail
