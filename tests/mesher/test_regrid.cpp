// The regrid's fills (docs/mesher.md, "Regrid"): a cavity's boundary cycle, read by how many
// of its quads meet each node, gets a grid with no irregular node inside (a lattice fill) or
// one (three or five grids round a centre), and each cycle node keeps its count of quads.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "fill.hpp"
#include "regrid.hpp"

using namespace laytracks;
using namespace laytracks::mesher_detail;

namespace {

/// Turns of a cycle of corners (turn 1) with `sides[i]` edges from corner i to corner i + 1.
std::vector<int> corner_turns(const std::vector<int>& sides) {
  std::vector<int> turn;
  for (const int s : sides) {
    turn.push_back(1);
    for (int k = 1; k < s; ++k) turn.push_back(0);
  }
  return turn;
}

/// The quads at each node of the fill.
std::map<std::uint32_t, int> quads_at(const TurnFill& f) {
  std::map<std::uint32_t, int> at;
  for (const auto& q : f.quads)
    for (const std::uint32_t v : q) ++at[v];
  return at;
}

/// The fill is a quad mesh of a disk whose boundary is the cycle: every edge is in two quads
/// but the cycle's, each once and the way the cycle runs; each cycle node in 2 - turn quads;
/// inner nodes in four quads, but those of `irregular` (inner node id: its quads).
void check_fill(const TurnFill& f,
                const std::vector<int>& turn,
                const std::map<std::uint32_t, int>& irregular = {}) {
  const auto n = static_cast<std::uint32_t>(turn.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& q : f.quads) {
    REQUIRE(std::set<std::uint32_t>(q.begin(), q.end()).size() == 4);
    for (std::size_t k = 0; k < 4; ++k) ++directed[{q[k], q[(k + 1) % 4]}];
  }
  for (const auto& [e, count] : directed) {
    CHECK(count == 1);
    const bool on_cycle = e.first < n && e.second < n && (e.first + 1) % n == e.second;
    if (!on_cycle) CHECK(directed.count({e.second, e.first}) == 1);
  }
  for (std::uint32_t i = 0; i < n; ++i) CHECK(directed.count({i, (i + 1) % n}) == 1);
  const std::map<std::uint32_t, int> at = quads_at(f);
  for (std::uint32_t i = 0; i < n; ++i) {
    INFO("cycle node " << i);
    CHECK(at.at(i) == 2 - turn[i]);
  }
  for (std::uint32_t v = n; v < n + f.interior.size(); ++v) {
    INFO("inner node " << v);
    const auto special = irregular.find(v);
    CHECK(at.at(v) == (special != irregular.end() ? special->second : 4));
  }
  // Euler for a disk: V - E + F = 1.
  const long edges = static_cast<long>(directed.size() + n) / 2;
  CHECK(static_cast<long>(n + f.interior.size()) - edges + static_cast<long>(f.quads.size()) == 1);
}

/// The cycle of a set of unit squares (a polyomino without holes or pinches) and its turns:
/// the directed edges of the squares that no other square has reversed, followed from the
/// lowest point. Returns the turns (2 - the squares at each cycle node).
std::vector<int> polyomino_turns(const std::set<std::pair<int, int>>& cells) {
  std::map<std::pair<int, int>, std::pair<int, int>> next;
  std::set<std::pair<std::pair<int, int>, std::pair<int, int>>> edges;
  for (const auto& [x, y] : cells) {
    const std::pair<int, int> c[4] = {{x, y}, {x + 1, y}, {x + 1, y + 1}, {x, y + 1}};
    for (int k = 0; k < 4; ++k) edges.insert({c[k], c[(k + 1) % 4]});
  }
  for (const auto& [a, b] : edges)
    if (!edges.count({b, a})) next[a] = b;
  std::vector<int> turn;
  const std::pair<int, int> start = next.begin()->first;
  std::pair<int, int> v = start;
  do {
    int count = 0;
    for (const auto& [dx, dy] :
         {std::pair{0, 0}, std::pair{-1, 0}, std::pair{0, -1}, std::pair{-1, -1}})
      count += static_cast<int>(cells.count({v.first + dx, v.second + dy}));
    turn.push_back(2 - count);
    v = next.at(v);
  } while (v != start);
  return turn;
}

/// Points of a polygon for the cycle: corner i of the turns at a regular polygon's vertex,
/// the straight nodes evenly between.
std::vector<Vec2> polygon_for(const std::vector<int>& turn, double radius, double phase) {
  std::vector<std::size_t> corners;
  for (std::size_t i = 0; i < turn.size(); ++i)
    if (turn[i] == 1) corners.push_back(i);
  const std::size_t c = corners.size();
  std::vector<Vec2> pts(turn.size());
  for (std::size_t j = 0; j < c; ++j) {
    const double a0 = phase + 2.0 * kPi * static_cast<double>(j) / static_cast<double>(c);
    const double a1 = phase + 2.0 * kPi * static_cast<double>(j + 1) / static_cast<double>(c);
    const Vec2 p0{radius * std::cos(a0), radius * std::sin(a0)};
    const Vec2 p1{radius * std::cos(a1), radius * std::sin(a1)};
    const std::size_t from = corners[j], to = corners[(j + 1) % c] + (j + 1 == c ? turn.size() : 0);
    for (std::size_t i = from; i < to; ++i)
      pts[i % turn.size()] =
          lerp(p0, p1, static_cast<double>(i - from) / static_cast<double>(to - from));
  }
  return pts;
}

/// The worst scaled Jacobian of the fill's quads, placed.
double worst_placed(const TurnFill& f, const std::vector<Vec2>& cycle) {
  const std::size_t n = cycle.size();
  const auto at = [&](std::uint32_t v) { return v < n ? cycle[v] : f.interior[v - n]; };
  double worst = 1.0;
  for (const auto& q : f.quads)
    worst = std::min(worst, min_scaled_jacobian(at(q[0]), at(q[1]), at(q[2]), at(q[3])));
  return worst;
}

}  // namespace

