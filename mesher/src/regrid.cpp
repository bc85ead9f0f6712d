#include "regrid.hpp"

#include <algorithm>
#include <cstddef>

namespace laytracks::mesher_detail {

namespace {
constexpr std::uint32_t kUnset = 0xffffffffu;
}  // namespace

std::optional<TurnFill> lattice_fill(const std::vector<int>& turn) {
  static constexpr int kStep[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  const std::size_t n = turn.size();
  int turning = 0;
  for (const int t : turn) {
    if (t < -1 || t > 1) return std::nullopt;
    turning += t;
  }
  if (n < 4 || turning != 4) return std::nullopt;
  // Node i sits at lattice[i]; the edge from it runs in the direction it turned to.
  std::vector<std::array<int, 2>> lattice(n);
  int dir = 0, x = 0, y = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) dir = (dir + turn[i] + 4) % 4;
    lattice[i] = {x, y};
    x += kStep[dir][0];
    y += kStep[dir][1];
  }
  if (x != 0 || y != 0) return std::nullopt;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  for (const auto& [lx, ly] : lattice) {
    x0 = std::min(x0, lx);
    y0 = std::min(y0, ly);
    x1 = std::max(x1, lx);
    y1 = std::max(y1, ly);
  }
  const auto wide = static_cast<std::size_t>(x1 - x0 + 1);
  const auto cell = [&](int lx, int ly) {
    return static_cast<std::size_t>(ly - y0) * wide + static_cast<std::size_t>(lx - x0);
  };
  std::vector<std::uint32_t> id(wide * static_cast<std::size_t>(y1 - y0 + 1), kUnset);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t& at = id[cell(lattice[i][0], lattice[i][1])];
    if (at != kUnset) return std::nullopt;  // the walk meets itself
    at = static_cast<std::uint32_t>(i);
  }
  TurnFill f;
  const auto node_at = [&](int lx, int ly) {
    std::uint32_t& at = id[cell(lx, ly)];
    if (at == kUnset) {
      at = static_cast<std::uint32_t>(n + f.interior.size());
      f.interior.push_back({0.0, 0.0});
    }
    return at;
  };
  // A square is inside when a ray from its centre along +x crosses the walk an odd number of
  // times (only the walk's vertical edges can cross it).
  for (int cy = y0; cy < y1; ++cy)
    for (int cx = x0; cx < x1; ++cx) {
      bool in = false;
      for (std::size_t i = 0; i < n; ++i) {
        const auto& a = lattice[i];
        const auto& b = lattice[(i + 1) % n];
        if ((a[1] > cy) != (b[1] > cy) && a[0] > cx) in = !in;
      }
      if (in)
        f.quads.push_back(
            {node_at(cx, cy), node_at(cx + 1, cy), node_at(cx + 1, cy + 1), node_at(cx, cy + 1)});
    }
  // A simple closed walk turning +4 runs counter-clockwise: its squares lie on its left, a
  // node at a left turn is in one of them, a straight node in two, one at a right turn in
  // three, and a lattice node inside in four.
  if (f.quads.empty()) return std::nullopt;
  return f;
}

std::optional<TurnFill> sided_fill(const std::vector<int>& turn) {
  const std::size_t n = turn.size();
  std::vector<std::size_t> corner;
  for (std::size_t i = 0; i < n; ++i) {
    if (turn[i] == 1)
      corner.push_back(i);
    else if (turn[i] != 0)
      return std::nullopt;
  }
  const std::size_t c = corner.size();
  if (c != 3 && c != 5) return std::nullopt;
  std::vector<long> s(c), a(c, 0), slope(c, 0), spoke(c);
  for (std::size_t i = 0; i < c; ++i)
    s[i] = static_cast<long>((corner[(i + 1) % c] + n - corner[i]) % n);
  // L_j = a_j + slope_j x, from L_0 = x, by L_{j+1} = s_j - L_{j-1} two steps at a time round
  // the odd cycle, back to L_0: x = (a + slope x) there.
  slope[0] = 1;
  std::size_t j = 0;
  long x = 0;
  for (std::size_t step = 0; step < c; ++step) {
    const std::size_t side = (j + 1) % c, next = (j + 2) % c;
    const long na = s[side] - a[j], ns = -slope[j];
    if (next == 0) {
      const long d = slope[0] - ns;  // 2 for an odd cycle
      if (d == 0 || (na - a[0]) % d != 0) return std::nullopt;
      x = (na - a[0]) / d;
      break;
    }
    a[next] = na;
    slope[next] = ns;
    j = next;
  }
  for (std::size_t i = 0; i < c; ++i) {
    spoke[i] = a[i] + slope[i] * x;
    if (spoke[i] < 1) return std::nullopt;
  }
  TurnFill f;
  const auto fresh = [&] {
    f.interior.push_back({0.0, 0.0});
    return static_cast<std::uint32_t>(n + f.interior.size() - 1);
  };
  const std::uint32_t centre = fresh();
  // Spoke i's nodes from its foot (side i, L_{i-1} edges after corner i) to the centre.
  std::vector<std::vector<std::uint32_t>> spokes(c);
  for (std::size_t i = 0; i < c; ++i) {
    const std::size_t foot = (corner[i] + static_cast<std::size_t>(spoke[(i + c - 1) % c])) % n;
    spokes[i].push_back(static_cast<std::uint32_t>(foot));
    for (long t = 1; t < spoke[i]; ++t) spokes[i].push_back(fresh());
    spokes[i].push_back(centre);
  }
  // Grid i: u along side i from corner i (to spoke i's foot), v back along side i - 1 (to
  // spoke i - 1's foot); (u, v) turns counter-clockwise at a corner of a counter-clockwise
  // cycle, so its squares do too.
  for (std::size_t i = 0; i < c; ++i) {
    const auto wide = static_cast<std::size_t>(spoke[(i + c - 1) % c]);
    const auto high = static_cast<std::size_t>(spoke[i]);
    std::vector<std::uint32_t> id((wide + 1) * (high + 1));
    for (std::size_t v = 0; v <= high; ++v)
      for (std::size_t u = 0; u <= wide; ++u) {
        std::uint32_t& at = id[v * (wide + 1) + u];
        if (v == 0)
          at = static_cast<std::uint32_t>((corner[i] + u) % n);
        else if (u == 0)
          at = static_cast<std::uint32_t>((corner[i] + n - v) % n);
        else if (u == wide)
          at = spokes[i][v];
        else if (v == high)
          at = spokes[(i + c - 1) % c][u];
        else
          at = fresh();
      }
    for (std::size_t v = 0; v < high; ++v)
      for (std::size_t u = 0; u < wide; ++u)
        f.quads.push_back({id[v * (wide + 1) + u], id[v * (wide + 1) + u + 1],
                           id[(v + 1) * (wide + 1) + u + 1], id[(v + 1) * (wide + 1) + u]});
  }
  return f;
}

