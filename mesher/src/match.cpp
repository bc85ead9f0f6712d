#include "match.hpp"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/max_cardinality_matching.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <utility>

#include "cdt.hpp"
#include "fill.hpp"

namespace laytracks::mesher_detail {

namespace {

/// The target size grows by one of these per unit of distance from a boundary node (whose own
/// size is the mean of its two edges), up to the polygon's longest edge: the first that pairs
/// every triangle is kept, else the one leaving the fewest alone.
constexpr double kMatchGradings[] = {0.3, 0.2, 0.45};
/// At most this many inner points (a face needing more goes to the other templates).
constexpr std::size_t kMatchMaxPoints = 20000;
/// Laplacian sweeps over the inner points before the triangles are paired.
constexpr int kMatchSmoothing = 4;
/// Two triangles are paired only when their quad's worst corner is above this; when that
/// leaves no perfect matching, any valid quad (above kMatchLastFloor) may be used.
constexpr double kMatchFloor = 0.2;
constexpr double kMatchLastFloor = 1e-3;

using Tri = std::array<std::uint32_t, 3>;

double twice_area(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); }

/// Moves each inner point towards the mean of its neighbours when no triangle round it turns.
void smooth_inner(std::vector<Vec2>& pts, std::uint32_t n, const std::vector<Tri>& tris) {
  std::vector<std::vector<std::uint32_t>> nb(pts.size()), around(pts.size());
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      nb[tris[t][k]].push_back(tris[t][(k + 1) % 3]);
      around[tris[t][k]].push_back(t);
    }
  for (int sweep = 0; sweep < kMatchSmoothing; ++sweep) {
    for (std::uint32_t v = n; v < pts.size(); ++v) {
      if (nb[v].empty()) continue;
      Vec2 c{0.0, 0.0};
      for (std::uint32_t u : nb[v]) c = c + pts[u];
      c = (1.0 / static_cast<double>(nb[v].size())) * c;
      const Vec2 old = pts[v];
      pts[v] = c;
      for (std::uint32_t t : around[v])
        if (!(twice_area(pts[tris[t][0]], pts[tris[t][1]], pts[tris[t][2]]) > 0.0)) {
          pts[v] = old;
          break;
        }
    }
  }
}

template <typename G, typename M>
struct KeepMatching {  // the matching the caller started
  static void find_matching(const G&, M) {}
};

struct Pair {
  std::uint32_t t0, t1;  ///< triangles, t0 < t1
  std::array<std::uint32_t, 4> quad;
  double jacobian, weight;
};

constexpr std::uint32_t kUnpaired = 0xffffffffu;

/// A maximum matching of the triangles over the pairs above `floor` (greedy by weight, best
/// first, then Edmonds' augmenting paths); kUnpaired for a triangle left alone.
std::vector<std::uint32_t> maximum_matching(std::size_t count,
                                            const std::vector<Pair>& pairs,
                                            double floor) {
  using G = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  using V = boost::graph_traits<G>::vertex_descriptor;
  const V none = boost::graph_traits<G>::null_vertex();
  G g(count);
  std::vector<V> mate(count, none);
  for (const Pair& p : pairs) {  // best first
    if (p.jacobian <= floor) continue;
    boost::add_edge(p.t0, p.t1, g);
    if (mate[p.t0] == none && mate[p.t1] == none) {
      mate[p.t0] = p.t1;
      mate[p.t1] = p.t0;
    }
  }
  boost::matching<G, V*, boost::property_map<G, boost::vertex_index_t>::type,
                  boost::edmonds_augmenting_path_finder, KeepMatching, boost::no_matching_verifier>(
      g, mate.data(), boost::get(boost::vertex_index, g));
  std::vector<std::uint32_t> out(count, kUnpaired);
  for (std::size_t t = 0; t < count; ++t)
    if (mate[t] != none) out[t] = static_cast<std::uint32_t>(mate[t]);
  return out;
}

/// The inner edge two paired triangles share (smaller node first).
std::pair<std::uint32_t, std::uint32_t> edge_of(const Pair& p) {
  return {std::min(p.quad[0], p.quad[2]), std::max(p.quad[0], p.quad[2])};
}

/// Costs of a path between two unpaired triangles (path_between): an edge that becomes marked
/// (a new pair) kPathStep, kPathPoorPair more when its quad's worst corner is below
/// kSmoothFloor (it becomes two rings of five); a triangle left with three marks (three quads
/// round its centre, its neighbours rings) kPathThreeMarks.
constexpr double kPathStep = 1.0;
constexpr double kPathPoorPair = 6.0;
constexpr double kPathThreeMarks = 8.0;