TEST_CASE("a cycle that turns as a rectangle's gets a grid with every inner node in four quads",
          "[regrid]") {
  for (int m = 1; m <= 5; ++m)
    for (int k = 1; k <= 5; ++k) {
      INFO(m << " x " << k);
      std::vector<int> turn = corner_turns({m, k, m, k});
      for (std::size_t start = 0; start < turn.size(); start += 3) {  // any node first
        std::vector<int> turned = turn;
        std::rotate(turned.begin(), turned.begin() + static_cast<std::ptrdiff_t>(start),
                    turned.end());
        const auto f = lattice_fill(turned);
        REQUIRE(f);
        CHECK(f->quads.size() == static_cast<std::size_t>(m * k));
        CHECK(f->interior.size() == static_cast<std::size_t>((m - 1) * (k - 1)));
        check_fill(*f, turned);
      }
      // Placed on a rectangle whose sides are evenly divided: the grid itself.
      std::vector<Vec2> rect;
      for (int i = 0; i < m; ++i) rect.push_back({1.5 * i, 0.0});
      for (int j = 0; j < k; ++j) rect.push_back({1.5 * m, 1.5 * j});
      for (int i = m; i > 0; --i) rect.push_back({1.5 * i, 1.5 * k});
      for (int j = k; j > 0; --j) rect.push_back({0.0, 1.5 * j});
      auto f = lattice_fill(turn);
      place_harmonic(*f, rect, 200);
      CHECK(worst_placed(*f, rect) > 0.999);
    }
}

TEST_CASE("a cycle that turns as a polyomino's gets its squares; one that cannot close gets none",
          "[regrid]") {
  // An L, a T, a plus, a staircase and a U, each as squares; the fill has as many squares.
  const std::vector<std::set<std::pair<int, int>>> shapes = {
      {{0, 0}, {1, 0}, {2, 0}, {0, 1}, {0, 2}},
      {{0, 0}, {1, 0}, {2, 0}, {1, 1}, {1, 2}, {0, 3}, {1, 3}, {2, 3}, {0, 4}, {1, 4}, {2, 4}},
      {{1, 0}, {1, 1}, {0, 1}, {2, 1}, {1, 2}, {0, 0}, {2, 2}, {3, 1}, {1, 3}},
      {{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}, {3, 2}, {0, 1}, {1, 2}, {2, 3}, {3, 3}},
      {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 1}, {3, 1}, {0, 2}, {3, 2}, {1, 0}, {0, 3}, {3, 3}}};
  for (const auto& cells : shapes) {
    const std::vector<int> turn = polyomino_turns(cells);
    INFO(turn.size() << " cycle nodes");
    const auto f = lattice_fill(turn);
    REQUIRE(f);
    CHECK(f->quads.size() == cells.size());
    check_fill(*f, turn);
  }
  // Sides 3, 2, 4, 2: the walk ends a step from its start (a dislocation inside).
  CHECK_FALSE(lattice_fill(corner_turns({3, 2, 4, 2})));
  // Three corners: the turns add up to 3.
  CHECK_FALSE(lattice_fill(corner_turns({2, 2, 2})));
  // Two squares touching at a corner only: the walk closes and turns by 4 but meets itself.
  CHECK_FALSE(lattice_fill({1, 1, -1, 1, 1, 1, -1, 1}));
}

