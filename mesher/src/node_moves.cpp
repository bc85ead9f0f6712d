// The node movers (docs/mesher.md, "Smoothing"): Laplacian sweeps, the corners' angle
// optimisation, the untangling search and the untapering, each moving only free nodes and
// each move checked before it is kept; final_sweeps chains them as the templates, the re-fill
// and the final smoothing relax. They read positions and quads only, so the same nodes give
// the same moves, to the bit, in every pose.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "fill.hpp"
#include "laytracks/mesher/quality.hpp"
#include "patch_quads.hpp"

namespace laytracks::mesher_detail {

double settled(double jacobian) { return std::round(jacobian / kJacobianGrain) * kJacobianGrain; }

void final_sweeps(std::vector<Vec2>& pos,
                  const std::vector<bool>& fixed,
                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                  int iterations,
                  double target,
                  const SweepSchedule* schedule) {
  smooth_nodes(pos, fixed, quads, iterations, schedule);
  // Then the corners' angles, against the edge lengths the Laplacian sweeps left.
  optimize_nodes(pos, fixed, quads, iterations, schedule);
  // Then each node still in a quad below `target` moves to raise its worst quad (above
  // kFinalEscapeTarget strictly: no worst quad falls, no quad is stretched).
  untangle_nodes(pos, fixed, quads, iterations, std::min(target, kFinalEscapeTarget),
                 kFinalEdgeFraction, false, schedule);
  if (target > kFinalEscapeTarget)
    untangle_nodes(pos, fixed, quads, iterations, target, kFinalEdgeFraction, true, schedule);
}

namespace {

bool keeps_sign(double before, double after) { return after > 0.0 || !(before > 0.0); }

/// A list per node, all in one block (each node's slice between offsets): the node movers'
/// adjacency, built for every template tried and every cavity relaxed, without an
/// allocation per node (with one per node, allocation was a tenth of the re-fill's time).
template <class T>
class NodeLists {
 public:
  /// A node's list, as far as it is filled.
  struct Range {
    const T* first;
    const T* last;
    const T* begin() const { return first; }
    const T* end() const { return last; }
    std::size_t size() const { return static_cast<std::size_t>(last - first); }
    bool empty() const { return first == last; }
    const T& operator[](std::size_t i) const { return first[i]; }
    const T& front() const { return *first; }
  };
  /// Room for count[v] items in node v's list; each starts empty.
  explicit NodeLists(const std::vector<std::uint32_t>& count) : start_(count.size() + 1, 0) {
    for (std::size_t v = 0; v < count.size(); ++v) start_[v + 1] = start_[v] + count[v];
    fill_.assign(start_.begin(), start_.end() - 1);
    items_.resize(start_.back());
  }
  void push(std::size_t v, const T& item) { items_[fill_[v]++] = item; }
  /// Sorts node v's list and drops its repeats.
  void sort_unique(std::size_t v) {
    T* first = items_.data() + start_[v];
    T* last = items_.data() + fill_[v];
    std::sort(first, last);
    fill_[v] = static_cast<std::size_t>(std::unique(first, last) - items_.data());
  }
  Range operator[](std::size_t v) const {
    return {items_.data() + start_[v], items_.data() + fill_[v]};
  }
  std::size_t size() const { return fill_.size(); }

 private:
  std::vector<std::size_t> start_, fill_;
  std::vector<T> items_;
};

using QuadsAt = NodeLists<std::uint32_t>;

/// Which nodes a sweep may pass over: what a sweep does at node v depends on the positions of
/// v and of the other nodes of its quads (its ring) only, so a node whose last visit left it
/// where it was, and none of whose ring has moved since, would do the same again: nothing.
/// Skipping it changes no result, to the last bit.
class Settled {
 public:
  Settled(std::size_t n,
          const QuadsAt& around,
          const std::vector<std::array<std::uint32_t, 4>>& quads)
      : start_(n + 1, 0), changed_(n, 0), settled_(n, 0) {
    std::vector<std::uint32_t> r;
    for (std::uint32_t v = 0; v < n; ++v) {
      r.clear();
      for (std::uint32_t q : around[v])
        for (std::uint32_t u : quads[q])
          if (u != v) r.push_back(u);
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
      ring_.insert(ring_.end(), r.begin(), r.end());
      start_[v + 1] = static_cast<std::uint32_t>(ring_.size());
    }
  }
  /// True when a visit of v would leave every node where it is.
  bool idle(std::uint32_t v) const {
    const std::uint64_t t = settled_[v];
    if (t == 0 || changed_[v] >= t) return false;
    for (std::uint32_t i = start_[v]; i < start_[v + 1]; ++i)
      if (changed_[ring_[i]] >= t) return false;
    return true;
  }
  /// After a visit of v: whether it moved v (any bit of its position). `stamp` orders the
  /// visits (from 1, rising along the sweeps' order): idle() compares only stamps, so the
  /// visits of one phase of a SweepSchedule may record theirs at once (each its own node's).
  void visited(std::uint32_t v, bool moved, std::uint64_t stamp) {
    if (moved) {
      changed_[v] = stamp;
      settled_[v] = 0;
    } else {
      settled_[v] = stamp;
    }
  }

