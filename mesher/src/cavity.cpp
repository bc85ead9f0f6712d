// Cavity re-fill (docs/mesher.md, "Cavity re-fill"): after the edge flips, before the
// smoothing (whose result, unlike the templates' nodes, differs between poses). A face
// template sees one face; its worst quads are often where two faces meet badly, or at a
// B-Rep vertex on a nearly straight boundary that only one quad touches (a 170-degree corner:
// no relaxation can mend that, the node is fixed). Here the quads round such a quad, across
// face borders, are taken out as one polygon (a cavity: its boundary has an even edge count,
// as any union of quads has) and filled again by the face templates; the new quads are
// relaxed with the quads round the cavity, and kept only when their worst beats that of the
// old quads relaxed the same way. A last pass takes the stars of poles (interior nodes of many
// quads, where a quad's worst corner is) as cavities.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "fill.hpp"
#include "laytracks/mesher/build_quads.hpp"
#include "laytracks/mesher/quality.hpp"
#include "memo.hpp"
#include "patch_quads.hpp"
#include "regrid.hpp"

namespace laytracks {

using namespace mesher_detail;

namespace {

using Quad = std::array<std::uint32_t, 4>;

/// A re-fill is kept when the worst of its quads (and of the ring's that moved), relaxed, beats
/// the old quads' relaxed alike by this.
constexpr double kRefillGain = 0.02;
/// A pass tries the worst kRefillFirst + (the patch's quads / kRefillShare) quads below the
/// threshold, no more: the re-fills cost a millisecond or so each, most fail where the
/// worst quads are bound by the boundary, and the worst quads are what the re-fill is for.
constexpr std::size_t kRefillFirst = 32;
constexpr std::size_t kRefillShare = 50;
/// Passes over a patch; each after the first looks only near what the one before changed.
constexpr int kRefillPasses = 2;
/// Cavities of more boundary nodes than this are not tried (the templates are O(n^3)); a
/// pole's star (pole_plan) up to kMaxPoleCavityNodes.
constexpr std::size_t kMaxCavityNodes = 48;
constexpr std::size_t kMaxPoleCavityNodes = 96;
/// A cavity is relaxed by the final smoothing's sweeps (final_sweeps), at most kRefillSweeps
/// of each kind (the cavity is small).
constexpr int kRefillSweeps = 4;
/// Attempts evaluated in parallel at a time (when the patch's re-fill runs alone, and it has
/// at least kRefillParallelQuads quads: in a smaller patch the attempts of a batch read the
/// same nodes and most are evaluated again; l_shape's 203 quads: refill 0.003 s alone, 0.009 s
/// in batches).
constexpr std::size_t kRefillBatch = 8;
constexpr std::size_t kRefillParallelQuads = 500;
constexpr std::uint32_t kNew = 0xffffffffu;
/// Nodes of at least this many quads are poles: their star is a cavity of its own.
constexpr std::size_t kPoleValence = 6;
/// The pole pass also tries the cavities round a quad whose worst corner is a pinned node of
/// that quad alone, at more than this (lone_flat): a boundary vertex on a nearly straight
/// outline that one quad meets (sin 157.5 degrees = 0.383 on cgal_wheel_16_spokes at 0.8 x
/// its size, four of them beyond the first pass's limit of attempts; with two quads the vertex
/// has 0.98 at best). The pass tries no other quads (until session 28 it took the worst ones
/// and tried the poles among them). Off round values: a regular 12-gon's corners are 150
/// degrees exactly, and a threshold there would read them one way or the other by the pose.
constexpr double kLoneFlatAngle = 152.5 * kPi / 180.0;
/// Corners of a quad within this much of its least scaled Jacobian are all its worst
/// (worst_corners): far above the rounding between poses (1e-11 on the fuzz parts), far below
/// the differences the templates' shapes make.
constexpr double kWorstCornerTie = 1e-7;
/// Regrid (regrid_plan): round an irregular node, its quads and then the quads at their nodes,
/// out to kRegridRings rings of at most kRegridQuads quads, are its cavities (6 rings and 250
/// quads: taper <= 0.8 a tenth lower on the sets for 10% more time, and more worst corners
/// lower than higher); a fill's inner nodes are placed by kRegridSweeps harmonic sweeps before
/// the relaxation.
constexpr int kRegridRings = 4;
constexpr std::size_t kRegridQuads = 120;
constexpr int kRegridSweeps = 100;
/// A regrid may change the cavity's quad count by at most this factor either way (star_5 at
/// the uniform size: its centre's pole of 40 small quads became 20 large ones, the quads at
/// the centre twice as large as the rest).
constexpr double kRegridCountRatio = 1.5;
/// A regrid may take its cavity's worst corner below min(the old worst, the re-fill threshold)
/// by at most kRegridMostDrop, and not below the larger of kRegridLowFloor and the best worst
/// corner the patch's outline allows (outline_bound), when no more of the cavity's quads are
/// beyond the skew or aspect thresholds (session 44): where the outline forces a worse corner
/// anyway, the rings whose worst corner the regrid could not keep to the bit are gridded too
/// (cgal_wiggly_03_cgal: 42 quads, tapered 25 -> 12, worst 0.688 -> 0.680; 15.6% -> 12.2%
/// tapered in all), and elsewhere the mesh's worst corner is not traded.
constexpr double kRegridLowFloor = 0.6;
constexpr double kRegridMostDrop = 0.03;
/// A regrid cavity that holds every quad at a pinned node (the patch's outline there) may give
/// that node another count of quads: the k of 1 to 3 whose corners a / k (a the outline's
/// angle there) have the largest sine, where that sine beats the present count's by at least
/// kRecountGain (session 51). The outline's vertices keep the counts the rails gave them,
/// and a reflex corner of 270 degrees in two quads of 135, or a vertex of 150 degrees in one
/// quad, left every fill of the cavities round it tapered.
constexpr double kRecountGain = 0.05;
/// A round cavity's O-grids (round_plan): the layers nearest its count and this many - 1 more.
constexpr std::size_t kRoundLayers = 2;
/// Whole patches (whole_plan): a patch of at most kWholeQuads quads whose outline has three,
/// four or five corners and no hole is tried as one cavity first.
constexpr std::size_t kWholeQuads = 4000;
constexpr std::size_t kWholeNodes = 1000;
/// A whole patch's fill may have up to this many times its quads (an equilateral triangle's
/// three grids have 1.73x the rails' fill, quads h along the sides by 0.58 h across).
constexpr double kWholeMoreQuads = 2.0;

/// Whether a quad is beyond quality.md's skew or aspect-ratio threshold. The re-fill counts
/// what the report counts with the report's own measure (measure_planar_quad), not the
/// smoothing's cheaper midline_faults: a 60-degree rhombus's skew is 30 degrees exactly, and
/// the two round it differently.
bool skewed_or_stretched(const QuadQuality& m) {
  return m.skew_deg >= QualityThresholds::kSkewDeg ||
         m.aspect_ratio >= QualityThresholds::kAspectRatio;
}

/// Whether the quad a, b, c, d is beyond a threshold that Table III counts.
bool beyond_thresholds(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  return beyond_table_iii(measure_planar_quad(a, b, c, d));
}

/// A set of ids cleared in O(1): an id is in it when its mark is the present stamp. Each user
/// keeps one per thread (the attempts run in parallel).
class Marks {
 public:
  /// Empties the set, for ids below `size`.
  void clear(std::size_t size) {
    if (mark_.size() < size) mark_.resize(size, 0);
    if (++stamp_ == 0) {
      std::fill(mark_.begin(), mark_.end(), 0);
      stamp_ = 1;
    }
  }
  void insert(std::uint32_t id) { mark_[id] = stamp_; }
  bool contains(std::uint32_t id) const { return mark_[id] == stamp_; }