/// The cheapest path (Dijkstra over triangle and whether it was entered across a marked edge)
/// from the unpaired triangle `from` to another one (`alone`), as the pairs it crosses in
/// order; toggling their marks leaves every triangle one or three. Ties go to the smaller
/// state, so the path is the same in every pose.
std::vector<std::size_t> path_between(
    std::uint32_t from,
    const std::vector<bool>& alone,
    const std::vector<std::vector<std::pair<std::uint32_t, std::size_t>>>& across,
    const std::vector<bool>& on,
    const std::vector<int>& degree,
    const std::vector<Pair>& pairs) {
  const std::size_t states = 2 * across.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost(states, inf);
  std::vector<std::size_t> via(states, pairs.size()), back(states, states);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> todo;
  const std::size_t start = 2 * std::size_t{from};
  cost[start] = 0.0;
  todo.push({0.0, start});
  while (!todo.empty()) {
    const auto [c, st] = todo.top();
    todo.pop();
    if (c > cost[st]) continue;
    const auto x = static_cast<std::uint32_t>(st / 2);
    if (x != from && alone[x]) {
      std::vector<std::size_t> path;
      for (std::size_t s = st; s != start; s = back[s]) path.push_back(via[s]);
      std::reverse(path.begin(), path.end());
      return path;
    }
    const bool entered_marked = st % 2 == 1;
    for (const auto& [u, k] : across[x]) {
      int left = degree[x] + (on[k] ? -1 : 1);
      if (x != from) left += entered_marked ? -1 : 1;
      double step =
          on[k] ? 0.0 : kPathStep + (pairs[k].jacobian < kSmoothFloor ? kPathPoorPair : 0.0);
      if (left == 3) step += kPathThreeMarks;
      const std::size_t next = 2 * std::size_t{u} + (on[k] ? 1 : 0);
      if (c + step < cost[next]) {
        cost[next] = c + step;
        via[next] = k;
        back[next] = st;
        todo.push({cost[next], next});
      }
    }
  }
  return {};
}

/// One triangulation and its matching.
struct Matching {
  std::vector<Vec2> pts;
  std::vector<Tri> tris;
  std::vector<Pair> pairs;  ///< across every inner edge, best first
  std::vector<std::uint32_t> mate;
  std::size_t unpaired = 0;
};

/// The polygon triangulated with inner points for sizes graded by `grading` (see
/// matched_triangles), and its triangles matched.
std::optional<Matching> match_with(const std::vector<Vec2>& polygon, double grading) {
  const auto n = static_cast<std::uint32_t>(polygon.size());
  std::vector<double> edge(n), own(n);
  double longest = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) {
    edge[i] = norm(polygon[(i + 1) % n] - polygon[i]);
    longest = std::max(longest, edge[i]);
  }
  for (std::uint32_t i = 0; i < n; ++i) own[i] = 0.5 * (edge[(i + n - 1) % n] + edge[i]);
  // The nodes by x: from the query's x outwards, a node farther in x than (s - the least
  // own size) / grading cannot lower s.
  std::vector<std::uint32_t> by_x(n);
  for (std::uint32_t i = 0; i < n; ++i) by_x[i] = i;
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t i, std::uint32_t j) {
    return polygon[i].x != polygon[j].x ? polygon[i].x < polygon[j].x : i < j;
  });
  const double least = *std::min_element(own.begin(), own.end());
  const auto size = [&](Vec2 p) {
    double s = longest;
    const auto from = std::lower_bound(by_x.begin(), by_x.end(), p.x,
                                       [&](std::uint32_t i, double x) { return polygon[i].x < x; });
    const auto visit = [&](std::uint32_t i) {
      const Vec2 d = p - polygon[i];
      s = std::min(s, own[i] + grading * std::sqrt(dot(d, d)));
    };
    for (auto it = from; it != by_x.end() && least + grading * (polygon[*it].x - p.x) < s; ++it)
      visit(*it);
    for (auto it = from; it != by_x.begin() && least + grading * (p.x - polygon[*(it - 1)].x) < s;
         --it)
      visit(*(it - 1));
    return s;
  };
  Matching r;
  r.pts = polygon;
  const std::vector<Vec2> inner = refinement_points(polygon, size, kMatchMaxPoints);
  if (inner.size() >= kMatchMaxPoints) return std::nullopt;
  r.pts.insert(r.pts.end(), inner.begin(), inner.end());
  r.tris = constrained_triangulation(r.pts, n);
  if (r.tris.empty()) return std::nullopt;
  if (!inner.empty()) {
    smooth_inner(r.pts, n, r.tris);
    r.tris = constrained_triangulation(r.pts, n);
    if (r.tris.empty()) return std::nullopt;
  }
  // Pairs across each inner edge; the quad runs round both triangles counter-clockwise.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<std::uint32_t, std::size_t>> half;
  const std::vector<Vec2>& pts = r.pts;
  for (std::uint32_t t = 0; t < r.tris.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t a = r.tris[t][k], b = r.tris[t][(k + 1) % 3], c = r.tris[t][(k + 2) % 3];
      const auto it = half.find({b, a});
      if (it == half.end()) {
        half[{a, b}] = {t, k};
        continue;
      }
      const std::uint32_t u = it->second.first;
      const std::uint32_t d = r.tris[u][(it->second.second + 2) % 3];  // triangle u = (b, a, d)
      const std::array<std::uint32_t, 4> q{a, d, b, c};
      const double j = min_scaled_jacobian(pts[q[0]], pts[q[1]], pts[q[2]], pts[q[3]]);
      const double w = std::min(j, quad_taper(pts[q[0]], pts[q[1]], pts[q[2]], pts[q[3]]));
      r.pairs.push_back({std::min(t, u), std::max(t, u), q, j, w});
    }
  std::sort(r.pairs.begin(), r.pairs.end(), [](const Pair& x, const Pair& y) {
    if (x.weight != y.weight) return x.weight > y.weight;
    if (x.t0 != y.t0) return x.t0 < y.t0;
    return x.t1 < y.t1;
  });
  const auto alone = [](const std::vector<std::uint32_t>& mate) {
    return static_cast<std::size_t>(std::count(mate.begin(), mate.end(), kUnpaired));
  };
  r.mate = maximum_matching(r.tris.size(), r.pairs, kMatchFloor);
  r.unpaired = alone(r.mate);
  if (r.unpaired > 0) {
    std::vector<std::uint32_t> last = maximum_matching(r.tris.size(), r.pairs, kMatchLastFloor);
    if (alone(last) < r.unpaired) {
      r.mate = std::move(last);
      r.unpaired = alone(r.mate);
    }
  }
  return r;
}

}  // namespace