 private:
  std::vector<std::uint32_t> start_, ring_;
  std::vector<std::uint64_t> changed_, settled_;
};

bool same_bits(Vec2 a, Vec2 b) { return std::memcmp(&a, &b, sizeof(Vec2)) == 0; }

/// How many of `quads` each of n nodes is in: the per-node lists are sized by it and so
/// allocated once (the relaxations build them for every template tried and every cavity).
std::vector<std::uint32_t> quad_counts(std::size_t n,
                                       const std::vector<std::array<std::uint32_t, 4>>& quads) {
  std::vector<std::uint32_t> count(n, 0);
  for (const auto& x : quads)
    for (std::uint32_t v : x) ++count[v];
  return count;
}

/// Per node of n, the quads it is a corner of (in quad order; twice for a node that is two
/// corners of one quad).
QuadsAt quads_at_nodes(std::size_t n, const std::vector<std::array<std::uint32_t, 4>>& quads) {
  QuadsAt around(quad_counts(n, quads));
  for (std::uint32_t q = 0; q < quads.size(); ++q)
    for (std::uint32_t v : quads[q]) around.push(v, q);
  return around;
}

/// The sweeps of the node movers: up to `iterations` passes over the nodes, each visiting
/// every node that is not fixed, is in a quad, and is not idle (Settled: none of its ring
/// moved since its last visit left it where it was); in index order, or in the order of
/// `schedule` when it has one, its groups of a phase at once (SweepSchedule). `visit(v)` moves
/// v or leaves it and returns true when the pass should count as progress; a pass without
/// progress is the last. `visit` may run on several threads at once, at nodes of different
/// groups: what it writes besides pos[v] (scratch) must be its thread's own.
template <class Visit>
void sweep_nodes(std::vector<Vec2>& pos,
                 const std::vector<bool>& fixed,
                 const QuadsAt& around,
                 const std::vector<std::array<std::uint32_t, 4>>& quads,
                 int iterations,
                 const SweepSchedule* schedule,
                 Visit&& visit) {
  const std::size_t n = pos.size();
  Settled settled_nodes(n, around, quads);
  // A visit's stamp: its pass, then the node's place in the pass's order.
  const auto visit_node = [&](std::uint32_t v, std::uint64_t stamp) {
    if (fixed[v] || around[v].empty() || settled_nodes.idle(v)) return false;
    const Vec2 start = pos[v];
    const bool progress = visit(v);
    settled_nodes.visited(v, !same_bits(pos[v], start), stamp);
    return progress;
  };
  if (schedule == nullptr || schedule->empty()) {
    for (int it = 0; it < iterations; ++it) {
      const std::uint64_t base = static_cast<std::uint64_t>(it) * (n + 1) + 1;
      bool moved = false;
      for (std::uint32_t v = 0; v < n; ++v)
        if (visit_node(v, base + v)) moved = true;
      if (!moved) break;
    }
    return;
  }
  std::vector<std::uint32_t> place(n, 0);
  std::uint32_t next = 0;
  for (const auto* groups : {&schedule->blocks, &schedule->seams})
    for (const auto& group : *groups)
      for (std::uint32_t v : group) place[v] = next++;
  for (int it = 0; it < iterations; ++it) {
    const std::uint64_t base = static_cast<std::uint64_t>(it) * (n + 1) + 1;
    bool moved = false;
    for (const auto* groups : {&schedule->blocks, &schedule->seams}) {
      std::vector<char> progress(groups->size(), 0);
      parallel_for(groups->size(), [&](std::size_t g) {
        for (std::uint32_t v : (*groups)[g])
          if (visit_node(v, base + place[v])) progress[g] = 1;
      });
      moved = moved || std::find(progress.begin(), progress.end(), 1) != progress.end();
    }
    if (!moved) break;
  }
}

/// Which of quality.md's midline measures the quad p0..p3 fails: bit 1 skew >= 30 degrees
/// (the acute angle between the midlines at most 60: |cos| >= 1/2), bit 2 aspect ratio >= 5.
unsigned midline_faults(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3) {
  const Vec2 d1 = 0.5 * ((p1 + p2) - (p3 + p0)), d2 = 0.5 * ((p2 + p3) - (p0 + p1));
  const double s1 = dot(d1, d1), s2 = dot(d2, d2), c = dot(d1, d2);  // squares: no hypot
  constexpr double kAspect2 = QualityThresholds::kAspectRatio * QualityThresholds::kAspectRatio;
  unsigned faults = 0;
  if (c * c >= 0.25 * s1 * s2) faults |= 1u;
  if (std::max(s1, s2) >= kAspect2 * std::min(s1, s2)) faults |= 2u;
  return faults;
}

}  // namespace

SweepSchedule sweep_schedule(std::size_t n,
                             const std::vector<bool>& fixed,
                             const std::vector<std::array<std::uint32_t, 4>>& quads) {
  const QuadsAt around = quads_at_nodes(n, quads);
  const auto movable = [&](std::uint32_t v) { return !fixed[v] && !around[v].empty(); };
  std::size_t count = 0;
  for (std::uint32_t v = 0; v < n; ++v)
    if (movable(v)) ++count;
  const std::size_t blocks = std::min(kSweepBlocks, count / kSweepBlockNodes);
  if (blocks < 2) return {};
  // Levels breadth-first, each component after the last (a level apart: they share no quad),
  // from the node a search from its lowest-numbered node reaches last: levels across the
  // component's longest way are narrow, and so are the seams.
  constexpr std::uint32_t kUnset = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> level(n, kUnset), queue;
  const auto search = [&](std::uint32_t from, std::uint32_t first) {
    level[from] = first;
    queue.assign(1, from);
    for (std::size_t head = 0; head < queue.size(); ++head) {
      const std::uint32_t v = queue[head];
      for (std::uint32_t q : around[v])
        for (std::uint32_t u : quads[q])
          if (level[u] == kUnset) {
            level[u] = level[v] + 1;
            queue.push_back(u);
          }
    }
  };
  std::uint32_t levels = 0;
  for (std::uint32_t s = 0; s < n; ++s) {
    if (level[s] != kUnset || around[s].empty()) continue;
    search(s, 0);
    const std::uint32_t far = queue.back();
    for (std::uint32_t v : queue) level[v] = kUnset;
    search(far, levels);
    levels = level[queue.back()] + 2;
  }
  std::vector<std::size_t> per_level(levels, 0);
  for (std::uint32_t v = 0; v < n; ++v)
    if (movable(v)) ++per_level[level[v]];
  // Cut before level c once the levels below hold the next block's share of the nodes, with
  // kSweepBlockLevels levels since the last cut and before the end.
  std::vector<std::uint32_t> cuts;
  std::size_t below = 0;
  for (std::uint32_t c = 1; c < levels && cuts.size() + 1 < blocks; ++c) {
    below += per_level[c - 1];
    const std::uint32_t last = cuts.empty() ? 0 : cuts.back();
    if (below * blocks >= (cuts.size() + 1) * count && c - last >= kSweepBlockLevels &&
        levels - c >= kSweepBlockLevels)
      cuts.push_back(c);
  }
  if (cuts.empty()) return {};
  SweepSchedule schedule;
  schedule.blocks.resize(cuts.size() + 1);
  schedule.seams.resize(cuts.size());
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!movable(v)) continue;
    // The first cut above v's level: v is in the block below it, or in its seam.
    const auto above = static_cast<std::size_t>(
        std::upper_bound(cuts.begin(), cuts.end(), level[v]) - cuts.begin());
    if (above < cuts.size() && level[v] + 1 == cuts[above])
      schedule.seams[above].push_back(v);
    else if (above > 0 && level[v] == cuts[above - 1])
      schedule.seams[above - 1].push_back(v);
    else
      schedule.blocks[above].push_back(v);
  }
  return schedule;
}