 private:
  std::vector<std::uint32_t> mark_;
  std::uint32_t stamp_ = 0;
};

/// Whether CavityMemo answers (set_cavity_memo) and how many it has answered (cavity_memo_hits).
std::atomic<bool> g_memo_on{true};
std::atomic<std::size_t> g_memo_hits{0};

/// What plan_cavity decided for a cavity, by the bytes of its problem in the cavity's frame
/// (the cycle, inner and ring nodes' positions there, which are free, and the quads over local
/// ids): the fill and the two relaxations read nothing else, so the same problem gets the same
/// answer, to the bit, wherever it comes from (docs/mesher.md, "Cavity re-fill"). The facets
/// of a faceted shell are often the same triangle turned (a cylinder's sides, a torus's), and
/// a pass retries cavities that nothing has changed since. Shared by the patches' re-fills,
/// which run in parallel: an answer computed twice at once is the same answer.
class CavityMemo {
 public:
  struct Answer {
    bool keep = false;
    /// When kept: the cycle's and the new inner nodes' positions, relaxed (cycle node i is
    /// i, inner node k is n + k), the new quads over those ids, and their worst corner.
    std::vector<Vec2> pos;
    std::vector<Quad> quads;
    double worst = 0.0;
    std::size_t gain = 0;  ///< a kept regrid's tapered quads fewer than before
    std::string log;       ///< the LAYTRACKS_DEBUG_CAVITY line

    /// Kept: the first `cycle` + interior positions of `now` (the fill relaxed with the ring)
    /// and the fill's quads.
    void keep_fill(const std::vector<Vec2>& now_pos,
                   double now_worst,
                   std::size_t cycle,
                   std::size_t interior,
                   const std::vector<Quad>& fill_quads) {
      pos.assign(now_pos.begin(), now_pos.begin() + static_cast<std::ptrdiff_t>(cycle + interior));
      quads = fill_quads;
      worst = now_worst;
    }
  };
  /// The answer to `key`'s problem: the one remembered, else compute()'s (then remembered).
  template <class Compute>
  std::shared_ptr<const Answer> answer(std::string key, Compute compute) {
    if (g_memo_on) {
      if (std::shared_ptr<const Answer> known = answers_.find(key)) {
        ++g_memo_hits;
        return known;
      }
    }
    std::shared_ptr<const Answer> computed = compute();
    if (g_memo_on) {
      const std::size_t bytes = key.size() + computed->pos.size() * sizeof(Vec2) +
                                computed->quads.size() * sizeof(Quad);
      answers_.insert(std::move(key), computed, bytes);
    }
    return computed;
  }

 private:
  /// The memo's bound (keys and positions), far above what it holds: the peak memory of
  /// torus_48_16_tri (1,536 facets, 60,463 quads) grows 76.1 -> 76.8 MB with it, of the tray
  /// at h = 0.25 (303,000 quads) 140.6 -> 143.6 MB.
  static constexpr std::size_t kMemoBytes = std::size_t{64} << 20;
  LockedMemo<Answer> answers_{kMemoBytes};
};

class PatchRefill {
 public:
  /// `parallel`: evaluate attempts on all cores (for a patch whose re-fill runs alone).
  PatchRefill(PatchQuads& pq, int iterations, double below, bool parallel, CavityMemo& memo)
      : pq_(pq),
        iterations_(std::min(iterations, kRefillSweeps)),
        below_(below),
        parallel_(parallel),
        memo_(memo) {
    alive_.assign(pq_.quads.size(), true);
    around_.resize(pq_.pos.size());
    changed_.assign(pq_.pos.size(), -1);
    written_.assign(pq_.pos.size(), 0);
    for (std::uint32_t q = 0; q < pq_.quads.size(); ++q)
      for (std::uint32_t v : pq_.quads[q]) around_[v].push_back(q);
  }

  /// Tries a re-fill round every quad below `below_`, worst first; after the first pass,
  /// only round quads near a node that the pass before moved or made. Returns the count kept.
  /// `poles`: the pass after the others, which tries, of the quads still below `below_`, those
  /// whose worst corner is at a pole (pole_plan: its star) or is a lone flat corner (lone_flat:
  /// the cavities of the first passes, which their count limit may not have reached).
  std::size_t run(int pass, bool poles = false) {
    std::vector<std::pair<double, std::uint32_t>> bad;
    for (std::uint32_t q = 0; q < pq_.quads.size(); ++q) {
      if (!alive_[q]) continue;
      const double j = jacobian(pq_.quads[q]);
      if (j < below_ && (pass == 0 || poles || near_change(q, pass - 1)) &&
          (!poles || pole_of(q) != kNew || lone_flat(q)))
        bad.emplace_back(settled(j), q);
    }
    std::sort(bad.begin(), bad.end());
    const std::size_t limit = kRefillFirst + pq_.quads.size() / kRefillShare;
    if (bad.size() > limit) bad.resize(limit);
    // Tried in order, worst first, in batches evaluated in parallel against the mesh as it was
    // before the batch; then kept in order. An attempt that read a node which an earlier
    // re-fill of its batch moved, made or re-linked is evaluated again: every decision is the
    // one the attempts made one by one would make (the same mesh, to the last bit).
    return in_batches(
        bad.size(), [&](std::size_t k) { return attempt(bad[k].second, poles); }, pass);
  }

  const std::vector<bool>& alive() const { return alive_; }

  /// The passes: up to kRefillPasses (each after the first only near what the one before
  /// changed, none after one that kept nothing), then the poles' pass. Returns the count kept.
  std::size_t passes() {
    std::size_t kept = 0;
    int pass = 0;
    for (; pass < kRefillPasses; ++pass) {
      const std::size_t more = run(pass);
      kept += more;
      if (more == 0) break;
    }
    return kept + run(pass, true);
  }

  /// The whole patch as one cavity (whole_plan), before the passes; 1 when kept.
  std::size_t whole() {
    std::vector<std::uint32_t> cavity;
    for (std::uint32_t q = 0; q < pq_.quads.size(); ++q)
      if (alive_[q]) cavity.push_back(q);
    if (cavity.empty() || cavity.size() > kWholeQuads) return 0;
    // Nothing to gain where no quad is beyond a threshold (most large patches).
    if (std::none_of(cavity.begin(), cavity.end(), [&](std::uint32_t q) {
          const Quad& x = pq_.quads[q];
          return beyond_thresholds(pq_.pos[x[0]], pq_.pos[x[1]], pq_.pos[x[2]], pq_.pos[x[3]]);
        }))
      return 0;
    std::string log;
    std::optional<Plan> plan = whole_plan(cavity, log);
    if (!log.empty()) std::fputs(log.c_str(), stderr);
    if (!plan) return 0;
    ++batch_id_;
    commit(*plan, 0);
    return 1;
  }

 private:
  /// Attempts attempt_of(0) .. attempt_of(total - 1) in order, in batches evaluated in
  /// parallel against the mesh as it was before the batch, then kept in order; an attempt that
  /// read a node which an earlier commit of its batch moved, made or re-linked is evaluated
  /// again. Returns the count kept (committed as `pass`).
  template <class AttemptOf>
  std::size_t in_batches(std::size_t total, AttemptOf attempt_of, int pass) {
    std::size_t kept = 0;
    const std::size_t batch = parallel_ ? kRefillBatch : 1;
    for (std::size_t first = 0; first < total; first += batch) {
      const std::size_t count = std::min(batch, total - first);
      std::vector<Attempt> tries(count);
      parallel_for(count, [&](std::size_t i) { tries[i] = attempt_of(first + i); });
      ++batch_id_;
      bool wrote = false;
      for (std::size_t i = 0; i < count; ++i) {
        Attempt& t = tries[i];
        if (wrote && std::any_of(t.reads.begin(), t.reads.end(),
                                 [&](std::uint32_t v) { return written_[v] == batch_id_; }))
          t = attempt_of(first + i);
        if (!t.log.empty()) std::fputs(t.log.c_str(), stderr);
        if (!t.plan) continue;
        commit(*t.plan, pass);
        wrote = true;
        ++kept;
      }
    }
    return kept;
  }

  /// Whether a node of a quad at q's nodes was moved or made in that pass.
  bool near_change(std::uint32_t q, int pass) const {
    for (std::uint32_t r : cavity_of(q, 1))
      for (std::uint32_t v : pq_.quads[r])
        if (changed_[v] == pass) return true;
    return false;
  }

  double jacobian(const Quad& q) const {
    return min_scaled_jacobian(pq_.pos[q[0]], pq_.pos[q[1]], pq_.pos[q[2]], pq_.pos[q[3]]);
  }

  /// The best smallest scaled Jacobian any quads of the polygon can have at its pinned nodes:
  /// a corner of interior angle a split into k quad corners has sin(a / k) at best.
  double corner_bound(const std::vector<Vec2>& poly, const std::vector<std::uint32_t>& ids) const {
    double bound = 1.0;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (!pq_.fixed[ids[i]]) continue;
      const double a = interior_angle(poly, i);
      double best = 0.0;
      for (int k = 1; k <= 8; ++k)
        if (a / k < kPi) best = std::max(best, std::sin(a / k));
      bound = std::min(bound, best);
    }
    return bound;
  }