std::optional<TurnFill> ogrid_fill(const std::vector<int>& turn,
                                   std::uint32_t layers,
                                   std::uint32_t start) {
  const auto n = static_cast<std::uint32_t>(turn.size());
  if (n < 8 || n % 2 != 0 || layers < 1) return std::nullopt;
  if (std::any_of(turn.begin(), turn.end(), [](int t) { return t != 0; })) return std::nullopt;
  const std::uint32_t a = n / 4, b = n / 2 - a;
  TurnFill f;
  const auto fresh = [&] {
    f.interior.push_back({0.0, 0.0});
    return static_cast<std::uint32_t>(n + f.interior.size() - 1);
  };
  // Ring l (0 the cycle, `layers` the core's boundary), node i (from `start`).
  std::vector<std::uint32_t> ring(static_cast<std::size_t>(layers + 1) * n);
  const auto r = [&](std::uint32_t l, std::uint32_t i) -> std::uint32_t& {
    return ring[static_cast<std::size_t>(l) * n + i % n];
  };
  for (std::uint32_t i = 0; i < n; ++i) r(0, i) = (start + i) % n;
  for (std::uint32_t l = 1; l <= layers; ++l)
    for (std::uint32_t i = 0; i < n; ++i) r(l, i) = fresh();
  for (std::uint32_t l = 0; l < layers; ++l)
    for (std::uint32_t i = 0; i < n; ++i)
      f.quads.push_back({r(l, i), r(l, i + 1), r(l + 1, i + 1), r(l + 1, i)});
  // The core: u along its first side (ring nodes 0 .. a), v along its second (a .. a + b).
  std::vector<std::uint32_t> grid(static_cast<std::size_t>(a + 1) * (b + 1), kUnset);
  const auto g = [&](std::uint32_t u, std::uint32_t v) -> std::uint32_t& {
    return grid[static_cast<std::size_t>(v) * (a + 1) + u];
  };
  for (std::uint32_t u = 0; u < a; ++u) g(u, 0) = r(layers, u);
  for (std::uint32_t v = 0; v < b; ++v) g(a, v) = r(layers, a + v);
  for (std::uint32_t u = 0; u < a; ++u) g(a - u, b) = r(layers, a + b + u);
  for (std::uint32_t v = 0; v < b; ++v) g(0, b - v) = r(layers, 2 * a + b + v);
  for (std::uint32_t v = 1; v < b; ++v)
    for (std::uint32_t u = 1; u < a; ++u) g(u, v) = fresh();
  for (std::uint32_t v = 0; v < b; ++v)
    for (std::uint32_t u = 0; u < a; ++u)
      f.quads.push_back({g(u, v), g(u + 1, v), g(u + 1, v + 1), g(u, v + 1)});
  return f;
}

void place_harmonic(TurnFill& fill, const std::vector<Vec2>& cycle, int sweeps) {
  const std::size_t n = cycle.size();
  std::vector<std::vector<std::uint32_t>> next_to(fill.interior.size());
  for (const auto& q : fill.quads)
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t v = q[k], w = q[(k + 1) % 4];
      if (v >= n) next_to[v - n].push_back(w);
      if (w >= n) next_to[w - n].push_back(v);
    }
  Vec2 centre{0.0, 0.0};
  for (const Vec2& p : cycle) centre = centre + (1.0 / static_cast<double>(n)) * p;
  for (Vec2& p : fill.interior) p = centre;
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (std::size_t i = 0; i < fill.interior.size(); ++i) {
      if (next_to[i].empty()) continue;
      Vec2 sum{0.0, 0.0};
      for (std::uint32_t w : next_to[i]) sum = sum + (w < n ? cycle[w] : fill.interior[w - n]);
      fill.interior[i] = (1.0 / static_cast<double>(next_to[i].size())) * sum;
    }
}

}  // namespace laytracks::mesher_detail