std::size_t keep_worst(std::vector<Vec2>& pos,
                       const std::vector<Vec2>& before,
                       const std::vector<std::array<std::uint32_t, 4>>& quads) {
  const auto jacobian = [&](const std::vector<Vec2>& at, const std::array<std::uint32_t, 4>& q) {
    return settled(min_scaled_jacobian(at[q[0]], at[q[1]], at[q[2]], at[q[3]]));
  };
  double floor = kKeepWorstAbove;
  for (const auto& q : quads) floor = std::min(floor, jacobian(before, q));
  std::size_t put_back = 0;
  // Each round puts back the nodes of every quad below the floor; a node put back stays, so
  // at worst every node is where it was (every quad at or above the floor) and it ends.
  for (bool again = true; again;) {
    again = false;
    for (const auto& q : quads) {
      if (jacobian(pos, q) >= floor) continue;
      for (std::uint32_t v : q)
        if (!same_bits(pos[v], before[v])) {
          pos[v] = before[v];
          ++put_back;
          again = true;
        }
    }
  }
  return put_back;
}

void smooth_nodes(std::vector<Vec2>& pos,
                  const std::vector<bool>& fixed,
                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                  int iterations,
                  const SweepSchedule* schedule) {
  const std::size_t n = pos.size();
  std::vector<std::uint32_t> count = quad_counts(n, quads);
  QuadsAt around(count);
  for (std::uint32_t& c : count) c *= 2;  // a node's edges: two per quad at it, before repeats go
  QuadsAt nbr(count);
  for (std::uint32_t q = 0; q < quads.size(); ++q) {
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t a = quads[q][k], b = quads[q][(k + 1) % 4];
      nbr.push(a, b);
      nbr.push(b, a);
      around.push(a, q);
    }
  }
  for (std::size_t v = 0; v < n; ++v) nbr.sort_unique(v);
  auto jac = [&](std::uint32_t q) {
    const auto& x = quads[q];
    return min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]);
  };
  // Every quad's value at the present positions, updated as its nodes move.
  std::vector<double> value(quads.size());
  for (std::uint32_t q = 0; q < quads.size(); ++q) value[q] = jac(q);
  // How close a node may come to a neighbour (kSmoothEdgeFloor), squared.
  std::vector<double> floor2(n, 0.0);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (fixed[v]) continue;  // never moved: its floor is never read
    double shortest = std::numeric_limits<double>::infinity();
    for (std::uint32_t w : nbr[v]) shortest = std::min(shortest, distance(pos[v], pos[w]));
    if (std::isfinite(shortest))
      floor2[v] = kSmoothEdgeFloor * shortest * kSmoothEdgeFloor * shortest;
  }
  sweep_nodes(pos, fixed, around, quads, iterations, schedule, [&](std::uint32_t v) {
    thread_local std::vector<double> t_trial;  // its thread's own: sweep_nodes
    std::vector<double>& trial = t_trial;
    Vec2 avg{0.0, 0.0};
    for (std::uint32_t w : nbr[v]) avg = avg + pos[w];
    avg = (1.0 / static_cast<double>(nbr[v].size())) * avg;
    double before = std::numeric_limits<double>::infinity();
    for (std::uint32_t q : around[v]) before = std::min(before, value[q]);
    for (std::uint32_t w : nbr[v]) {
      const Vec2 d = avg - pos[w];
      if (dot(d, d) < floor2[v]) return false;
    }
    const Vec2 old = pos[v];
    pos[v] = avg;
    // Below min(b, kSmoothFloor) the move is refused (settled(x) <= x + 1e-9 for |x| <= 1):
    // the quads after the one that goes below it need not be computed.
    const double b = settled(before);
    const double give_up = std::min(b, kSmoothFloor) - 1e-8;
    double after = std::numeric_limits<double>::infinity();
    trial.clear();
    for (std::uint32_t q : around[v]) {
      trial.push_back(jac(q));
      after = std::min(after, trial.back());
      if (after < give_up) break;
    }
    // Accept when the worst quad around v does not get worse (or stays above the floor).
    const double a = settled(after);
    if (a >= std::min(b, kSmoothFloor) && (a >= b || a >= kSmoothFloor) &&
        keeps_sign(before, after)) {
      for (std::size_t i = 0; i < trial.size(); ++i) value[around[v][i]] = trial[i];
      return old != avg;
    }
    pos[v] = old;
    return false;
  });
}