  /// The quads at the nodes of `quads`, sorted.
  std::vector<std::uint32_t> quads_at_nodes_of(const std::vector<std::uint32_t>& quads) const {
    thread_local Marks seen;  // each quad once, then sorted (most are at several nodes)
    seen.clear(pq_.quads.size());
    std::vector<std::uint32_t> c;
    for (std::uint32_t r : quads)
      for (std::uint32_t v : pq_.quads[r])
        for (std::uint32_t o : around_[v])
          if (!seen.contains(o)) {
            seen.insert(o);
            c.push_back(o);
          }
    std::sort(c.begin(), c.end());
    return c;
  }

  /// Quad q with its neighbours across its edges (kind 0) or at its nodes (kind 1), or the
  /// quads at the nodes of those (kind 2), sorted.
  std::vector<std::uint32_t> cavity_of(std::uint32_t q, int kind) const {
    if (kind == 2) return quads_at_nodes_of(cavity_of(q, 1));
    std::vector<std::uint32_t> c{q};
    const Quad& x = pq_.quads[q];
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t a = x[k], b = x[(k + 1) % 4];
      for (std::uint32_t o : around_[a]) {
        if (o == q) continue;
        const Quad& y = pq_.quads[o];
        if (kind == 1 || std::find(y.begin(), y.end(), b) != y.end()) c.push_back(o);
      }
    }
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    return c;
  }

  /// A cavity's quads with the quads round it, over local ids: the cycle, the inner nodes,
  /// then the ring's other nodes (held where they are), in the cavity's frame.
  struct Local {
    std::vector<std::uint32_t> ids;  ///< local id -> patch node id (kNew: an inner node)
    std::vector<Vec2> pos;
    std::vector<Quad> quads;  ///< the cavity's first, then the ring's
    double worst = 0.0;       ///< after relaxing: the cavity's quads and the ring's that moved
  };

  /// The cavity's quads (over cycle ids 0..n-1 and inner ids n..) with the ring, not yet
  /// relaxed: the ring's other nodes after the inner ones, held where they are (`fixed`).
  Local local_problem(const std::vector<Vec2>& cycle_pos,
                      const std::vector<std::uint32_t>& cycle,
                      const std::vector<Vec2>& inner_pos,
                      const std::vector<Quad>& cavity_quads,
                      const std::vector<std::uint32_t>& ring,
                      const LocalFrame& cf,
                      std::vector<bool>& fixed) const {
    Local l;
    l.ids = cycle;
    l.pos = cycle_pos;
    fixed.clear();
    for (std::uint32_t v : cycle) fixed.push_back(pq_.fixed[v]);
    for (const Vec2& p : inner_pos) {
      l.ids.push_back(kNew);
      l.pos.push_back(p);
      fixed.push_back(false);
    }
    l.quads = cavity_quads;
    const std::size_t first_ring = l.ids.size();
    for (std::uint32_t o : ring) {
      Quad lq{};
      for (std::size_t k = 0; k < 4; ++k) {
        const std::uint32_t v = pq_.quads[o][k];
        const auto at = std::find(cycle.begin(), cycle.end(), v);
        if (at != cycle.end()) {
          lq[k] = static_cast<std::uint32_t>(at - cycle.begin());
          continue;
        }
        const auto seen =
            std::find(l.ids.begin() + static_cast<std::ptrdiff_t>(first_ring), l.ids.end(), v);
        if (seen != l.ids.end()) {
          lq[k] = static_cast<std::uint32_t>(seen - l.ids.begin());
          continue;
        }
        lq[k] = static_cast<std::uint32_t>(l.ids.size());
        l.ids.push_back(v);
        l.pos.push_back(cf.to_local(pq_.pos[v]));
        fixed.push_back(true);
      }
      l.quads.push_back(lq);
    }
    return l;
  }

