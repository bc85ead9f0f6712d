// closest_self_contact: vertex and segment boxes, grown by the search distance, paired by
// box intersection (predicates.cpp); each pair measured in the patch's frame.
#include "laytracks/brep/self_contact.hpp"

#include <algorithm>
#include <cstdio>
#include <tuple>
#include <vector>

#include "predicates.hpp"

namespace laytracks {
namespace {

/// `vertex 12`, or `an arc point` for a point made by discretising an arc.
std::string vertex_label(const Part& part, VertexId v) {
  const std::int64_t source = part.vertices[v.index()].source_index;
  return source >= 0 ? "vertex " + std::to_string(source) : "an arc point";
}

std::string loop_label(std::uint32_t loop) {
  return loop == 0 ? "the outer loop" : "loop " + std::to_string(loop) + " (a hole)";
}

/// x with `digits` significant digits.
std::string number(double x, int digits = 3) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

}  // namespace

std::optional<SelfContact> closest_self_contact(const Part& part, double within) {
  std::optional<SelfContact> best;
  const auto key = [](const SelfContact& c) {
    return std::make_tuple(c.distance, c.patch.value, c.loop, c.vertex, c.seg_loop, c.seg);
  };
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    const auto& loops = part.patches[p].polygon.loops;
    std::vector<Box2> points, segments;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> point_at, segment_at;  // (loop, place)
    for (std::uint32_t l = 0; l < loops.size(); ++l) {
      const auto n = static_cast<std::uint32_t>(loops[l].size());
      for (std::uint32_t i = 0; i < n; ++i) {
        Box2 b;
        b.add(loops[l][i] - Vec2{within, within});
        b.add(loops[l][i] + Vec2{within, within});
        points.push_back(b);
        point_at.emplace_back(l, i);
        Box2 s;
        s.add(loops[l][i]);
        s.add(loops[l][(i + 1) % n]);
        segments.push_back(s);
        segment_at.emplace_back(l, i);
      }
    }
    for (const auto& [pi, si] : detail::overlapping_boxes(points, segments)) {
      const auto [l, i] = point_at[pi];
      const auto [m, s] = segment_at[si];
      const auto n = static_cast<std::uint32_t>(loops[m].size());
      if (l == m) {
        // Segments s .. s + 1 with s at i - 2, i - 1, i or i + 1: they end at the vertex or at
        // one of its neighbours.
        const std::uint32_t ahead = (s + n - i) % n;  // s - i, as a place along the loop
        if (ahead <= 1 || ahead >= n - 2) continue;
      }
      SelfContact c;
      c.patch = PatchId(p);
      c.loop = l;
      c.vertex = i;
      c.seg_loop = m;
      c.seg = s;
      c.distance = segment_distance(loops[l][i], loops[m][s], loops[m][(s + 1) % n]);
      if (c.distance > within) continue;
      if (!best || key(c) < key(*best)) best = c;
    }
  }
  return best;
}

std::string describe(const Part& part, const SelfContact& c) {
  const Patch& patch = part.patches[c.patch.index()];
  const Loop& at = patch.loops[c.loop];
  const Loop& seg = patch.loops[c.seg_loop];
  const VertexId v = at.vertices[c.vertex];
  const Vec3 x = part.vertices[v.index()].position;
  const VertexId a = seg.vertices[c.seg];
  const VertexId b = seg.vertices[(c.seg + 1) % seg.vertices.size()];
  std::string s = part.patch_label(c.patch) + ": its boundary comes within " + number(c.distance) +
                  " " + part.units + " (" + number(c.distance / part.size) +
                  " x the part's size) of itself: " + vertex_label(part, v) + " at (" +
                  number(x.x, 9) + ", " + number(x.y, 9) + ", " + number(x.z, 9) + ") of " +
                  loop_label(c.loop) + " and the segment from " + vertex_label(part, a) + " to " +
                  vertex_label(part, b) + " of " + loop_label(c.seg_loop);
  return s;
}

}  // namespace laytracks
