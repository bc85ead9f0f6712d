#include "corridors.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <tuple>

#include "boundary_index.hpp"
#include "laytracks/brep/union_find.hpp"
#include "rail_layer.hpp"

namespace laytracks::cutgraph_detail {
namespace {

/// Relative margin in Eq. (1) so that L / w = k + 1/2 rounds the same way in every pose.
constexpr double kHalfMargin = 1e-9;

/// Point at loop parameter u (wrapped) of a polygon loop.
Vec2 point_at(const std::vector<Vec2>& loop, double u, std::uint32_t* seg, double* s) {
  const std::size_t n = loop.size();
  u = std::fmod(u, static_cast<double>(n));
  if (u < 0) u += static_cast<double>(n);
  std::size_t i = std::min(static_cast<std::size_t>(u), n - 1);
  *seg = static_cast<std::uint32_t>(i);
  *s = u - static_cast<double>(i);
  return lerp(loop[i], loop[(i + 1) % n], *s);
}

/// Length of the loop from parameter u0 to u1 (u1 >= u0, may wrap once).
double length_between(const std::vector<Vec2>& loop, double u0, double u1) {
  const std::size_t n = loop.size();
  double len = 0.0;
  double u = u0;
  while (u < u1 - 1e-15) {
    const double next = std::min(u1, std::floor(u) + 1.0);
    const std::size_t i = static_cast<std::size_t>(std::floor(u)) % n;
    len += (next - u) * distance(loop[i], loop[(i + 1) % n]);
    u = next;
  }
  return len;
}

class Finder {
 public:
  Finder(const Part& part, const std::vector<MedialAxis>& axes, const CutGraph& graph,
         OppositeCache* cache)
      : part_(part), axes_(axes), graph_(graph), index_(part), cache_(cache) {}

  Corridors run() {
    std::size_t loops = 0;
    for (const Patch& p : part_.patches) {
      loop_base_.push_back(loops);
      loops += p.loops.size();
    }
    build_segs(loops);
    now_.resize(loops);
    cursor_.assign(loops, 0);
    UnionFind uf(out_.segs.size());
    for (std::size_t i = 0; i < out_.segs.size(); ++i) {
      link_opposite(i, uf);
      link_across(i, uf);
    }
    std::map<std::size_t, std::size_t> number;
    for (std::size_t i = 0; i < out_.segs.size(); ++i) {
      const std::size_t r = uf.find(i);
      if (!number.count(r)) number[r] = number.size();
      out_.segs[i].corridor = number[r];
    }
    out_.count = number.size();
    if (cache_) cache_->loops = std::move(now_);
    return out_;
  }

 private:
  /// Break points of every loop: its CUT-VERTs and its non-smooth corners.
  void build_segs(std::size_t loops) {
    breaks_.assign(loops, {});
    first_seg_.assign(loops, 0);
    for (const CutVert& c : graph_.cuts) {
      const double n =
          static_cast<double>(part_.patches[c.patch.index()].polygon.loops[c.at.loop].size());
      breaks_[flat(c.patch.value, c.at.loop)].push_back(std::fmod(c.at.u(), n));
    }
    for (std::uint32_t p = 0; p < part_.patches.size(); ++p) {
      const Patch& patch = part_.patches[p];
      for (std::uint32_t l = 0; l < patch.loops.size(); ++l) {
        auto& b = breaks_[flat(p, l)];
        for (std::uint32_t i = 0; i < patch.loops[l].vertices.size(); ++i) {
          if (corner_turn(part_, PatchId(p), l, i) != 0) b.push_back(static_cast<double>(i));
        }
        std::sort(b.begin(), b.end());
        b.erase(std::unique(b.begin(), b.end(), [](double x, double y) { return y - x < 1e-12; }),
                b.end());
        const auto& poly = patch.polygon.loops[l];
        const double n = static_cast<double>(poly.size());
        first_seg_[flat(p, l)] = out_.segs.size();
        if (b.empty()) {  // a loop without rails or corners: one CUT-SEG all round
          out_.segs.push_back({PatchId(p), l, 0.0, n, length_between(poly, 0.0, n), 0, {}, {}});
          continue;
        }
        for (std::size_t k = 0; k < b.size(); ++k) {
          const double u0 = b[k];
          const double u1 = k + 1 < b.size() ? b[k + 1] : b[0] + n;
          out_.segs.push_back({PatchId(p), l, u0, u1, length_between(poly, u0, u1), 0, {}, {}});
        }
      }
    }
  }