  /// The cavity's quads with the ring (local_problem), relaxed as the final smoothing relaxes
  /// (kRefillSweeps sweeps of each kind): their worst, of the cavity's quads and the ring's
  /// that moved.
  Local relaxed(const std::vector<Vec2>& cycle_pos,
                const std::vector<std::uint32_t>& cycle,
                const std::vector<Vec2>& inner_pos,
                const std::vector<Quad>& cavity_quads,
                const std::vector<std::uint32_t>& ring,
                const LocalFrame& cf,
                int sweeps = -1) const {
    std::vector<bool> fixed;
    Local l = local_problem(cycle_pos, cycle, inner_pos, cavity_quads, ring, cf, fixed);
    const std::vector<Vec2> start = l.pos;
    final_sweeps(l.pos, fixed, l.quads, sweeps < 0 ? iterations_ : sweeps, kFinalEscapeTarget);
    l.worst = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < l.quads.size(); ++k) {
      const Quad& q = l.quads[k];
      if (k >= cavity_quads.size() &&
          std::all_of(q.begin(), q.end(), [&](std::uint32_t v) { return l.pos[v] == start[v]; }))
        continue;
      l.worst = std::min(l.worst,
                         min_scaled_jacobian(l.pos[q[0]], l.pos[q[1]], l.pos[q[2]], l.pos[q[3]]));
    }
    return l;
  }

  /// A re-fill decided on: what commit() needs.
  struct Plan {
    std::vector<std::uint32_t> cavity, cycle;
    std::vector<Vec2> cycle_local;  ///< the cycle's positions in cf before the re-fill
    LocalFrame cf;
    std::size_t interior = 0;       ///< the new inner nodes (local ids n.. of `now`)
    std::size_t fresh = 0;          ///< the new quads (the first of `now.quads`)
    Local now;                      ///< the new quads relaxed with the ring
    std::size_t gain = 0;           ///< a regrid's: its tapered quads fewer than before
    bool round = false;             ///< a regrid's O-grid (its cavity turns by 0)
  };

  /// One attempt round quad q, made on the mesh as it is (nothing changed): the first cavity
  /// kind whose re-fill is worth keeping, if any.
  struct Attempt {
    std::optional<Plan> plan;
    std::vector<std::uint32_t> reads;  ///< the nodes whose positions or quads it may have read
    std::string log;                   ///< LAYTRACKS_DEBUG_CAVITY lines
  };
  Attempt attempt(std::uint32_t q, bool poles) const {
    Attempt t;
    t.reads = reach(q);
    if (!alive_[q] || jacobian(pq_.quads[q]) >= below_) return t;
    if (poles) {
      // A pole's star; a lone flat corner (never at a pole: that node is pinned) goes on to
      // the cavities below; any other quad the pass took has become neither since.
      const std::uint32_t pole = pole_of(q);
      if (pole != kNew) {
        t.plan = pole_plan(pole, t.log);
        return t;
      }
      if (!lone_flat(q)) return t;
    }
    // The quads across its edges first (the smallest change), then those at its nodes, then
    // those at the nodes of those.
    for (int kind = 0; kind < 3 && !t.plan; ++kind) t.plan = plan_cavity(cavity_of(q, kind), t.log);
    return t;
  }

  /// The region with every quad at its reflex nodes added (a free node that has three or
  /// more of its quads in it but not all), again until it has none: a ring's jagged outline
  /// made straighter, so that more rings turn as a rectangle's or a pentagon's do.
  std::vector<std::uint32_t> closed_region(std::vector<std::uint32_t> region) const {
    thread_local Marks in_region;
    in_region.clear(pq_.quads.size());
    for (std::uint32_t q : region) in_region.insert(q);
    for (;;) {
      const std::size_t end = region.size();
      for (std::size_t i = 0; i < end; ++i)
        for (std::uint32_t v : pq_.quads[region[i]]) {
          if (pq_.fixed[v]) continue;
          std::size_t in = 0;
          for (std::uint32_t o : around_[v]) in += in_region.contains(o) ? 1u : 0u;
          if (in < 3 || in == around_[v].size()) continue;
          for (std::uint32_t o : around_[v])
            if (!in_region.contains(o)) {
              in_region.insert(o);
              region.push_back(o);
            }
        }
      if (region.size() == end || region.size() > kRegridQuads) break;
    }
    std::sort(region.begin(), region.end());
    return region;
  }

  /// One regrid attempt round node v on the mesh as it is; reads: v and the nodes of the
  /// quads at the nodes of the largest cavity looked at (its ring's nodes too).
  Attempt regrid_attempt(std::uint32_t v) const {
    Attempt t;
    t.reads = {v};
    if (!regrid_candidate(v)) return t;
    std::vector<std::uint32_t> region = around_[v];
    std::sort(region.begin(), region.end());
    std::vector<std::uint32_t> looked;
    // The first cavity whose grid is kept; after an O-grid's (round_plan), the larger ones too,
    // while they are kept, and of those the one with the fewest tapered quads (the first on
    // ties): rings of trapezoids round a pole go out further than its first ring.
    const auto take = [&](std::optional<Plan> plan) {
      keep_most_gain(t.plan, std::move(plan));
      return t.plan.has_value();
    };
    for (int ring = 0; ring < kRegridRings && (!t.plan || t.plan->round); ++ring) {
      if (ring > 0) region = quads_at_nodes_of(region);
      if (region.size() > kRegridQuads) break;
      looked = region;
      if (take(regrid_plan(region, t.log)) && !t.plan->round) continue;
      std::vector<std::uint32_t> closed = closed_region(region);
      if (closed.size() == region.size() || closed.size() > kRegridQuads) continue;
      looked = closed;
      take(regrid_plan(closed, t.log));
    }
    t.reads = nodes_of(quads_at_nodes_of(looked));
    if (!std::binary_search(t.reads.begin(), t.reads.end(), v))
      t.reads.insert(std::lower_bound(t.reads.begin(), t.reads.end(), v), v);
    return t;
  }

  /// A pole: the node of q's worst corner when many quads meet there (kPoleValence), each
  /// corner there narrow (12 sectors of 30 degrees: 0.5 at best). No cavity round q alone
  /// takes that node out; the quads round it, alone and then with the quads at their nodes,
  /// filled again can (arcs__scallop12: 0.499 -> 0.829).
  std::optional<Plan> pole_plan(std::uint32_t pole, std::string& log) const {
    std::vector<std::uint32_t> star = around_[pole];
    std::sort(star.begin(), star.end());
    if (std::optional<Plan> plan = plan_cavity(star, log, kMaxPoleCavityNodes)) return plan;
    return plan_cavity(quads_at_nodes_of(star), log, kMaxPoleCavityNodes);
  }

  /// The corners of q whose scaled Jacobian is within kWorstCornerTie of its least, as bits
  /// (1 << k). Of two corners equal but for rounding (a kite's, an isosceles trapezoid's) both,
  /// in every pose: settled values alone chose the first of the pair, unless a grain's rounding
  /// boundary fell between them (fuzz seed 52052's bent_031: a kite's corners at a pole of 20
  /// quads and at a node of 3, 6e-12 apart; the pole's star was tried in one pose only).
  unsigned worst_corners(std::uint32_t q) const {
    const Quad& x = pq_.quads[q];
    double c[4];
    double worst = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < 4; ++k) {
      c[k] = corner_jacobian(pq_.pos[x[k]], pq_.pos[x[(k + 1) % 4]], pq_.pos[x[(k + 3) % 4]]);
      worst = std::min(worst, c[k]);
    }
    unsigned bits = 0;
    for (std::size_t k = 0; k < 4; ++k)
      if (c[k] <= worst + kWorstCornerTie) bits |= 1u << k;
    return bits;
  }

  /// The node of q's worst corner when it is a pole (a free node of kPoleValence quads or
  /// more), else kNew: the first such node among its worst corners (worst_corners).
  std::uint32_t pole_of(std::uint32_t q) const {
    const unsigned worst = worst_corners(q);
    for (std::size_t k = 0; k < 4; ++k) {
      const std::uint32_t v = pq_.quads[q][k];
      if ((worst >> k & 1u) && !pq_.fixed[v] && around_[v].size() >= kPoleValence) return v;
    }
    return kNew;
  }

  /// Whether one of q's worst corners (worst_corners) is a pinned node that q alone meets, at
  /// more than kLoneFlatAngle: a boundary vertex on a nearly straight outline that no other
  /// quad shares.
  bool lone_flat(std::uint32_t q) const {
    const Quad& x = pq_.quads[q];
    const unsigned worst = worst_corners(q);
    for (std::size_t k = 0; k < 4; ++k) {
      if (!(worst >> k & 1u) || !pq_.fixed[x[k]] || around_[x[k]].size() != 1) continue;
      const double a =
          interior_angle({pq_.pos[x[0]], pq_.pos[x[1]], pq_.pos[x[2]], pq_.pos[x[3]]}, k);
      if (a > kLoneFlatAngle && a <= kPi) return true;  // a reflex corner (inverted) is not flat
    }
    return false;
  }

  /// What an attempt round q reads: the nodes of the quads at the nodes of the quads at the
  /// nodes of... q, three rings out (its largest cavity is two rings; the quads round a
  /// cavity, whose nodes the relaxation reads, one more).
  std::vector<std::uint32_t> reach(std::uint32_t q) const {
    return nodes_of(quads_at_nodes_of(cavity_of(q, 2)));
  }

  /// The nodes of `quads`, sorted, each once.
  std::vector<std::uint32_t> nodes_of(const std::vector<std::uint32_t>& quads) const {
    thread_local Marks seen;
    seen.clear(pq_.pos.size());
    std::vector<std::uint32_t> nodes;
    for (std::uint32_t r : quads)
      for (std::uint32_t v : pq_.quads[r])
        if (!seen.contains(v)) {
          seen.insert(v);
          nodes.push_back(v);
        }
    std::sort(nodes.begin(), nodes.end());
    return nodes;
  }

  /// The boundary of a cavity as one simple cycle (counter-clockwise: the directed edges whose
  /// reverse no cavity quad has), none when it is not one or longer than kMaxCavityNodes.
  std::optional<std::vector<std::uint32_t>> cavity_cycle(const std::vector<std::uint32_t>& cavity,
                                                         std::size_t most = kMaxCavityNodes) const {
    // Its boundary: the directed edges whose reverse no cavity quad has, one cycle.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    for (std::uint32_t c : cavity)
      for (std::size_t k = 0; k < 4; ++k)
        edges.emplace_back(pq_.quads[c][k], pq_.quads[c][(k + 1) % 4]);
    std::sort(edges.begin(), edges.end());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> border;
    for (const auto& [a, b] : edges)
      if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(b, a)))
        border.emplace_back(a, b);
    if (border.size() < 4 || border.size() > most) return std::nullopt;
    // A simple cycle: one edge out of every border node, all of them on one loop.
    for (std::size_t i = 1; i < border.size(); ++i)
      if (border[i].first == border[i - 1].first) return std::nullopt;
    auto next = [&](std::uint32_t a) {
      const auto it = std::lower_bound(border.begin(), border.end(), std::make_pair(a, 0u));
      return it != border.end() && it->first == a ? it->second : kNew;
    };
    std::vector<std::uint32_t> cycle{border.front().first};
    for (std::uint32_t v = next(cycle.front()); v != cycle.front(); v = next(v)) {
      if (v == kNew || cycle.size() >= border.size()) return std::nullopt;
      cycle.push_back(v);
    }
    if (cycle.size() != border.size()) return std::nullopt;
    return cycle;
  }

  /// The nodes of a cavity's quads not on its cycle, sorted; none when one is pinned.
  std::optional<std::vector<std::uint32_t>> inner_nodes(
      const std::vector<std::uint32_t>& cavity, const std::vector<std::uint32_t>& cycle) const {
    std::vector<std::uint32_t> on_cycle = cycle;
    std::sort(on_cycle.begin(), on_cycle.end());
    std::vector<std::uint32_t> inner;
    for (std::uint32_t c : cavity)
      for (std::uint32_t v : pq_.quads[c])
        if (!std::binary_search(on_cycle.begin(), on_cycle.end(), v)) inner.push_back(v);
    std::sort(inner.begin(), inner.end());
    inner.erase(std::unique(inner.begin(), inner.end()), inner.end());
    for (std::uint32_t v : inner)
      if (pq_.fixed[v]) return std::nullopt;
    return inner;
  }

  /// The quads round a cavity: alive, not in it, at a node of its boundary; sorted.
  std::vector<std::uint32_t> ring_of(const std::vector<std::uint32_t>& cavity,
                                     const std::vector<std::uint32_t>& cycle) const {
    std::vector<std::uint32_t> ring;
    for (std::uint32_t v : cycle)
      for (std::uint32_t o : around_[v])
        if (!std::binary_search(cavity.begin(), cavity.end(), o)) ring.push_back(o);
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    return ring;
  }

  /// The cavity's quads over local ids: cycle node i is i, inner node k (of `inner`, sorted)
  /// is cycle.size() + k.
  std::vector<Quad> local_quads(const std::vector<std::uint32_t>& cavity,
                                const std::vector<std::uint32_t>& cycle,
                                const std::vector<std::uint32_t>& inner) const {
    const auto local_id = [&](std::uint32_t v) {
      const auto at = std::find(cycle.begin(), cycle.end(), v);
      return at != cycle.end()
                 ? static_cast<std::uint32_t>(at - cycle.begin())
                 : static_cast<std::uint32_t>(
                       cycle.size() +
                       static_cast<std::size_t>(std::lower_bound(inner.begin(), inner.end(), v) -
                                                inner.begin()));
    };
    std::vector<Quad> quads;
    for (std::uint32_t c : cavity) {
      Quad lq{};
      for (std::size_t k = 0; k < 4; ++k) lq[k] = local_id(pq_.quads[c][k]);
      quads.push_back(lq);
    }
    return quads;
  }

  /// A cavity in its own gridded frame (LocalFrame: its first node, the least id, at the
  /// origin), so that the same cavity in every pose of the part is the same problem, bit for
  /// bit, and the templates and the relaxation decide alike: its cycle's and inner nodes'
  /// positions there, and its quads over local ids (local_quads).
  struct Posed {
    LocalFrame cf;
    std::vector<Vec2> cycle, inner;
    std::vector<Quad> quads;
  };
  Posed posed(const std::vector<std::uint32_t>& cavity,
              const std::vector<std::uint32_t>& cycle,
              const std::vector<std::uint32_t>& inner) const {
    Posed p{LocalFrame(pq_.pos, cycle), {}, {}, local_quads(cavity, cycle, inner)};
    for (std::uint32_t v : cycle) p.cycle.push_back(p.cf.to_local(pq_.pos[v]));
    for (std::uint32_t v : inner) p.inner.push_back(p.cf.to_local(pq_.pos[v]));
    return p;
  }

  /// A re-fill of the cavity, when it raises the worst quad of it and of the quads round it.
  std::optional<Plan> plan_cavity(const std::vector<std::uint32_t>& cavity,
                                  std::string& log,
                                  std::size_t most = kMaxCavityNodes) const {
    const std::optional<std::vector<std::uint32_t>> found = cavity_cycle(cavity, most);
    if (!found) return std::nullopt;
    const std::vector<std::uint32_t>& cycle = *found;
    // Its inner nodes go; none of them may be pinned.
    const std::optional<std::vector<std::uint32_t>> inner_found = inner_nodes(cavity, cycle);
    if (!inner_found) return std::nullopt;
    const std::vector<std::uint32_t>& inner = *inner_found;
    // The quads round it: alive, not in it, at a node of its boundary.
    const std::vector<std::uint32_t> ring = ring_of(cavity, cycle);

    const Posed old = posed(cavity, cycle, inner);
    const LocalFrame& cf = old.cf;
    const std::vector<Vec2>& old_inner = old.inner;
    const std::vector<Quad>& old_quads = old.quads;
    FaceInput face;
    face.cycle = old.cycle;
    for (std::uint32_t v : cycle) face.free_nodes.push_back(!pq_.fixed[v]);
    const std::size_t n = cycle.size();
    double before = std::numeric_limits<double>::infinity();
    for (const Quad& lq : old_quads) {
      auto at = [&](std::uint32_t i) { return i < n ? face.cycle[i] : old_inner[i - n]; };
      before = std::min(before, min_scaled_jacobian(at(lq[0]), at(lq[1]), at(lq[2]), at(lq[3])));
    }
    // No quad mesh of the cavity beats what its pinned corners allow: skip hopeless ones.
    const double bound = corner_bound(face.cycle, cycle);
    if (bound < before + kRefillGain) return std::nullopt;
    FaceSide all;
    all.kind = FaceSide::Kind::Boundary;
    all.edges = static_cast<std::uint32_t>(cycle.size());
    face.sides.push_back(all);
    // What follows reads the problem in the cavity's frame alone (CavityMemo): its key.
    const std::shared_ptr<const CavityMemo::Answer> answer = memo_.answer(
        problem_key(face.cycle, cycle, old_inner, old_quads, ring, cf),
        [&] { return refill_answer(face, cycle, old_inner, old_quads, ring, cf, bound); });
    log += answer->log;
    return plan_of(*answer, cavity, cycle, face.cycle, cf);
  }

  /// The plan of a kept answer (CavityMemo::Answer) for this cavity; none when not kept.
  static std::optional<Plan> plan_of(const CavityMemo::Answer& answer,
                                     const std::vector<std::uint32_t>& cavity,
                                     const std::vector<std::uint32_t>& cycle,
                                     const std::vector<Vec2>& cycle_local,
                                     const LocalFrame& cf) {
    if (!answer.keep) return std::nullopt;
    const std::size_t interior = answer.pos.size() - cycle.size();
    Local now;
    now.ids = cycle;
    now.ids.resize(answer.pos.size(), kNew);
    now.pos = answer.pos;
    now.quads = answer.quads;
    now.worst = answer.worst;
    Plan plan{cavity, cycle, cycle_local, cf, interior, answer.quads.size(), std::move(now)};
    plan.gain = answer.gain;
    return plan;
  }

  /// The bytes of a cavity's problem in its frame: the positions of its cycle, inner and
  /// ring nodes, which are free, and its and the ring's quads over local ids (local_problem).
  std::string problem_key(const std::vector<Vec2>& cycle_pos,
                          const std::vector<std::uint32_t>& cycle,
                          const std::vector<Vec2>& inner_pos,
                          const std::vector<Quad>& cavity_quads,
                          const std::vector<std::uint32_t>& ring,
                          const LocalFrame& cf) const {
    std::vector<bool> fixed;
    const Local l = local_problem(cycle_pos, cycle, inner_pos, cavity_quads, ring, cf, fixed);
    const std::size_t counts[3] = {cycle.size(), inner_pos.size(), cavity_quads.size()};
    std::string key;
    append_bytes(key, counts);
    append_bytes(key, l.pos);
    append_bytes(key, l.quads);
    for (std::size_t i = 0; i < cycle.size(); ++i) key.push_back(fixed[i] ? '1' : '0');
    return key;
  }

  /// The fill of a cavity and its judgement (plan_cavity): the new quads, relaxed with the
  /// ring, kept when their worst beats the old quads' relaxed alike by kRefillGain.
  std::shared_ptr<const CavityMemo::Answer> refill_answer(const FaceInput& face,
                                                          const std::vector<std::uint32_t>& cycle,
                                                          const std::vector<Vec2>& old_inner,
                                                          const std::vector<Quad>& old_quads,
                                                          const std::vector<std::uint32_t>& ring,
                                                          const LocalFrame& cf,
                                                          double bound) const {
    auto answer = std::make_shared<CavityMemo::Answer>();
    const std::size_t n = cycle.size();
    // The old quads relaxed with the quads round the cavity: what the smoothing could do
    // without a re-fill. When that is good enough, or as good as the corners allow, no re-fill.
    // Before the fill, which costs about three relaxations: on a hull of triangles (shells.py
    // seed 47047's hull_020) a quarter of the cavities end here and a tenth at the fill.
    const Local was = relaxed(face.cycle, cycle, old_inner, old_quads, ring, cf);
    if (was.worst >= below_ || bound < was.worst + kRefillGain) return answer;
    const std::optional<FaceMesh> filled = fill_cavity(face);
    if (!filled) return answer;
    const FaceMesh& fm = *filled;

    // The old quads and the new, each relaxed with the quads round the cavity: the new are kept
    // when their worst (and that of the quads round them that moved) beats the old's by
    // kRefillGain. Both relaxed alike, so that a re-fill is not kept for what relaxation alone
    // would have done.
    Local now = relaxed(face.cycle, cycle, fm.interior, fm.quads, ring, cf);
    static const bool debug = std::getenv("LAYTRACKS_DEBUG_CAVITY") != nullptr;
    answer->keep = settled(now.worst) >= settled(was.worst) + kRefillGain;
    if (debug) {
      char line[200];
      std::snprintf(
          line, sizeof line,
          "cavity: %zu quads, %zu nodes round, %s (%zu quads, %.6f), worst %.3f -> %.3f%s\n",
          old_quads.size(), n, to_string(fm.kind), fm.quads.size(), fm.min_jacobian, was.worst,
          now.worst, answer->keep ? " kept" : "");
      answer->log = line;
    }
    if (answer->keep) answer->keep_fill(now.pos, now.worst, n, fm.interior.size(), fm.quads);
    return answer;
  }

  /// The count of a regrid cavity's quads that its fill gives cycle node v, which has `in`
  /// of them now: `in`, but at a pinned node whose every quad is in the cavity, the count of
  /// 1 to 3 whose corners have the largest sine, when it beats `in`'s by kRecountGain
  /// (settled: the outline's angle is the same in every pose up to rounding).
  std::size_t fill_count(std::uint32_t v, std::size_t in) const {
    if (!pq_.fixed[v] || in != around_[v].size() || in == 0) return in;
    const double a = outline_angle_[v];
    const auto best_sine = [a](std::size_t k) {
      const double c = a / static_cast<double>(k);
      return c < kPi ? std::sin(c) : -1.0;
    };
    std::size_t best = in;
    for (std::size_t k = 1; k <= 3; ++k)
      if (settled(best_sine(k)) >= settled(best_sine(best) + kRecountGain)) best = k;
    return best;
  }

  /// Whether the regrid starts at node v: an irregular inner node (not in four quads), or a
  /// pinned one whose count of quads fill_count would change.
  bool regrid_candidate(std::uint32_t v) const {
    const std::size_t count = around_[v].size();
    if (count == 0) return false;
    return pq_.fixed[v] ? fill_count(v, count) != count : count != 4;
  }

  /// Whether regrid_plan could fill the cavity, read from the counts alone (no cycle built):
  /// its boundary nodes' quads in it turn by 4 round it with an irregular inner node, or by 3
  /// or 5 with two and no reflex node; and a quad of it is tapered. Most rings fail here.
  /// With `recount`, the pinned nodes' counts are fill_count's. -1 when not worth a fill, 0
  /// when worth it with no count changed, 1 when worth it with some recounted.
  int worth_regrid(const std::vector<std::uint32_t>& cavity, bool recount) const {
    thread_local Marks in_cavity, seen;
    in_cavity.clear(pq_.quads.size());
    seen.clear(pq_.pos.size());
    for (std::uint32_t q : cavity) in_cavity.insert(q);
    int turning = 0;
    std::size_t irregular = 0, reflex = 0, recounted = 0;
    for (std::uint32_t q : cavity)
      for (std::uint32_t v : pq_.quads[q]) {
        if (seen.contains(v)) continue;
        seen.insert(v);
        std::size_t in = 0;
        for (std::uint32_t o : around_[v]) in += in_cavity.contains(o) ? 1u : 0u;
        if (in == around_[v].size() && !pq_.fixed[v]) {
          irregular += in != 4 ? 1u : 0u;
          continue;
        }
        const std::size_t count = recount ? fill_count(v, in) : in;
        recounted += count != in ? 1u : 0u;
        in = count;
        if (in > 3) return -1;
        turning += 2 - static_cast<int>(in);
        reflex += in == 3 ? 1u : 0u;
      }
    // What the fill would mend: the irregular inner nodes and the recounted pinned ones (a
    // sided fill keeps one irregular node, its centre).
    const std::size_t mended = irregular + recounted;
    const bool lattice = turning == 4 && mended >= 1;
    const bool sided = (turning == 3 || turning == 5) && mended >= 2 && reflex == 0;
    const bool round = turning == 0 && mended >= 1 && reflex == 0;
    if (!lattice && !sided && !round) return -1;
    // A cavity with no tapered quad has nothing to gain (and most have none). Settled: a
    // trapezoid of sides 2 and 3 (rows of a triangle's grid) has a taper of 0.8 exactly, and
    // the pose's rounding must not decide.
    const bool tapered = std::any_of(cavity.begin(), cavity.end(), [&](std::uint32_t q) {
      const Quad& x = pq_.quads[q];
      return settled(quad_taper(pq_.pos[x[0]], pq_.pos[x[1]], pq_.pos[x[2]], pq_.pos[x[3]])) <=
             settled(QualityThresholds::kTaper);
    });
    return !tapered ? -1 : recounted > 0 ? 1 : 0;
  }

  /// The cavity filled with fewer irregular nodes (not in four quads) than it has inside:
  /// a lattice fill where its boundary turns as a rectangle's does (no irregular node), a
  /// fill round one centre where it turns as a triangle's or a pentagon's (one); each cycle
  /// node keeps its count of the cavity's quads. Kept when, both relaxed with the quads round
  /// the cavity, fewer of its quads are tapered (quality.md: taper <= 0.8), the worst corner
  /// is no lower (or at least the re-fill threshold) and the count changes by at most
  /// kRegridCountRatio.
  std::optional<Plan> regrid_plan(const std::vector<std::uint32_t>& cavity,
                                  std::string& log) const {
    // With the pinned nodes recounted first; where that changes a count but gives no fill that
    // is kept, with the counts as they are (a recount must not cost a regrid the cavity had).
    const int recounting = worth_regrid(cavity, true);
    std::optional<Plan> plan;
    if (recounting >= 0) plan = regrid_counted(cavity, recounting > 0, log);
    if (!plan && recounting != 0 && worth_regrid(cavity, false) >= 0)
      plan = regrid_counted(cavity, false, log);
    return plan;
  }

  /// regrid_plan's fill with the counts as they are, or with fill_count's (`recount`).
  std::optional<Plan> regrid_counted(const std::vector<std::uint32_t>& cavity,
                                     bool recount,
                                     std::string& log) const {
    const std::optional<std::vector<std::uint32_t>> found = cavity_cycle(cavity);
    if (!found) return std::nullopt;
    const std::vector<std::uint32_t>& cycle = *found;
    const std::size_t n = cycle.size();
    const std::optional<std::vector<std::uint32_t>> inner_found = inner_nodes(cavity, cycle);
    if (!inner_found || inner_found->empty()) return std::nullopt;
    const std::vector<std::uint32_t>& inner = *inner_found;
    // The turns worth_regrid added up (and checked, with the irregular inner nodes), per node.
    std::vector<int> turn(n);
    int turning = 0;
    bool recounted = false;
    for (std::size_t i = 0; i < n; ++i) {
      const auto count = static_cast<std::size_t>(std::count_if(
          around_[cycle[i]].begin(), around_[cycle[i]].end(),
          [&](std::uint32_t o) { return std::binary_search(cavity.begin(), cavity.end(), o); }));
      const std::size_t given = recount ? fill_count(cycle[i], count) : count;
      recounted = recounted || given != count;
      turn[i] = 2 - static_cast<int>(given);
      turning += turn[i];
    }
    const Posed old = posed(cavity, cycle, inner);
    const auto header = [&] {
      Vec2 mid{0.0, 0.0};
      for (const Vec2& p : old.cycle) mid = mid + (1.0 / static_cast<double>(n)) * p;
      mid = old.cf.to_patch(mid);
      char line[200];
      std::snprintf(line, sizeof line,
                    "regrid: near (%g, %g) %zu quads, %zu inner nodes, turning %d", mid.x, mid.y,
                    cavity.size(), inner.size(), turning);
      return std::string(line);
    };
    if (turning == 0) return round_plan(cavity, cycle, turn, old, log, header, recounted);
    std::optional<TurnFill> fill = turning == 4 ? lattice_fill(turn) : sided_fill(turn);
    if (!fill || !count_ok(*fill, cavity.size(), kRegridCountRatio)) return std::nullopt;
    // The turns are part of the problem: a pinned node's count (fill_count) reads the outline's
    // angle in the patch's frame, which the posed positions of the key hold only to rounding.
    std::string kind = "regrid";
    append_bytes(kind, turn);
    return judged_grid(kind, std::move(*fill), cavity, cycle, old, false, log, header, recounted);
  }

  /// `plan` in `best`'s place when it untapers more (the first kept on ties).
  static void keep_most_gain(std::optional<Plan>& best, std::optional<Plan> plan) {
    if (plan && (!best || plan->gain > best->gain)) best = std::move(plan);
  }

  /// A round cavity (every cycle node in two of its quads; regrid_plan): O-grids of the layers
  /// whose count best matches the cavity's and of kRoundLayers - 1 more, each with its core's
  /// first corner under the cycle's first node or n / 8 nodes on; of those kept, the one with
  /// the fewest tapered quads (the first on ties).
  template <class Header>
  std::optional<Plan> round_plan(const std::vector<std::uint32_t>& cavity,
                                 const std::vector<std::uint32_t>& cycle,
                                 const std::vector<int>& turn,
                                 const Posed& old,
                                 std::string& log,
                                 Header header,
                                 bool recounted) const {
    const std::size_t n = cycle.size();
    const std::size_t core = (n / 4) * (n / 2 - n / 4);
    // The layers whose count is nearest the cavity's (at least one).
    const std::size_t layers =
        cavity.size() > core ? std::max<std::size_t>(1, (cavity.size() - core + n / 2) / n) : 1;
    std::optional<Plan> best;
    for (std::size_t more = 0; more < kRoundLayers; ++more)
      for (std::size_t start : {std::size_t{0}, n / 8}) {
        std::optional<TurnFill> fill = ogrid_fill(turn, static_cast<std::uint32_t>(layers + more),
                                                  static_cast<std::uint32_t>(start));
        if (!fill || !count_ok(*fill, cavity.size(), kRegridCountRatio)) continue;
        const std::string kind =
            "ogrid " + std::to_string(layers + more) + " " + std::to_string(start) + " ";
        std::optional<Plan> plan =
            judged_grid(kind, std::move(*fill), cavity, cycle, old, false, log, header, recounted);
        keep_most_gain(best, std::move(plan));
      }
    if (best) best->round = true;
    return best;
  }

  /// Whether a grid fill's quad count is within bounds against the cavity's: at most
  /// `most_more` times it, at least 1 / kRegridCountRatio.
  static bool count_ok(const TurnFill& fill, std::size_t cavity_quads, double most_more) {
    const double more = static_cast<double>(fill.quads.size()) / static_cast<double>(cavity_quads);
    return more <= most_more && more * kRegridCountRatio >= 1.0;
  }

  /// A grid fill of the cavity (regrid_plan, whole_plan) judged by regrid_answer in the
  /// cavity's frame alone, through the memo under `kind`; with LAYTRACKS_DEBUG_CAVITY, the
  /// line `header` makes, then the answer's, go to `log` (none when no quad was beyond).
  template <class Header>
  std::optional<Plan> judged_grid(const std::string& kind,
                                  TurnFill fill,
                                  const std::vector<std::uint32_t>& cavity,
                                  const std::vector<std::uint32_t>& cycle,
                                  const Posed& old,
                                  bool every_measure,
                                  std::string& log,
                                  Header header,
                                  bool no_more_skewed = false) const {
    const std::vector<std::uint32_t> ring = ring_of(cavity, cycle);
    // The answer depends on how low the regrid may go (regrid_low_), which is the patch's.
    std::string key = kind + problem_key(old.cycle, cycle, old.inner, old.quads, ring, old.cf);
    if (!every_measure) append_bytes(key, regrid_low_);
    append_bytes(key, no_more_skewed);
    const std::shared_ptr<const CavityMemo::Answer> answer = memo_.answer(std::move(key), [&] {
      return regrid_answer(std::move(fill), old, cycle, ring, every_measure, no_more_skewed);
    });
    static const bool debug = std::getenv("LAYTRACKS_DEBUG_CAVITY") != nullptr;
    if (debug && !answer->log.empty()) log += header() + answer->log;
    return plan_of(*answer, cavity, cycle, old.cycle, old.cf);
  }

  /// A patch read by its outline's corners (polygon_corners) rather than by its quads: three
  /// or five corners get sided_fill's grids round one centre, four a lattice; judged as a
  /// regrid is. A small facet of a faceted shell is a triangle whose every side the rails of
  /// its neighbours cross: its faces, cut by rails from three or more directions, are rows of
  /// tapered quads, where three grids round its centre are close to parallelograms.
  std::optional<Plan> whole_plan(const std::vector<std::uint32_t>& cavity, std::string& log) const {
    const std::optional<std::vector<std::uint32_t>> found = cavity_cycle(cavity, kWholeNodes);
    if (!found) return std::nullopt;  // (a patch with a hole has more than one cycle)
    const std::vector<std::uint32_t>& cycle = *found;
    const std::optional<std::vector<std::uint32_t>> inner_found = inner_nodes(cavity, cycle);
    if (!inner_found || inner_found->empty()) return std::nullopt;
    const Posed old = posed(cavity, cycle, *inner_found);
    const std::optional<std::vector<std::uint32_t>> corners = polygon_corners(old.cycle);
    if (!corners || corners->size() < 3 || corners->size() > 5) return std::nullopt;
    std::vector<int> turn(cycle.size(), 0);
    for (std::uint32_t k : *corners) turn[k] = 1;
    std::optional<TurnFill> fill = corners->size() == 4 ? lattice_fill(turn) : sided_fill(turn);
    if (!fill || !count_ok(*fill, cavity.size(), kWholeMoreQuads)) return std::nullopt;
    return judged_grid("whole", std::move(*fill), cavity, cycle, old, true, log, [&] {
      char line[200];
      std::snprintf(line, sizeof line, "whole patch: %zu quads, %zu corners", cavity.size(),
                    corners->size());
      return std::string(line);
    });
  }

  /// regrid_plan's fill placed in the cavity and judged against the old quads, both relaxed
  /// with the ring.
  std::shared_ptr<const CavityMemo::Answer> regrid_answer(TurnFill fill,
                                                          const Posed& old,
                                                          const std::vector<std::uint32_t>& cycle,
                                                          const std::vector<std::uint32_t>& ring,
                                                          bool every_measure = false,
                                                          bool no_more_skewed = false) const {
    auto answer = std::make_shared<CavityMemo::Answer>();
    const std::size_t n = cycle.size();
    const LocalFrame& cf = old.cf;
    const std::vector<Vec2>& cyc = old.cycle;
    place_harmonic(fill, cyc, kRegridSweeps);
    // Judged after kRefillSweeps sweeps whatever the smoothing asked for, so that the choice,
    // and the element count, do not depend on it; the new quads keep those positions (also
    // with --smooth 0: the harmonic positions alone may fold where the cavity is not convex).
    // How many of the first `count` quads of l are beyond: tapered (every_measure: any
    // threshold Table III counts), or skewed or stretched (`skew`).
    const auto beyond = [every_measure](const Local& l, std::size_t count, bool skew = false) {
      std::size_t t = 0;
      for (std::size_t q = 0; q < count; ++q) {
        const Quad& x = l.quads[q];
        const Vec2 a = l.pos[x[0]], b = l.pos[x[1]], c = l.pos[x[2]], d = l.pos[x[3]];
        if (skew            ? skewed_or_stretched(measure_planar_quad(a, b, c, d))
            : every_measure ? beyond_thresholds(a, b, c, d)
                            : quad_taper(a, b, c, d) <= QualityThresholds::kTaper)
          ++t;
      }
      return t;
    };
    const Local was = relaxed(cyc, cycle, old.inner, old.quads, ring, cf, kRefillSweeps);
    const std::size_t t_was = beyond(was, old.quads.size());
    if (t_was == 0) return answer;  // nothing to gain
    Local now = relaxed(cyc, cycle, fill.interior, fill.quads, ring, cf, kRefillSweeps);
    const std::size_t t_now = beyond(now, fill.quads.size());
    // A whole patch keeps its worst corner (every_measure): cheaper than a regrid's bound,
    // which may trade a patch's worst down to the threshold for fewer tapered quads.
    const double floor = every_measure ? settled(was.worst) : std::min(settled(was.worst), below_);
    // Below that floor (not for a whole patch), down to regrid_low_, with no more quads beyond
    // the skew or aspect thresholds.
    const bool lower_ok =
        !every_measure && settled(now.worst) >= std::min(floor, regrid_low_) &&
        settled(now.worst) >= floor - kRegridMostDrop &&
        beyond(now, fill.quads.size(), true) <= beyond(was, old.quads.size(), true);
    // A fill that gives a pinned node another count (fill_count) trades that node's corners
    // for the cavity's: no more of its quads may be skewed or stretched.
    const bool skew_ok =
        !no_more_skewed || beyond(now, fill.quads.size(), true) <= beyond(was, old.quads.size(), true);
    answer->keep = t_now < t_was && now.worst > kMinValidJacobian && skew_ok &&
                   (settled(now.worst) >= floor || lower_ok);
    static const bool debug = std::getenv("LAYTRACKS_DEBUG_CAVITY") != nullptr;
    if (debug) {
      char line[200];
      std::snprintf(line, sizeof line, " -> %zu quads, tapered %zu -> %zu, worst %.3f -> %.3f%s\n",
                    fill.quads.size(), t_was, t_now, was.worst, now.worst,
                    answer->keep ? " kept" : "");
      answer->log = line;
    }
    if (answer->keep) {
      answer->keep_fill(now.pos, now.worst, n, fill.interior.size(), fill.quads);
      answer->gain = t_was - t_now;
    }
    return answer;
  }

 public:
  /// The regrid pass (regrid_plan): every irregular inner node (not in four quads) in node
  /// order, in batches evaluated in parallel as run() does; the quads round it, then the quads
  /// at their nodes, out to kRegridRings rings (at most kRegridQuads quads), are its cavities.
  std::size_t regrid() {
    regrid_low_ =
        std::max(kRegridLowFloor, settled(outline_bound(pq_.pos, pq_.fixed, pq_.quads, &alive_)));
    // Pinned nodes do not move and their quads cover the outline's angle whatever the regrids
    // change: read once (fill_count).
    outline_angle_ = pinned_angles(pq_.pos, pq_.fixed, pq_.quads, &alive_);
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t v = 0; v < pq_.pos.size(); ++v)
      if (regrid_candidate(v)) candidates.push_back(v);
    return in_batches(
        candidates.size(), [&](std::size_t k) { return regrid_attempt(candidates[k]); },
        kRefillPasses + 1);
  }

 private:
  /// Kept: the cavity's quads go, the new ones and their inner nodes come. Marks the nodes it
  /// changes (written_) for the attempts of the batch after it.
  void commit(Plan& plan, int pass) {
    const std::size_t n = plan.cycle.size();
    const std::vector<Vec2>& pos = plan.now.pos;
    std::vector<std::uint32_t>& ids = plan.now.ids;
    for (std::uint32_t c : plan.cavity) {
      alive_[c] = false;
      for (std::uint32_t v : pq_.quads[c]) {
        written_[v] = batch_id_;
        auto& at = around_[v];
        at.erase(std::remove(at.begin(), at.end(), c), at.end());
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (pos[i] == plan.cycle_local[i]) continue;
      changed_[plan.cycle[i]] = pass;
      pq_.pos[plan.cycle[i]] = plan.cf.to_patch(pos[i]);
    }
    for (std::size_t i = n; i < n + plan.interior; ++i) {
      ids[i] = static_cast<std::uint32_t>(pq_.pos.size());
      pq_.pos.push_back(plan.cf.to_patch(pos[i]));
      pq_.fixed.push_back(false);
      pq_.global.push_back(kNew);
      around_.emplace_back();
      changed_.push_back(pass);
      written_.push_back(batch_id_);
    }
    for (std::size_t k = 0; k < plan.fresh; ++k) {
      Quad q{};
      for (std::size_t m = 0; m < 4; ++m) q[m] = ids[plan.now.quads[k][m]];
      const auto id = static_cast<std::uint32_t>(pq_.quads.size());
      pq_.quads.push_back(q);
      alive_.push_back(true);
      for (std::uint32_t v : q) around_[v].push_back(id);
    }
  }

  PatchQuads& pq_;
  int iterations_;
  double below_;  ///< quads worse than this get a re-fill tried
  /// How low a regrid may take its cavity's worst corner (regrid(): kRegridLowFloor)
  double regrid_low_ = std::numeric_limits<double>::infinity();
  /// The outline's angle at each pinned node (regrid(): pinned_angles), for fill_count.
  std::vector<double> outline_angle_;
  bool parallel_;
  CavityMemo& memo_;
  std::vector<bool> alive_;
  std::vector<std::vector<std::uint32_t>> around_;  ///< node -> alive quads at it
  std::vector<int> changed_;  ///< node -> the last pass that moved or made it (-1: none)
  std::vector<std::uint64_t> written_;  ///< node -> the last batch whose re-fill changed it
  std::uint64_t batch_id_ = 0;
};

}  // namespace