TEST_CASE("a cycle of three or five corners gets grids round one centre node", "[regrid]") {
  struct Case {
    std::vector<int> sides;
    std::size_t quads;  ///< 0: no fill
  };
  // s_j = L_{j-1} + L_{j+1}; quads = sum of L_{i-1} L_i.
  const Case cases[] = {{{2, 2, 2}, 3},        {{4, 4, 4}, 12},       {{3, 3, 4}, 8},
                        {{6, 5, 5}, 21},       {{3, 3, 3}, 0},        {{2, 2, 6}, 0},
                        {{2, 2, 2, 2, 2}, 5},  {{4, 4, 4, 4, 4}, 20}, {{3, 3, 4, 3, 3}, 13},
                        {{3, 4, 3, 4, 4}, 16}, {{4, 3, 3, 4, 4}, 17}, {{2, 2, 2, 2, 3}, 0},
                        {{2, 2, 2, 2, 4}, 0},  {{2, 2, 2, 2}, 0}};
  for (const Case& c : cases) {
    std::vector<int> turn = corner_turns(c.sides);
    INFO(turn.size() << " cycle nodes, " << c.sides.size() << " corners, sides from "
                     << c.sides.front());
    const auto f = sided_fill(turn);
    if (c.quads == 0) {
      CHECK_FALSE(f);
      continue;
    }
    REQUIRE(f);
    CHECK(f->quads.size() == c.quads);
    const auto centre = static_cast<std::uint32_t>(turn.size());  // the first inner node
    check_fill(*f, turn, {{centre, static_cast<int>(c.sides.size())}});
    // On a regular polygon: valid quads, the centre inside (at the middle when the sides are
    // equal).
    auto placed = *f;
    const std::vector<Vec2> poly = polygon_for(turn, 3.0, 0.3);
    place_harmonic(placed, poly, 300);
    CHECK(worst_placed(placed, poly) > 0.3);
    const double inradius = 3.0 * std::cos(kPi / static_cast<double>(c.sides.size()));
    CHECK(norm(placed.interior.front()) < 0.8 * inradius);
    if (std::all_of(c.sides.begin(), c.sides.end(), [&](int x) { return x == c.sides.front(); }))
      CHECK(norm(placed.interior.front()) < 1e-9);
  }
  // A pentagon's sides that solve: L = (1, 2, 1, 2, 2) gives s_j = L_{j-1} + L_{j+1}.
  const std::vector<long> L = {1, 2, 1, 2, 2};
  std::vector<int> sides;
  for (std::size_t j = 0; j < 5; ++j)
    sides.push_back(static_cast<int>(L[(j + 4) % 5] + L[(j + 1) % 5]));
  const std::vector<int> turn = corner_turns(sides);
  const auto f = sided_fill(turn);
  REQUIRE(f);
  std::size_t quads = 0;
  for (std::size_t i = 0; i < 5; ++i) quads += static_cast<std::size_t>(L[(i + 4) % 5] * L[i]);
  CHECK(f->quads.size() == quads);
  check_fill(*f, turn, {{static_cast<std::uint32_t>(turn.size()), 5}});
}

TEST_CASE("a cycle whose nodes are all straight gets an O-grid: rings round a core grid",
          "[regrid]") {
  // n cycle nodes, `layers` rings of n quads, a core of a x b quads (a = n / 4, b = n / 2 - a)
  // whose four corners, on the last ring, are the only inner nodes in three quads.
  for (std::uint32_t n : {8u, 10u, 12u, 14u, 20u, 22u})
    for (std::uint32_t layers : {1u, 2u, 3u})
      for (std::uint32_t start : {0u, 1u, n / 8, n - 1}) {
        INFO(n << " cycle nodes, " << layers << " layers, first corner under " << start);
        const std::vector<int> turn(n, 0);
        const auto f = ogrid_fill(turn, layers, start);
        REQUIRE(f);
        const std::uint32_t a = n / 4, b = n / 2 - a;
        CHECK(f->quads.size() == layers * n + a * b);
        CHECK(f->interior.size() == layers * n + (a - 1) * (b - 1));
        // The last ring's nodes come after the others (ring l's node i is n + (l - 1) n + i,
        // i counted from `start`); its nodes 0, a, a + b and 2a + b are the core's corners.
        std::map<std::uint32_t, int> corners;
        for (std::uint32_t i : {0u, a, a + b, 2 * a + b}) corners[n + (layers - 1) * n + i] = 3;
        check_fill(*f, turn, corners);
        // On a regular polygon (a circle's chords): valid quads, none much distorted.
        auto placed = *f;
        const double radius = 2.0 + 0.5 * static_cast<double>(n);
        std::vector<Vec2> poly;
        for (std::uint32_t i = 0; i < n; ++i) {
          const double t = 0.2 + 2.0 * kPi * static_cast<double>(i) / static_cast<double>(n);
          poly.push_back({radius * std::cos(t), radius * std::sin(t)});
        }
        place_harmonic(placed, poly, 500);
        CHECK(worst_placed(placed, poly) > 0.3);
      }
  // A corner (a turn of 1 and one of -1: the turns still add up to 0), an odd cycle, too few
  // nodes, no layer: none.
  std::vector<int> bent(12, 0);
  bent[2] = 1;
  bent[7] = -1;
  CHECK_FALSE(ogrid_fill(bent, 1, 0));
  CHECK_FALSE(ogrid_fill(std::vector<int>(11, 0), 1, 0));
  CHECK_FALSE(ogrid_fill(std::vector<int>(6, 0), 1, 0));
  CHECK_FALSE(ogrid_fill(std::vector<int>(12, 0), 0, 0));
}