  /// The index of loop l of patch p among all patches' loops.
  std::size_t flat(std::uint32_t p, std::uint32_t l) const { return loop_base_[p] + l; }

  /// The CUT-SEG of loop l of patch p that contains parameter u.
  std::size_t seg_at(std::uint32_t p, std::uint32_t l, double u) const {
    const std::size_t first = first_seg_[flat(p, l)];
    const double n = static_cast<double>(part_.patches[p].polygon.loops[l].size());
    u = std::fmod(u, n);
    if (u < 0.0) u += n;
    const auto& b = breaks_[flat(p, l)];
    if (b.empty()) return first;
    const auto k = std::upper_bound(b.begin(), b.end(), u) - b.begin();
    // Before the first break: the last CUT-SEG, which wraps round.
    return first + (k == 0 ? b.size() - 1 : static_cast<std::size_t>(k) - 1);
  }

  /// Joins a CUT-SEG with the CUT-SEGs its points map onto across the medial axis. Several
  /// points are mapped; one that lands on (or within the point tolerance of) a break point or
  /// a corner, or whose axis point is a branch point, is ambiguous, decided by rounding, and
  /// is not used (holes2__cube_holes, a regular octagon in a square: a point mapped through a
  /// branch point joined two corridors in one pose and not in another). (A CUT-SEG that maps into a
  /// concave vertex's fan therefore forms its own corridor with that fan.)
  void link_opposite(std::size_t i, UnionFind& uf) {
    const CutSeg& cs = out_.segs[i];
    const double tol = kSamePointRel * part_.size;
    for (const OppositeCache::Image& q : images(cs)) {
      if (!q.usable) continue;
      if (near_break(cs.patch.value, q.loop, q.u, q.position, tol)) continue;
      uf.unite(i, seg_at(cs.patch.value, q.loop, q.u));
    }
  }

  /// Where CUT-SEG cs's sample points map to across the axis: from the cache when the last
  /// search had this CUT-SEG. CUT-SEGs come loop by loop, each loop's in order.
  const std::array<OppositeCache::Image, OppositeCache::kAt.size()>& images(const CutSeg& cs) {
    const std::size_t l = flat(cs.patch.value, cs.loop);
    std::vector<OppositeCache::Seg>& now = now_[l];
    if (cache_ && l < cache_->loops.size()) {
      const std::vector<OppositeCache::Seg>& was = cache_->loops[l];
      std::size_t& c = cursor_[l];
      while (c < was.size() && was[c].u0 < cs.u0) ++c;
      if (c < was.size() && was[c].u0 == cs.u0 && was[c].u1 == cs.u1) {
        now.push_back(was[c]);
        return now.back().images;
      }
    }
    OppositeCache::Seg seg{cs.u0, cs.u1, {}};
    for (std::size_t k = 0; k < OppositeCache::kAt.size(); ++k)
      seg.images[k] = map_across(cs.patch, cs.loop, cs.u0 + OppositeCache::kAt[k] * (cs.u1 - cs.u0));
    now.push_back(seg);
    return now.back().images;
  }