std::optional<MarkedTriangles> matched_triangles(const std::vector<Vec2>& polygon) {
  const auto n = static_cast<std::uint32_t>(polygon.size());
  if (n < 4 || n % 2 != 0) return std::nullopt;
  double area = 0.0;
  for (std::uint32_t i = 0; i < n; ++i) area += cross(polygon[i], polygon[(i + 1) % n]);
  if (!(area > 0.0)) return std::nullopt;
  // The first grading that pairs every triangle, else the one that leaves the fewest alone.
  std::optional<Matching> best;
  for (const double grading : kMatchGradings) {
    std::optional<Matching> m = match_with(polygon, grading);
    if (m && (!best || m->unpaired < best->unpaired)) best = std::move(m);
    if (best && best->unpaired == 0) break;
  }
  if (!best) return std::nullopt;
  std::vector<Vec2>& pts = best->pts;
  std::vector<Tri>& tris = best->tris;
  const std::vector<Pair>& pairs = best->pairs;
  const std::vector<std::uint32_t>& mate = best->mate;
  MarkedTriangles out;
  out.inner.assign(pts.begin() + n, pts.end());
  // The marks: the matched pairs' shared edges, then each path between two unpaired triangles
  // toggled (path_between).
  std::vector<std::vector<std::pair<std::uint32_t, std::size_t>>> across(
      tris.size());  // (triangle, pair)
  std::vector<bool> on(pairs.size());
  std::vector<int> degree(tris.size(), 0);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    across[pairs[k].t0].push_back({pairs[k].t1, k});
    across[pairs[k].t1].push_back({pairs[k].t0, k});
    on[k] = mate[pairs[k].t0] == pairs[k].t1;
    if (on[k]) {
      ++degree[pairs[k].t0];
      ++degree[pairs[k].t1];
    }
  }
  for (auto& a : across) std::sort(a.begin(), a.end());
  std::vector<bool> alone(tris.size(), false);
  for (std::size_t t = 0; t < tris.size(); ++t) alone[t] = mate[t] == kUnpaired;
  out.unpaired = best->unpaired;
  for (std::uint32_t s0 = 0; s0 < tris.size(); ++s0) {
    if (!alone[s0]) continue;
    alone[s0] = false;
    const std::vector<std::size_t> path = path_between(s0, alone, across, on, degree, pairs);
    if (path.empty()) return std::nullopt;  // cannot happen: the count is even, the dual connected
    for (const std::size_t k : path) {
      const int step = on[k] ? -1 : 1;
      on[k] = !on[k];
      degree[pairs[k].t0] += step;
      degree[pairs[k].t1] += step;
    }
    alone[pairs[path.back()].t0] = false;
    alone[pairs[path.back()].t1] = false;
  }
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (on[k]) out.marks.push_back(edge_of(pairs[k]));
  std::sort(out.marks.begin(), out.marks.end());
  out.triangles = std::move(tris);
  return out;
}

}  // namespace laytracks::mesher_detail