void set_cavity_memo(bool on) { g_memo_on = on; }

std::size_t cavity_memo_hits() { return g_memo_hits; }

namespace mesher_detail {

std::size_t refill_face(const std::vector<Vec2>& cycle, FaceMesh& m, double below, int iterations) {
  const std::size_t n = cycle.size();
  PatchQuads pq;
  pq.pos = cycle;
  pq.pos.insert(pq.pos.end(), m.interior.begin(), m.interior.end());
  pq.fixed.assign(pq.pos.size(), false);
  std::fill(pq.fixed.begin(), pq.fixed.begin() + static_cast<std::ptrdiff_t>(n), true);
  pq.global.resize(pq.pos.size());
  for (std::uint32_t i = 0; i < pq.global.size(); ++i) pq.global[i] = i;
  pq.quads = m.quads;
  CavityMemo memo;
  PatchRefill refill(pq, iterations, below, false, memo);
  const std::size_t kept = refill.passes();
  if (kept == 0) return 0;
  // The live quads over the cycle's ids and the inner nodes they use, renumbered in order.
  const std::vector<bool>& alive = refill.alive();
  std::vector<std::uint32_t> id(pq.pos.size(), kNew);
  for (std::uint32_t i = 0; i < n; ++i) id[i] = i;
  FaceMesh out;
  out.kind = m.kind;
  for (std::size_t q = 0; q < pq.quads.size(); ++q) {
    if (!alive[q]) continue;
    Quad x = pq.quads[q];
    for (std::uint32_t& v : x) {
      if (id[v] == kNew) {
        id[v] = static_cast<std::uint32_t>(n + out.interior.size());
        out.interior.push_back(pq.pos[v]);
      }
      v = id[v];
    }
    out.quads.push_back(x);
  }
  m = std::move(out);
  return kept;
}

}  // namespace mesher_detail