void untangle_nodes(std::vector<Vec2>& pos,
                    const std::vector<bool>& fixed,
                    const std::vector<std::array<std::uint32_t, 4>>& quads,
                    int iterations,
                    double target,
                    double min_edge_fraction,
                    bool strict,
                    const SweepSchedule* schedule) {
  const std::size_t n = pos.size();
  const QuadsAt around = quads_at_nodes(n, quads);
  // Scaled Jacobians do not see size: a node may not come closer to a neighbour than
  // kMinEdgeFraction x the mean length of its edges before the search, or quads would shrink
  // to points.
  std::vector<double> floor_len(n, 0.0);
  for (std::uint32_t v = 0; v < n; ++v) {
    if (fixed[v]) continue;  // never searched: its floor is never read
    double sum = 0.0;
    int count = 0;
    for (std::uint32_t q : around[v])
      for (std::size_t k = 0; k < 4; ++k)
        if (quads[q][k] == v) {
          sum += distance(pos[v], pos[quads[q][(k + 1) % 4]]);
          ++count;
        }
    floor_len[v] = count ? min_edge_fraction * sum / count : 0.0;
  }
  std::vector<double> floor2(n);  // squared, for the comparisons in the search's inner loop
  for (std::uint32_t v = 0; v < n; ++v) floor2[v] = floor_len[v] * floor_len[v];
  const auto squared_distance = [](Vec2 a, Vec2 b) { return dot(a - b, a - b); };
  // The worst quad round v, or -infinity when an edge at v is below its floor: a node whose
  // edge is already that short takes any position that lengthens it, within `floor_j` below.
  // Settled (kJacobianGrain) for the comparisons; `raw` gets the unrounded worst.
  // The general form, for a node that is more than one corner of a quad (a degenerate quad).
  auto worst_at = [&](std::uint32_t v, double& raw) {
    double w = std::numeric_limits<double>::infinity();
    for (std::uint32_t q : around[v]) {
      const auto& x = quads[q];
      for (std::size_t k = 0; k < 4; ++k)
        if (x[k] == v && (squared_distance(pos[v], pos[x[(k + 1) % 4]]) < floor2[v] ||
                          squared_distance(pos[v], pos[x[(k + 3) % 4]]) < floor2[v]))
          return -std::numeric_limits<double>::infinity();
      w = std::min(w, min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]));
    }
    raw = w;
    return settled(w);
  };
  // The usual form: v is one corner of each quad round it, and while v moves (its neighbours
  // stay) each quad's corner opposite v keeps its value, and the lengths of the two edges
  // there. `ring` holds, per quad round v, the nodes after, opposite and before v, those two
  // squared lengths and that corner's value; the other three corners are computed as
  // min_scaled_jacobian does, term for term, so the values are the same to the last bit.
  struct Opposite {
    Vec2 a, c, d;     // the quad's nodes after v, opposite v, before v
    double ca2, cd2;  // |c - a|^2, |c - d|^2
    double jc;        // the scaled Jacobian of the corner at c
  };
  // Scratch of a visit, its thread's own (visits may run on several threads at once:
  // sweep_nodes); each visit binds them once (a thread_local is looked up at every use).
  thread_local std::vector<Opposite> t_ring;
  thread_local std::vector<Vec2> t_edges;  // the edges at a node, for its step
  // The worst corner round v at p (min over its quads, as worst_at's raw), `short_edge` set
  // when an edge at v is below its floor. With `give_up` finite, it may stop as soon as the
  // worst so far is below it (then the value returned is only known to be below it).
  // `stopped` is set when it stopped so (or at a short edge): the candidate cannot be taken.
  const auto worst_of = [&](std::vector<Opposite>& ring, Vec2 p, double fl2, double give_up,
                            bool& short_edge, bool& stopped) {
    double w = std::numeric_limits<double>::infinity();
    short_edge = false;
    stopped = false;
    const bool may_stop = give_up > -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Opposite& o = ring[i];
      const Vec2 ea = o.a - p, ed = o.d - p, pa = p - o.a, pd = p - o.d;
      const double la = dot(ea, ea), ld = dot(ed, ed);
      if (la < fl2 || ld < fl2) short_edge = true;
      if (!(short_edge && may_stop)) {
        w = std::min(w, corner_of_edges(ea, ed, la * ld));  // at v: e1 = a - v, e0 = d - v
        w = std::min(w,
                     corner_of_edges(o.c - o.a, pa, o.ca2 * la));  // at a: e1 = c - a, e0 = v - a
        w = std::min(w,
                     corner_of_edges(pd, o.c - o.d, ld * o.cd2));  // at d: e1 = v - d, e0 = c - d
        w = std::min(w, o.jc);
      }
      if (w < give_up || (short_edge && may_stop)) {
        // This quad first next time: the search's candidates are near one another, and the
        // quad that stopped one most likely stops the next (the order changes no minimum).
        std::swap(ring[i], ring.front());
        stopped = true;
        return w;
      }
    }
    return w;
  };
  static const Vec2 kDirs[8] = {{1, 0},  {0.7071, 0.7071},   {0, 1},  {-0.7071, 0.7071},
                                {-1, 0}, {-0.7071, -0.7071}, {0, -1}, {0.7071, -0.7071}};
  // Strict (the final smoothing's second stage): a move may not stretch a quad round v to an
  // aspect ratio that quality.md calls bad (midline_faults) when it was not: raising the
  // worst corner past 0.6 made cgal_Detmier's aspect >= 5 go 0 -> 1.4%.
  // Whether moving v from `from` to `to` stretches a quad round it. pos[v] is put back as it
  // was: the search of a node that is twice in a quad has already set it to the candidate.
  const auto stretches = [&](std::uint32_t v, Vec2 from, Vec2 to) {
    const Vec2 was = pos[v];
    bool stretched = false;
    for (std::uint32_t q : around[v]) {
      const auto& x = quads[q];
      pos[v] = from;
      const bool now = midline_faults(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]) & 2u;
      pos[v] = to;
      const bool then = midline_faults(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]) & 2u;
      if (then && !now) {
        stretched = true;
        break;
      }
    }
    pos[v] = was;
    return stretched;
  };
  // One visit of node v: the compass search from where it is. True when it raised v's worst.
  const auto search_node = [&](std::uint32_t v) {
    std::vector<Opposite>& ring = t_ring;
    std::vector<Vec2>& edges = t_edges;
    double raw = 0.0;
    bool moved = false;
    bool simple = true;
    ring.clear();
    for (std::uint32_t q : around[v]) {
      const auto& x = quads[q];
      std::size_t k = 0, count = 0;
      for (std::size_t i = 0; i < 4; ++i)
        if (x[i] == v) {
          k = i;
          ++count;
        }
      if (count != 1) {
        simple = false;
        break;
      }
      Opposite o;
      o.a = pos[x[(k + 1) % 4]];
      o.c = pos[x[(k + 2) % 4]];
      o.d = pos[x[(k + 3) % 4]];
      const Vec2 e1 = o.d - o.c, e0 = o.a - o.c;  // the corner at c: e1 to d, e0 to a
      o.ca2 = dot(o.c - o.a, o.c - o.a);
      o.cd2 = dot(o.c - o.d, o.c - o.d);
      o.jc = corner_of_edges(e1, e0, dot(e1, e1) * dot(e0, e0));
      ring.push_back(o);
    }
    // `before`: the worst quad round v now, whatever its edges; `current` as worst_at.
    double current = 0.0, before = 0.0;
    if (simple) {
      bool short_edge = false, stopped = false;
      before = worst_of(ring, pos[v], floor2[v], -std::numeric_limits<double>::infinity(),
                        short_edge, stopped);
      current = short_edge ? -std::numeric_limits<double>::infinity() : settled(before);
    } else {
      current = worst_at(v, raw);
      before = std::numeric_limits<double>::infinity();
      for (std::uint32_t q : around[v]) {
        const auto& x = quads[q];
        before = std::min(before, min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]));
      }
    }
    if (current >= target) return false;
    if (simple) {
      // A candidate's worst is at most the least corner opposite v, which no move of v
      // changes: when that is no better than v's worst now, no candidate can be taken
      // (settled is monotone), and the search would try its 48 or more in vain.
      double fixed_worst = std::numeric_limits<double>::infinity();
      for (const Opposite& o : ring) fixed_worst = std::min(fixed_worst, o.jc);
      if (settled(fixed_worst) <= current) return false;
    }
    // Step: a quarter of the shortest edge at v.
    edges.clear();
    for (std::uint32_t q : around[v])
      for (std::size_t k = 0; k < 4; ++k)
        if (quads[q][k] == v) {
          edges.push_back(pos[v] - pos[quads[q][(k + 1) % 4]]);
          edges.push_back(pos[v] - pos[quads[q][(k + 3) % 4]]);
        }
    double step = shortest_norm(edges);
    // No move may take the worst quad round v below min(its value now, kSmoothFloor), the
    // floor of the other sweeps. Binding only when v starts with an edge below its floor
    // (current is then -infinity): before, any position with long enough edges was
    // "better", however inverted its quads (tray_ribs, adaptive, dtheta 1: a quad turned
    // clockwise in floor_ne).
    const double floor_j = strict ? settled(before) : std::min(settled(before), kSmoothFloor);
    step *= 0.25;
    Vec2 ref{1.0, 0.0};
    for (std::size_t k = 0; k < 4; ++k)
      if (quads[around[v].front()][k] == v) {
        const Vec2 e = pos[quads[around[v].front()][(k + 1) % 4]] - pos[v];
        const double length = norm(e);
        if (length > 0.0) ref = (1.0 / length) * e;
      }
    // A candidate is taken only when its settled worst w > best + 1e-12 and w >= floor_j;
    // settled(x) <= x + 1e-9 for the values here (|x| <= 1), so a raw worst below
    // max(best + 1e-12, floor_j) - kGiveUpMargin cannot be taken and its search may stop.
    constexpr double kGiveUpMargin = 1e-8;
    // Directions turn with the node's first edge, not with the frame: every pose of a part
    // relaxes the same way.
    Vec2 dirs[8];
    for (std::size_t i = 0; i < 8; ++i) {
      const Vec2 k = kDirs[i];
      dirs[i] = {k.x * ref.x - k.y * ref.y, k.x * ref.y + k.y * ref.x};
    }
    for (int shrink = 0; shrink < 6 && step > 0.0; ++shrink, step *= 0.5) {
      bool better = true;
      for (int walk = 0; better && walk < 16; ++walk) {
        better = false;
        const Vec2 here = pos[v];
        Vec2 best_pos = here;
        double best = current;
        for (const Vec2& d : dirs) {
          const Vec2 p = here + step * d;
          double w = 0.0;
          if (simple) {
            bool short_edge = false, stopped = false;
            const double give_up = std::max(best + 1e-12, floor_j) - kGiveUpMargin;
            raw = worst_of(ring, p, floor2[v], give_up, short_edge, stopped);
            w = short_edge || stopped ? -std::numeric_limits<double>::infinity() : settled(raw);
          } else {
            pos[v] = p;
            w = worst_at(v, raw);
          }
          if (w > best + 1e-12 && w >= floor_j && keeps_sign(before, raw) &&
              (!strict || !stretches(v, here, p))) {
            best = w;
            best_pos = p;
          }
        }
        pos[v] = best_pos;
        if (best > current + 1e-9) {
          current = best;
          better = true;
          moved = true;
        }
      }
    }
    return moved;
  };
  sweep_nodes(pos, fixed, around, quads, iterations, schedule, search_node);
}