  OppositeCache::Image map_across(PatchId p, std::uint32_t l, double u) const {
    const auto& poly = part_.patches[p.index()].polygon.loops[l];
    const double tol = kSamePointRel * part_.size;
    OppositeCache::Image out;
    BoundaryPoint bp;
    std::uint32_t seg;
    double s;
    bp.position = point_at(poly, u, &seg, &s);
    bp.site = {BoundarySite::Kind::Segment, l, seg};
    bp.s = s;
    const MedialAxis& axis = axes_[p.index()];
    // Through a branch point (or within the point tolerance of one) the other side is any
    // of its touching points, decided by rounding: not used either.
    const auto m = axis.project(bp);
    if (!m || !m->edge.valid()) return out;
    const MaEdge& me = axis.edge(m->edge);
    for (const MaVertexId v : {me.a, me.b})
      if (axis.vertex(v).degree >= 3 && distance(axis.vertex(v).position, m->position) <= tol)
        return out;
    const auto q = axis.touching_point(*m, axis.far_side(*m, bp));
    if (q.site.kind == BoundarySite::Kind::Corner) return out;
    out.usable = true;
    out.loop = q.site.loop;
    out.u = static_cast<double>(q.site.index) + q.s;
    out.position = q.position;
    return out;
  }

  /// True when a point of loop l (parameter u, position x) is within tol of a break point.
  bool near_break(std::uint32_t p, std::uint32_t l, double u, Vec2 x, double tol) const {
    const auto& b = breaks_[flat(p, l)];
    if (b.empty()) return false;
    const auto& poly = part_.patches[p].polygon.loops[l];
    const double n = static_cast<double>(poly.size());
    u = std::fmod(u, n);
    if (u < 0.0) u += n;
    const auto k = static_cast<std::size_t>(std::upper_bound(b.begin(), b.end(), u) - b.begin());
    std::uint32_t seg;
    double s;
    for (std::size_t j : {(k + b.size() - 1) % b.size(), k % b.size()}) {
      if (distance(point_at(poly, b[j], &seg, &s), x) <= tol) return true;
    }
    return false;
  }

  /// Joins a CUT-SEG with the CUT-SEGs of the other patches on each B-Rep edge it covers.
  void link_across(std::size_t i, UnionFind& uf) const {
    const CutSeg& cs = out_.segs[i];
    const std::size_t n = part_.patches[cs.patch.index()].polygon.loops[cs.loop].size();
    for (double u = cs.u0; u < cs.u1 - 1e-12;) {
      const double next = std::min(cs.u1, std::floor(u) + 1.0);
      const double mid = 0.5 * (u + next);
      const std::uint32_t seg =
          static_cast<std::uint32_t>(static_cast<std::size_t>(std::floor(mid)) % n);
      const double s = mid - std::floor(mid);
      const EdgeId e = index_.edge_at(cs.patch, cs.loop, seg);
      const double t = index_.edge_param(cs.patch, cs.loop, seg, s);
      for (const SegmentRef& r : index_.segments_of(e)) {
        if (r.patch == cs.patch && r.loop == cs.loop && r.seg == seg) continue;
        const double s2 = r.forward ? t : 1.0 - t;
        uf.unite(i, seg_at(r.patch.value, r.loop, static_cast<double>(r.seg) + s2));
      }
      u = next;
    }
  }