std::size_t refill_cavities(
    const Part& part, QuadMesh& mesh, int iterations, double below, std::size_t* regrids) {
  const std::vector<bool> pinned = pinned_nodes(mesh);
  const std::vector<std::vector<std::uint32_t>> by_patch = elements_by_patch(part, mesh);
  // Each patch's re-fill reads its own quads and the pinned nodes, which no re-fill moves, so
  // the patches run in parallel; their results are merged in patch order.
  struct Result {
    PatchQuads pq;
    std::vector<bool> alive;
    std::size_t kept = 0, regrids = 0;
  };
  std::vector<Result> results(part.patches.size());
  CavityMemo memo;
  // With one patch to re-fill, its attempts run in parallel instead (a parallel_for within
  // the patches' would run on its caller's thread).
  const std::vector<std::size_t> busy = busy_patches(by_patch);
  const bool inner = busy.size() == 1 && worker_threads() > 1;
  parallel_for(busy.size(), [&](std::size_t i) {
    const std::size_t p = busy[i];
    Result& r = results[p];
    r.pq = patch_quads(part, mesh, p, by_patch[p], pinned);
    if (r.pq.quads.empty()) return;
    PatchRefill refill(r.pq, iterations, below, inner && r.pq.quads.size() >= kRefillParallelQuads,
                       memo);
    r.regrids = refill.whole();
    r.kept = refill.passes();
    r.regrids += refill.regrid();
    if (r.kept + r.regrids > 0) r.alive = refill.alive();
  });
  std::size_t kept = 0, regridded = 0;
  std::vector<bool> drop(mesh.elements.size(), false);
  std::vector<MeshElement> added;
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    Result& r = results[p];
    if (r.kept + r.regrids == 0) continue;
    PatchQuads& pq = r.pq;
    kept += r.kept;
    regridded += r.regrids;
    const std::uint32_t shell = mesh.elements[pq.elements.front()].shell;
    const Frame& frame = part.patches[p].frame;
    for (std::size_t i = 0; i < pq.global.size(); ++i) {
      if (pq.global[i] == kNew) {
        pq.global[i] = static_cast<std::uint32_t>(mesh.nodes.size());
        mesh.nodes.push_back(frame.to_3d(pq.pos[i]));
      } else {
        mesh.nodes[pq.global[i]] = frame.to_3d(pq.pos[i]);
      }
    }
    const std::vector<bool>& alive = r.alive;
    for (std::size_t q = 0; q < pq.quads.size(); ++q) {
      if (q < pq.elements.size()) {
        if (!alive[q]) drop[pq.elements[q]] = true;
        continue;
      }
      if (!alive[q]) continue;
      added.push_back(element_of(pq, pq.quads[q], p, shell));
    }
  }
  if (regrids) *regrids = regridded;
  if (kept + regridded == 0) return 0;
  replace_elements(mesh, drop, added);
  return kept;
}

}  // namespace laytracks