void optimize_nodes(std::vector<Vec2>& pos,
                    const std::vector<bool>& fixed,
                    const std::vector<std::array<std::uint32_t, 4>>& quads,
                    int iterations,
                    const SweepSchedule* schedule) {
  const std::size_t n = pos.size();
  // The corners whose triangle moves with node v: in every quad round v, the corner at v and
  // its two neighbours.
  struct Corner {
    std::uint32_t q;
    std::size_t k;
  };
  std::vector<std::uint32_t> count = quad_counts(n, quads);
  QuadsAt around(count);
  for (std::uint32_t& c : count) c *= 3;
  NodeLists<Corner> corners(count);
  for (std::uint32_t q = 0; q < quads.size(); ++q)
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t v = quads[q][k];
      around.push(v, q);
      for (std::size_t d : {0u, 1u, 3u}) corners.push(v, {q, (k + d) % 4});
    }
  // Target lengths: every edge as long as it is now. Measured against them, a corner's ideal
  // is a right angle between edges of their present lengths, so a graded or stretched mesh
  // keeps its sizes and only the angles improve (against a unit square instead, the plate's
  // ring round its hole was skewed to even its edges: min scaled Jacobian 0.78 -> 0.65).
  std::vector<std::array<double, 4>> target(quads.size());  // edge k: from corner k to k + 1
  for (std::size_t q = 0; q < quads.size(); ++q)
    for (std::size_t k = 0; k < 4; ++k)
      target[q][k] = distance(pos[quads[q][k]], pos[quads[q][(k + 1) % 4]]);
  auto jac = [&](std::uint32_t q) {
    const auto& x = quads[q];
    return min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]);
  };
  // The objective at v: the sum of the condition numbers (|a|^2 + |b|^2) / (2 a x b) of the
  // corners it is part of, a and b the corner's edges over their target lengths (1 for the
  // ideal corner, infinite as it flattens). Each term is a quadratic over a positive affine
  // function of v, so the sum is convex where it is finite and one Newton step goes most of
  // the way; gradient and Hessian need no frame, so every pose moves the same.
  auto objective = [&](std::uint32_t v, Vec2* grad, double* hess) {
    double f = 0.0;
    if (grad) *grad = {0.0, 0.0};
    if (hess) hess[0] = hess[1] = hess[2] = 0.0;
    for (const Corner& c : corners[v]) {
      const auto& x = quads[c.q];
      const std::uint32_t p = x[c.k], nx = x[(c.k + 1) % 4], pv = x[(c.k + 3) % 4];
      const double wa = 1.0 / target[c.q][c.k], wb = 1.0 / target[c.q][(c.k + 3) % 4];
      const Vec2 a = wa * (pos[nx] - pos[p]), b = wb * (pos[pv] - pos[p]);
      const double d = cross(a, b);
      if (!(d > 0.0)) return std::numeric_limits<double>::infinity();
      const double num = dot(a, a) + dot(b, b);
      f += 0.5 * num / d;
      if (!grad) continue;
      // a and b move with v at rates sa, sb (+-their weights, or 0); d is affine in v.
      const double sa = wa * (v == p ? -1.0 : v == nx ? 1.0 : 0.0);
      const double sb = wb * (v == p ? -1.0 : v == pv ? 1.0 : 0.0);
      const Vec2 gn = 2.0 * (sa * a + sb * b);
      const Vec2 gd = sa * Vec2{b.y, -b.x} + sb * Vec2{-a.y, a.x};
      *grad = *grad + (0.5 / (d * d)) * (d * gn - num * gd);
      // H = hn / (2d) I - (gn gd' + gd gn') / (2d^2) + num gd gd' / d^3
      const double hn = 2.0 * (sa * sa + sb * sb);
      const double i2 = 0.5 / (d * d), i3 = num / (d * d * d);
      hess[0] += 0.5 * hn / d - 2.0 * i2 * gn.x * gd.x + i3 * gd.x * gd.x;
      hess[1] += -i2 * (gn.x * gd.y + gd.x * gn.y) + i3 * gd.x * gd.y;
      hess[2] += 0.5 * hn / d - 2.0 * i2 * gn.y * gd.y + i3 * gd.y * gd.y;
    }
    return f;
  };
  // Whether an edge at v is now shorter than kOptimizeEdgeFloor x its target (the condition
  // numbers do not see size, and a step may close an edge that is already tiny).
  const auto shortens = [&](std::uint32_t v) {
    for (std::uint32_t q : around[v])
      for (std::size_t k = 0; k < 4; ++k) {
        if (quads[q][k] != v) continue;
        const std::uint32_t next = quads[q][(k + 1) % 4], prev = quads[q][(k + 3) % 4];
        if (distance(pos[v], pos[next]) < kOptimizeEdgeFloor * target[q][k] ||
            distance(pos[v], pos[prev]) < kOptimizeEdgeFloor * target[q][(k + 3) % 4])
          return true;
      }
    return false;
  };
  // One visit of node v: a Newton step, halved until it is taken or too small.
  const auto visit = [&](std::uint32_t v) {
    Vec2 g;
    double h[3];
    const double f0 = objective(v, &g, h);
    if (!std::isfinite(f0)) return false;  // an inverted corner: the untangler's work
    const double det = h[0] * h[2] - h[1] * h[1];
    if (!(det > 0.0) || !(h[0] > 0.0)) return false;
    const Vec2 step{-(h[2] * g.x - h[1] * g.y) / det, -(h[0] * g.y - h[1] * g.x) / det};
    // The Newton decrement -g.step / 2 is the decrease the step promises (dimensionless, the
    // same in every pose and at every scale): below kOptimizeTolerance the node stays.
    if (-0.5 * dot(g, step) < kOptimizeTolerance) return false;
    double before = std::numeric_limits<double>::infinity();
    for (std::uint32_t q : around[v]) before = std::min(before, jac(q));
    const Vec2 old = pos[v];
    bool kept = false;
    // Halve the step until the objective falls and no quad round v goes below the floor.
    for (double t = 1.0; t > 1e-3 && !kept; t *= 0.5) {
      pos[v] = old + t * step;
      if (pos[v] == old) break;
      if (shortens(v)) continue;
      if (!(objective(v, nullptr, nullptr) < f0)) continue;
      double after = std::numeric_limits<double>::infinity();
      for (std::uint32_t q : around[v]) after = std::min(after, jac(q));
      kept = settled(after) >= std::min(settled(before), kSmoothFloor) && keeps_sign(before, after);
    }
    if (!kept) pos[v] = old;
    return kept;
  };
  sweep_nodes(pos, fixed, around, quads, iterations, schedule, visit);
}