  const Part& part_;
  const std::vector<MedialAxis>& axes_;
  const CutGraph& graph_;
  BoundaryIndex index_;
  Corridors out_;
  std::vector<std::size_t> first_seg_;         ///< by loop: its first CUT-SEG
  std::vector<std::vector<double>> breaks_;    ///< by loop: its break points, ascending
  OppositeCache* cache_;
  std::vector<std::size_t> loop_base_;              ///< patch -> its first loop's index
  std::vector<std::vector<OppositeCache::Seg>> now_;  ///< this search's CUT-SEGs, by loop
  std::vector<std::size_t> cursor_;                 ///< by loop: where the sweep of the cache is
};

}  // namespace

Corridors find_corridors(const Part& part,
                         const std::vector<MedialAxis>& axes,
                         const CutGraph& graph,
                         OppositeCache* cache) {
  return Finder(part, axes, graph, cache).run();
}

std::vector<CorridorPiece> corridor_pieces_impl(const Part& part,
                                                const std::vector<MedialAxis>& axes,
                                                const CutGraph& graph,
                                                OppositeCache* cache) {
  return corridor_pieces_of(part, graph, find_corridors(part, axes, graph, cache));
}

std::vector<CorridorPiece> corridor_pieces_of(const Part& part,
                                              const CutGraph& graph,
                                              Corridors c) {
  // Where the rail at each break point meets the axis: from the rail segments, else the corner.
  std::map<LoopKey, Vec2> ma_at;
  const auto key = [&](PatchId p, std::uint32_t loop, double u) {
    return loop_key(part, p, loop, u);
  };
  for (const RailSegment& s : graph.segments) {
    const CutVert& cv = graph.cuts[s.cut.index()];
    ma_at[key(cv.patch, cv.at.loop, cv.at.u())] = graph.macuts[s.ma.index()].point.position;
  }
  for (CutSeg& cs : c.segs) {
    const auto& poly = part.patches[cs.patch.index()].polygon.loops[cs.loop];
    std::uint32_t seg;
    double s;
    const auto end_point = [&](double u) {
      const auto it = ma_at.find(key(cs.patch, cs.loop, u));
      return it != ma_at.end() ? it->second : point_at(poly, u, &seg, &s);
    };
    cs.ma0 = end_point(cs.u0);
    cs.ma1 = end_point(cs.u1);
  }
  return c.segs;
}

namespace {

/// The boundary point at arc length x along CUT-SEG cs.
BoundaryPoint point_at_length(const Part& part, const CutSeg& cs, double x) {
  const auto& poly = part.patches[cs.patch.index()].polygon.loops[cs.loop];
  double u = cs.u0;
  double walked = 0.0;
  while (true) {
    const double next = std::min(cs.u1, std::floor(u) + 1.0);
    const std::size_t i = static_cast<std::size_t>(std::floor(u)) % poly.size();
    const double seg_len = distance(poly[i], poly[(i + 1) % poly.size()]);
    const double piece = (next - u) * seg_len;
    if (walked + piece >= x || next >= cs.u1) {
      u += seg_len > 0.0 ? (x - walked) / seg_len : 0.0;
      break;
    }
    walked += piece;
    u = next;
  }
  BoundaryPoint bp;
  std::uint32_t seg;
  double s;
  bp.position = point_at(poly, u, &seg, &s);
  if (x >= cs.length && s == 0.0) {  // the far end on its own segment, not the next one's start
    seg = static_cast<std::uint32_t>((seg + poly.size() - 1) % poly.size());
    s = 1.0;
  }
  bp.site = {BoundarySite::Kind::Segment, cs.loop, seg};
  bp.s = s;
  return bp;
}

/// Seeds at these arc lengths along CUT-SEG cs.
void seeds_at(const Part& part, const CutSeg& cs, const std::vector<double>& at,
              std::vector<TrackSeed>& seeds) {
  for (double x : at) seeds.push_back({cs.patch, point_at_length(part, cs, x)});
}

/// Eq. (1), ceil(L / w - 0.5): halves round down. The small margin keeps a length of exactly
/// k + 1/2 widths from rounding differently when the part is turned.
double track_count(double length, double width) {
  return std::max(1.0, std::ceil(length / width - 0.5 - kHalfMargin));
}

}  // namespace

namespace {

/// The longest CUT-SEG of each corridor (the first one on ties: deterministic).
std::vector<std::size_t> masters(const Corridors& corridors) {
  std::vector<std::size_t> master(corridors.count, SIZE_MAX);
  for (std::size_t i = 0; i < corridors.segs.size(); ++i) {
    // Lengths equal within rounding are ties, kept by the first: the same in every pose.
    std::size_t& m = master[corridors.segs[i].corridor];
    if (m == SIZE_MAX || corridors.segs[i].length > corridors.segs[m].length * (1.0 + kHalfMargin))
      m = i;
  }
  master.erase(std::remove(master.begin(), master.end(), SIZE_MAX), master.end());
  return master;
}

/// Two widths this close (relative) are equal: both ends of the corridor step together.
constexpr double kSameWidthRel = 1e-6;

/// The width law is read this far (relative to the CUT-SEG's length) inside a CUT-SEG's ends:
/// at a corner itself, which side's disk a point belongs to is decided by rounding.
constexpr double kEndInset = 1e-6;

/// Delta S at arc length x along CUT-SEG cs, from the width law.
double width_at(const Part& part, const TrackWidthLaw& law, const CutSeg& cs, double x) {
  const double inset = kEndInset * cs.length;
  return law.width(cs.patch, point_at_length(part, cs, std::clamp(x, inset, cs.length - inset)));
}

}  // namespace

std::vector<double> march_tracks(double length, const std::function<double(double)>& width) {
  std::vector<double> left, right;
  double lo = 0.0, hi = length;
  // The width at each end, read again only when that end moves (each read is a probe of the
  // radius function through the patches).
  double w0 = width(lo), wn = width(hi);
  // Each step places at least one end width, which is positive: bounded by length / floor.
  while (hi > lo) {
    const double rem = hi - lo;
    const double ratio = rem / (w0 + wn);
    if (ratio < kOneCutRatio * (1.0 + kHalfMargin)) break;  // one track: no CUT-VERT
    if (ratio <= kManyCutsRatio * (1.0 + kHalfMargin)) {
      // One CUT-VERT, splitting the rest in the ratio of the end widths (Step 3).
      left.push_back(lo + rem * w0 / (w0 + wn));
      break;
    }
    // Room for more: step from the narrower end (both when they are equal), so that the
    // corridor is paved from its fine end, whichever end of the loop that is.
    const bool same = std::abs(w0 - wn) <= kSameWidthRel * std::max(w0, wn);
    const bool step_lo = same || w0 < wn;
    const bool step_hi = same || !step_lo;
    if (step_lo) {
      lo += w0;
      left.push_back(lo);
      w0 = width(lo);
    }
    if (step_hi) {
      hi -= wn;
      right.push_back(hi);
      wn = width(hi);
    }
  }
  left.insert(left.end(), right.rbegin(), right.rend());
  return left;
}

namespace {

/// Where the track rails cut CUT-SEG cs (arc lengths along it): Eq. (1)'s equal tracks, or
/// Algorithm III's march from the width law.
std::vector<double> cuts_along(const Part& part, const CutSeg& cs, const TrackSpacing& spacing) {
  if (spacing.law) {
    return march_tracks(cs.length,
                        [&](double x) { return width_at(part, *spacing.law, cs, x); });
  }
  const double tracks = track_count(cs.length, spacing.width);
  std::vector<double> at;
  for (int k = 1; k < static_cast<int>(tracks); ++k) at.push_back(cs.length * k / tracks);
  return at;
}

/// True when CUT-SEG cs is longer than kGapWidths x its width (adaptive: the mean of the
/// widths at its ends).
bool is_gap(const Part& part, const CutSeg& cs, const TrackSpacing& spacing) {
  const double width =
      spacing.law ? 0.5 * (width_at(part, *spacing.law, cs, 0.0) +
                           width_at(part, *spacing.law, cs, cs.length))
                  : spacing.width;
  return cs.length > kGapWidths * width * (1.0 + kHalfMargin);
}

}  // namespace

std::vector<TrackSeed> track_seeds(const Part& part,
                                   const Corridors& corridors,
                                   const TrackSpacing& spacing) {
  std::vector<TrackSeed> seeds;
  for (std::size_t m : masters(corridors)) {
    const CutSeg& cs = corridors.segs[m];
    seeds_at(part, cs, cuts_along(part, cs, spacing), seeds);
  }
  return seeds;
}

std::vector<TrackSeed> gap_seeds(const Part& part,
                                 const Corridors& corridors,
                                 const TrackSpacing& spacing) {
  std::vector<TrackSeed> seeds;
  for (const CutSeg& cs : corridors.segs) {
    if (is_gap(part, cs, spacing)) seeds_at(part, cs, cuts_along(part, cs, spacing), seeds);
  }
  return seeds;
}

}  // namespace laytracks::cutgraph_detail

namespace laytracks {

std::vector<CorridorPiece> corridor_pieces(const Part& part,
                                           const std::vector<MedialAxis>& axes,
                                           const CutGraph& graph) {
  return cutgraph_detail::corridor_pieces_impl(part, axes, graph);
}

}  // namespace laytracks
