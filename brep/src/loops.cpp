// Rule 3 of build_part(): loop lengths, repeated and shared vertices, vertex spacing.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "build_state.hpp"
#include "describe.hpp"

namespace laytracks::detail {
namespace {

using Cell = std::array<std::int64_t, 3>;

/// Where each vertex was last seen while scanning the loops.
struct Seen {
  std::size_t patch = std::numeric_limits<std::size_t>::max();
  std::size_t loop = 0;
  std::size_t position = 0;
};

/// Refuses a loop that is too short, repeats a vertex, or shares one with an earlier loop of
/// the same patch. `seen` holds the last sighting of every vertex.
void check_loop(const BuildState& s, std::size_t p, std::size_t l, std::vector<Seen>& seen) {
  const auto& loop = s.raw.patches[p].loops[l];
  const std::string where = patch_name(s, p) + ": " + loop_name(l);
  if (loop.size() < 3) {
    fail(where + " has only " + std::to_string(loop.size()) +
         (loop.size() == 1 ? " vertex" : " vertices") + "; a loop needs at least 3");
  }
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto v = static_cast<std::size_t>(loop[i]);
    Seen& last = seen[v];
    if (last.patch == p && last.loop == l) {
      fail(where + " repeats vertex " + std::to_string(v) + " (at positions " +
           std::to_string(last.position) + " and " + std::to_string(i) + ")");
    }
    if (last.patch == p) {
      fail(where + " touches " + loop_name(last.loop) + " at vertex " + std::to_string(v) + " " +
           point(s.raw.vertices[v]) + "; the loops of a patch must not touch");
    }
    last = {p, l, i};
  }
}

/// The grid cell of p for cells of side h, counted from lo (clamped far out: no overflow).
Cell cell_of(Vec3 p, Vec3 lo, double h) {
  const auto index = [h](double c) {
    return static_cast<std::int64_t>(std::clamp(std::floor(c / h), -4e18, 4e18));
  };
  return {index(p.x - lo.x), index(p.y - lo.y), index(p.z - lo.z)};
}

/// The message for two vertices closer than the minimum distance.
std::string too_close(const BuildState& s, VertexId a, VertexId b, double min_distance) {
  if (b < a) std::swap(a, b);
  const Vec3 pa = s.part.vertices[a.index()].position;
  const Vec3 pb = s.part.vertices[b.index()].position;
  const bool both_file = b.index() < s.file_vertex_count();
  const std::string names =
      both_file ? "vertices " + std::to_string(a.index()) + " and " + std::to_string(b.index())
                : vertex_name(s, a) + " and " + vertex_name(s, b);
  return names + " are only " + len(s, distance(pa, pb)) + " apart, at " + point(pa) +
         "; distinct vertices must be at least " + len(s, min_distance) + " apart (" +
         num(Tolerances::kMinVertexDistance) + " x the part size)";
}

}  // namespace

void check_loops(BuildState& s) {
  std::vector<Seen> seen(s.raw.vertices.size());
  for (std::size_t p = 0; p < s.raw.patches.size(); ++p) {
    for (std::size_t l = 0; l < s.raw.patches[p].loops.size(); ++l) check_loop(s, p, l, seen);
  }
  std::vector<VertexId> used;
  for (std::size_t i = 0; i < s.used.size(); ++i) {
    if (s.used[i]) used.emplace_back(i);
  }
  check_vertex_spacing(s, used);
}

void check_vertex_spacing(const BuildState& s, const std::vector<VertexId>& ids) {
  // A grid of cells twice the minimum distance: a close neighbour of a point lies in its own
  // cell or, along each axis, in the one cell on the side of the nearer face: 8 cells to visit.
  const double min_distance = Tolerances::kMinVertexDistance * s.part.size;
  const double h = 2.0 * min_distance;
  const Vec3 lo = s.part.bbox.lo;
  std::vector<std::pair<Cell, std::size_t>> grid;
  grid.reserve(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    grid.emplace_back(cell_of(s.part.vertices[ids[k].index()].position, lo, h), k);
  }
  std::sort(grid.begin(), grid.end());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const Vec3 p = s.part.vertices[ids[k].index()].position;
    const Cell c = cell_of(p, lo, h);
    const Vec3 f = (1.0 / h) * (p - lo);
    const Cell side = {(f.x - std::floor(f.x)) < 0.5 ? -1 : 1,
                       (f.y - std::floor(f.y)) < 0.5 ? -1 : 1,
                       (f.z - std::floor(f.z)) < 0.5 ? -1 : 1};
    for (int corner = 0; corner < 8; ++corner) {
      Cell n = c;
      for (int d = 0; d < 3; ++d) {
        if (corner & (1 << d)) n[static_cast<std::size_t>(d)] += side[static_cast<std::size_t>(d)];
      }
      auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(n, std::size_t{0}));
      for (; it != grid.end() && it->first == n; ++it) {
        if (it->second == k) continue;
        const Vec3 q = s.part.vertices[ids[it->second].index()].position;
        if (distance(p, q) < min_distance)
          fail(too_close(s, ids[k], ids[it->second], min_distance));
      }
    }
  }
}

}  // namespace laytracks::detail