std::vector<double> pinned_angles(const std::vector<Vec2>& pos,
                                  const std::vector<bool>& fixed,
                                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                                  const std::vector<bool>* alive,
                                  std::vector<std::uint32_t>* counts) {
  std::vector<double> angle(pos.size(), 0.0);
  if (counts) counts->assign(pos.size(), 0);
  for (std::size_t q = 0; q < quads.size(); ++q) {
    if (alive && !(*alive)[q]) continue;
    const auto& x = quads[q];
    for (std::size_t k = 0; k < 4; ++k) {
      if (!fixed[x[k]]) continue;
      angle[x[k]] += interior_angle({pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]}, k);
      if (counts) ++(*counts)[x[k]];
    }
  }
  return angle;
}

double outline_bound(const std::vector<Vec2>& pos,
                     const std::vector<bool>& fixed,
                     const std::vector<std::array<std::uint32_t, 4>>& quads,
                     const std::vector<bool>* alive) {
  std::vector<std::uint32_t> count;
  const std::vector<double> angle = pinned_angles(pos, fixed, quads, alive, &count);
  double bound = 1.0;
  for (std::size_t v = 0; v < pos.size(); ++v)
    if (count[v] > 0) bound = std::min(bound, std::sin(angle[v] / count[v]));
  return bound;
}

void untaper_nodes(std::vector<Vec2>& pos,
                   const std::vector<bool>& fixed,
                   const std::vector<std::array<std::uint32_t, 4>>& quads,
                   int iterations,
                   const SweepSchedule* schedule) {
  const std::size_t n = pos.size();
  const QuadsAt around = quads_at_nodes(n, quads);
  // The quad across each edge of each quad (kNone on the boundary).
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::array<std::uint32_t, 4>> across(quads.size(), {kNone, kNone, kNone, kNone});
  for (std::uint32_t q = 0; q < quads.size(); ++q)
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t a = quads[q][k], b = quads[q][(k + 1) % 4];
      for (std::uint32_t w : around[a])
        if (w != q && std::find(quads[w].begin(), quads[w].end(), b) != quads[w].end())
          across[q][k] = w;
    }
  const auto area = [&](std::uint32_t q) {
    const auto& x = quads[q];
    return 0.5 * cross(pos[x[2]] - pos[x[0]], pos[x[3]] - pos[x[1]]);
  };
  // Loose (kLooseUntaperBelow): the outline forces a worse corner than the bar anyway; each
  // quad's worst corner when the sweeps began bounds how far a move may lower it.
  const double bound = settled(outline_bound(pos, fixed, quads));
  const bool loose = bound < settled(kLooseUntaperBelow);
  std::vector<double> first;
  if (loose)
    for (const auto& x : quads)
      first.push_back(min_scaled_jacobian(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]));
  const double slack = loose ? kLooseUntaperSlack : kUntaperJacobianSlack;
  // Per quad round the node being moved: its faults before the move (scratch, its thread's
  // own: sweep_nodes; a visit binds it once).
  thread_local std::vector<unsigned> t_faults;
  // What a move must stay within to be taken (try_move's tests that only get worse as the
  // quads round v are added up: the sum, the tapered count, the worst quad, the area ratio).
  struct Bar {
    double sum;     ///< the sum must end below this
    int tapered;    ///< at most this many tapered (when descending; else any)
    double worst;   ///< settled worst no lower than this
    bool positive;  ///< the worst must stay positive (keeps_sign)
    double ratio;   ///< area ratio at most this
  };
  // The sum of (1 - taper)^2 over the quads round v, their worst scaled Jacobian and the sum
  // of their scaled Jacobians, the largest area ratio between one of them and a quad across
  // an edge of it, and how many of them are tapered (quality.md: taper <= 0.8); with `faults`
  // filled, infinity when a quad has a fault it did not have. With a `bar`, infinity as soon
  // as the quads so far fail it (each of its measures only gets worse with more quads: the
  // move would not be taken, and the ones that are taken are measured in full).
  const auto measure = [&](std::vector<unsigned>& faults, std::uint32_t v, double& worst,
                           double& jacobians, double& ratio, int& tapered, const Bar* bar) {
    double sum = 0.0;
    worst = std::numeric_limits<double>::infinity();
    jacobians = 0.0;
    ratio = 1.0;
    tapered = 0;
    constexpr double kFails = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < around[v].size(); ++i) {
      const std::uint32_t q = around[v][i];
      const auto& x = quads[q];
      const Vec2 a = pos[x[0]], b = pos[x[1]], c = pos[x[2]], d = pos[x[3]];
      const unsigned f = midline_faults(a, b, c, d);
      if (faults.size() < around[v].size())
        faults.push_back(f);
      else if (f & ~faults[i])
        return kFails;
      const auto [taper, jq] = quad_taper_jacobian(a, b, c, d);
      if (taper <= QualityThresholds::kTaper) ++tapered;
      const double off = 1.0 - taper;
      sum += off * off;
      if (bar && (!(sum < bar->sum) || tapered > bar->tapered)) return kFails;
      worst = std::min(worst, jq);
      jacobians += jq;
      if (bar && (settled(worst) < bar->worst || (bar->positive && !(worst > 0.0)))) return kFails;
      const double aq = area(q);
      for (std::uint32_t w : across[q]) {
        if (w == kNone) continue;
        const double aw = area(w);
        if (aq > 0.0 && aw > 0.0) ratio = std::max(ratio, std::max(aq, aw) / std::min(aq, aw));
      }
      if (bar && ratio > bar->ratio) return kFails;
    }
    return sum;
  };
  // First the moves towards the parallelograms alone; then, from where they stop, with the
  // descent as well, and no move raising the count of tapered quads round the node. (With the
  // descent from the start, descents made before the first kind of move had settled held it
  // back: t_junction's tapered quads 12 -> 7, not 12 -> 1.)
  bool descend = false;
  const auto visit = [&](std::uint32_t v) {
    // Where v would make each quad round it a parallelogram (the node after it plus the
    // node before it minus the opposite node), averaged.
    Vec2 goal{0.0, 0.0};
    bool simple = true;
    for (std::uint32_t q : around[v]) {
      const auto& x = quads[q];
      std::size_t k = 0, count = 0;
      for (std::size_t i = 0; i < 4; ++i)
        if (x[i] == v) {
          k = i;
          ++count;
        }
      simple = simple && count == 1;
      goal = goal + (pos[x[(k + 1) % 4]] + pos[x[(k + 3) % 4]] - pos[x[(k + 2) % 4]]);
    }
    const Vec2 old = pos[v];
    // A node whose quads are all nearly parallelograms stays.
    simple = simple && std::any_of(around[v].begin(), around[v].end(), [&](std::uint32_t q) {
               const auto& x = quads[q];
               return quad_taper(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]) < kUntaperFrom;
             });
    if (simple) {
      goal = (1.0 / static_cast<double>(around[v].size())) * goal;
      std::vector<unsigned>& faults = t_faults;
      faults.clear();
      double worst_before = 0.0, jacobians_before = 0.0, ratio_before = 1.0;
      int tapered_before = 0;
      const double before =
          measure(faults, v, worst_before, jacobians_before, ratio_before, tapered_before, nullptr);
      const double ratio_cap = std::max(ratio_before, kUntaperAreaRatio);
      double worst_floor = settled(worst_before);
      if (loose) {
        double least = std::numeric_limits<double>::infinity();
        for (std::uint32_t q : around[v]) least = std::min(least, first[q]);
        worst_floor = std::min(
            worst_floor, settled(std::max({kLooseUntaperFloor, bound, least - kLooseUntaperDrop})));
      }
      const Bar bar{before - kUntaperGain,
                    descend ? tapered_before : std::numeric_limits<int>::max(), worst_floor,
                    worst_before > 0.0, ratio_cap};
      // Moves v to p when that passes every test; else leaves it where it was.
      const auto try_move = [&](Vec2 p) {
        pos[v] = p;
        double worst = 0.0, jacobians = 0.0, ratio = 1.0;
        int tapered = 0;
        const double after = measure(faults, v, worst, jacobians, ratio, tapered, &bar);
        if (after < before - kUntaperGain && (!descend || tapered <= tapered_before) &&
            settled(worst) >= worst_floor && keeps_sign(worst_before, worst) &&
            ratio <= ratio_cap && jacobians >= jacobians_before - slack)
          return true;
        pos[v] = old;
        return false;
      };
      const bool moved = try_move(lerp(old, goal, 1.0)) || try_move(lerp(old, goal, 0.5)) ||
                         try_move(lerp(old, goal, 0.25));
      // Where no such move passes and a quad round v is tapered, down the sum's gradient
      // (central differences): the parallelogram points of a node's quads pull apart where
      // they disagree (a kite beside a trapezoid), and their mean may help none of them.
      if (descend && !moved && tapered_before > 0) {
        double length = 0.0;
        std::size_t edges = 0;
        for (std::uint32_t q : around[v])
          for (std::uint32_t u : quads[q])
            if (u != v) {
              length += distance(pos[u], old);
              ++edges;
            }
        length /= static_cast<double>(edges);
        const auto sum_at = [&](Vec2 p) {
          pos[v] = p;
          double sum = 0.0;
          for (std::uint32_t q : around[v]) {
            const auto& x = quads[q];
            const double off = 1.0 - quad_taper(pos[x[0]], pos[x[1]], pos[x[2]], pos[x[3]]);
            sum += off * off;
          }
          pos[v] = old;
          return sum;
        };
        const double e = kUntaperDifference * length;
        const Vec2 slope{sum_at(old + Vec2{e, 0.0}) - sum_at(old - Vec2{e, 0.0}),
                         sum_at(old + Vec2{0.0, e}) - sum_at(old - Vec2{0.0, e})};
        const double steep = norm(slope);
        if (steep > 0.0)
          for (double step : kUntaperDescent)
            if (try_move(old - (step * length / steep) * slope)) break;
      }
    }
    return !same_bits(pos[v], old);
  };
  sweep_nodes(pos, fixed, around, quads, iterations, schedule, visit);
  descend = true;
  sweep_nodes(pos, fixed, around, quads, iterations, schedule, visit);
}

}  // namespace laytracks::mesher_detail
