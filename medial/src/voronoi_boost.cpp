// The segment Voronoi diagram through Boost.Polygon's voronoi (the Boost backend): the only
// translation unit of medial/ that includes it. See docs/medial-backends.md for the figures.
//
// Boost.Polygon builds the diagram by a sweep line with exact predicates on 32-bit integer
// input, so the corners are first rounded to a grid:
// - the grid: the polygon's box is centred on 0 and scaled uniformly so that its larger
//   half-extent is 2^30 grid units; a corner p becomes llround((p - centre) / unit). One grid
//   unit is thus 2^-30 (9.3e-10) of the box's larger half-extent, at most 4.7e-10 of the box's
//   diagonal; rounding moves a corner by at most 0.71 unit. Corners build_part lets through
//   are at least 1e-9 x the part's size apart, over 2 units, so they stay distinct; two corners
//   on the same grid point are refused all the same. Coordinates stay within +-(2^30 + 1),
//   well inside Boost's 32-bit input.
// - the topology (which sites are neighbours, which corner is reflex) is decided exactly on the
//   grid, and the turns we report are computed exactly on the same grid points, so they agree
//   with it. Everything else keeps the input doubles: Boost's vertices (accurate on the grid)
//   are mapped back and refined against the double sites (refine_vertex).
// - the grid's diagram is that of a polygon up to a unit away from the input, and two things
//   can differ from the input's diagram, both mended here: a nearly straight corner can change
//   convexity (keep_convexity moves it back to the right side), and where a short segment faces
//   far-away sites two vertices can come in the reverse order (unfold flips them back). Where
//   either cannot be mended the diagram is refused and VoronoiBackend::Boost uses CGAL.
#include <algorithm>
#include <boost/polygon/point_data.hpp>
#include <boost/polygon/segment_data.hpp>
#include <boost/polygon/voronoi.hpp>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>

#include "laytracks/brep/error.hpp"
#include "sites.hpp"
#include "voronoi.hpp"

namespace laytracks::medial_detail {
namespace {

namespace bp = boost::polygon;
using GridPoint = bp::point_data<std::int32_t>;
using GridSegment = bp::segment_data<std::int32_t>;
using Diagram = bp::voronoi_diagram<double>;
using Cell = Diagram::cell_type;
using Edge = Diagram::edge_type;
using Vertex = Diagram::vertex_type;

/// The rounding of the polygon's corners onto Boost's integer grid (see the file comment).
class Grid {
 public:
  /// The grid of a polygon's box. Throws InternalError for an empty or non-finite box.
  explicit Grid(const Polygon2& polygon) {
    Box2 box;
    for (const auto& loop : polygon.loops) {
      for (Vec2 p : loop) box.add(p);
    }
    const double half = 0.5 * std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
    if (box.empty() || !(half > 0.0) || !std::isfinite(half)) {
      throw InternalError("medial axis (Boost backend): the polygon's box is empty or not finite");
    }
    centre_ = lerp(box.lo, box.hi, 0.5);
    unit_ = std::ldexp(half, -30);
  }

  /// p in grid units, before rounding.
  Vec2 scale(Vec2 p) const { return {(p.x - centre_.x) / unit_, (p.y - centre_.y) / unit_}; }

  /// The grid point nearest to p.
  GridPoint round(Vec2 p) const {
    const Vec2 q = scale(p);
    return {static_cast<std::int32_t>(std::llround(q.x)),
            static_cast<std::int32_t>(std::llround(q.y))};
  }

  /// A point given in grid units, back in the polygon's coordinates.
  Vec2 unround(double x, double y) const { return {centre_.x + x * unit_, centre_.y + y * unit_}; }

 private:
  Vec2 centre_;
  double unit_ = 1.0;
};

/// Exact sign of the turn a -> b -> c on the grid: +1 left, -1 right, 0 straight. Coordinates
/// are within +-(2^30 + 1), so each product of differences stays below 2^63.
std::int8_t grid_turn(const GridPoint& a, const GridPoint& b, const GridPoint& c) {
  const std::int64_t ux = std::int64_t{b.x()} - a.x();
  const std::int64_t uy = std::int64_t{b.y()} - a.y();
  const std::int64_t vx = std::int64_t{c.x()} - b.x();
  const std::int64_t vy = std::int64_t{c.y()} - b.y();
  const std::int64_t lhs = ux * vy;
  const std::int64_t rhs = uy * vx;
  return static_cast<std::int8_t>((lhs > rhs) - (lhs < rhs));
}

class Builder {
 public:
  explicit Builder(const Polygon2& polygon) : polygon_(polygon), grid_(polygon) {}

  /// Rounds, builds Boost's diagram, converts it to our contract and refines it; empty, with
  /// the reason in *why, when the rounding changes the diagram beyond local repair.
  std::optional<VoronoiDiagram> run(std::string* why) {
    round_corners();
    if (!keep_convexity()) {
      *why =
          "rounding to the grid changes the convexity of a corner, and no grid point within 2 "
          "units mends it";
      return std::nullopt;
    }
    std::vector<GridSegment> segments;
    segments.reserve(points_.size());
    for (std::uint32_t l = 0; l < polygon_.loops.size(); ++l) {
      const std::size_t n = polygon_.loops[l].size();
      for (std::size_t i = 0; i < n; ++i) {
        segments.emplace_back(point(l, i), point(l, (i + 1) % n));
        flat_.push_back({BoundarySite::Kind::Segment, l, static_cast<std::uint32_t>(i)});
      }
    }
    bp::construct_voronoi(segments.begin(), segments.end(), &vd_);
    VoronoiDiagram out;
    out.turn = turns();
    cell_sites();
    mark_left_edges();
    collect_vertices(out);
    collect_edges(out);
    if (!unfold(out)) {
      *why = "rounding to the grid folds the diagram where no flip mends it";
      return std::nullopt;
    }
    return out;
  }

 private:
  /// Rounds every corner to the grid; throws InternalError if two share a grid point.
  void round_corners() {
    loop_start_.assign(polygon_.loops.size(), 0);
    for (std::size_t l = 0; l < polygon_.loops.size(); ++l) {
      loop_start_[l] = points_.size();
      for (Vec2 p : polygon_.loops[l]) points_.push_back(grid_.round(p));
    }
    std::vector<std::size_t> order(points_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto less = [&](std::size_t a, std::size_t b) {
      const GridPoint& p = points_[a];
      const GridPoint& q = points_[b];
      return p.x() != q.x() ? p.x() < q.x() : p.y() != q.y() ? p.y() < q.y() : a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t k = 1; k < order.size(); ++k) {
      if (points_[order[k - 1]] == points_[order[k]]) {
        throw InternalError("medial axis (Boost backend): corners " + label(order[k - 1]) +
                            " and " + label(order[k]) +
                            " round to the same point of the integer grid (2^31 units across "
                            "the polygon's box) that Boost.Polygon needs: they are closer than "
                            "about 1e-9 of the polygon's size");
      }
    }
  }

  /// Whether corner i of loop l is convex on the grid exactly when it is on the input.
  bool same_convexity(std::size_t l, std::size_t i) const {
    const std::size_t n = polygon_.loops[l].size();
    const bool grid_convex =
        grid_turn(point(l, (i + n - 1) % n), point(l, i), point(l, (i + 1) % n)) > 0;
    return grid_convex == (exact_[l][i] > 0);
  }

  /// Rounding can change the sign of a nearly straight corner's turn (below about a grid unit
  /// over the length of its segments), and a convex corner ends a branch of the axis where a
  /// reflex one does not. So such corners are moved back (mend()), each corner staying within
  /// 2 grid units of its exact position. (A straight corner may become reflex: that only adds
  /// degree-2 vertices to the axis.) Returns false when some corner cannot be mended.
  bool keep_convexity() {
    exact_ = exact_turns(polygon_);
    std::vector<std::pair<std::size_t, std::size_t>> bad;
    for (std::size_t l = 0; l < polygon_.loops.size(); ++l) {
      for (std::size_t i = 0; i < polygon_.loops[l].size(); ++i) {
        if (!same_convexity(l, i)) bad.emplace_back(l, i);
      }
    }
    if (bad.empty()) return true;
    std::unordered_set<std::uint64_t> occupied;
    for (const GridPoint& p : points_) occupied.insert(key(p));
    for (int pass = 0; pass < 4 && !bad.empty(); ++pass) {
      std::vector<std::pair<std::size_t, std::size_t>> still;
      for (const auto& [l, i] : bad) {
        if (!same_convexity(l, i) && !mend(l, i, occupied)) still.emplace_back(l, i);
      }
      bad = std::move(still);
    }
    return bad.empty();
  }

  /// Mends corner i of loop l as keep_convexity() describes, moving it and its two neighbours
  /// (an inflection of a finely polygonised curve can need both sides moved): the choice with
  /// the least squared displacement that makes corner i right and no corner from i - 2 to i + 2
  /// wrong that was right. False when no choice within 2 units of the exact positions will do.
  bool mend(std::size_t l, std::size_t i, std::unordered_set<std::uint64_t>& occupied) {
    const std::size_t n = polygon_.loops[l].size();
    const std::size_t moved[3] = {(i + n - 1) % n, i, (i + 1) % n};
    std::vector<std::size_t> checked;
    std::vector<bool> was_ok;
    for (std::size_t k = 0; k < 5; ++k) {
      checked.push_back((i + n - 2 + k) % n);
      was_ok.push_back(same_convexity(l, checked.back()));
    }
    // The grid points each moved corner may take, with their squared distances to its target.
    GridPoint original[3];
    std::vector<std::pair<GridPoint, double>> options[3];
    for (std::size_t m = 0; m < 3; ++m) {
      original[m] = point(l, moved[m]);
      const Vec2 target = grid_.scale(polygon_.loops[l][moved[m]]);
      for (std::int32_t dx = -2; dx <= 2; ++dx) {
        for (std::int32_t dy = -2; dy <= 2; ++dy) {
          const GridPoint c(original[m].x() + dx, original[m].y() + dy);
          const double d = std::hypot(c.x() - target.x, c.y() - target.y);
          const bool own = dx == 0 && dy == 0;
          if (own || (d <= 2.0 && occupied.count(key(c)) == 0)) options[m].emplace_back(c, d * d);
        }
      }
    }
    const auto slot = [&](std::size_t m) -> GridPoint& {
      return points_[loop_start_[l] + moved[m]];
    };
    double best_cost = INFINITY;
    GridPoint best[3] = {original[0], original[1], original[2]};
    for (const auto& p0 : options[0]) {
      for (const auto& p1 : options[1]) {
        for (const auto& p2 : options[2]) {
          const double cost = p0.second + p1.second + p2.second;
          if (cost >= best_cost || p0.first == p1.first || p1.first == p2.first ||
              p0.first == p2.first) {
            continue;
          }
          slot(0) = p0.first;
          slot(1) = p1.first;
          slot(2) = p2.first;
          bool ok = same_convexity(l, i);
          for (std::size_t k = 0; k < checked.size() && ok; ++k) {
            ok = !was_ok[k] || same_convexity(l, checked[k]);
          }
          if (ok) {
            best_cost = cost;
            best[0] = p0.first;
            best[1] = p1.first;
            best[2] = p2.first;
          }
        }
      }
    }
    for (std::size_t m = 0; m < 3; ++m) slot(m) = best[m];
    if (!std::isfinite(best_cost)) return false;
    for (std::size_t m = 0; m < 3; ++m) {
      if (best[m] == original[m]) continue;
      occupied.erase(key(original[m]));
      occupied.insert(key(best[m]));
    }
    return true;
  }

  /// A grid point as one integer, for hashing.
  static std::uint64_t key(const GridPoint& p) {
    return (std::uint64_t{static_cast<std::uint32_t>(p.x())} << 32) |
           static_cast<std::uint32_t>(p.y());
  }

  /// "loop l corner i" for a flat corner index.
  std::string label(std::size_t flat) const {
    std::size_t l = loop_start_.size() - 1;
    while (loop_start_[l] > flat) --l;
    return "(loop " + std::to_string(l) + ", corner " + std::to_string(flat - loop_start_[l]) + ")";
  }

  /// The grid point of corner i of loop l.
  const GridPoint& point(std::size_t l, std::size_t i) const { return points_[loop_start_[l] + i]; }

  /// Exact turn signs at every corner, on the grid.
  std::vector<std::vector<std::int8_t>> turns() const {
    std::vector<std::vector<std::int8_t>> turn(polygon_.loops.size());
    for (std::size_t l = 0; l < polygon_.loops.size(); ++l) {
      const std::size_t n = polygon_.loops[l].size();
      turn[l].resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        turn[l][i] = grid_turn(point(l, (i + n - 1) % n), point(l, i), point(l, (i + 1) % n));
      }
    }
    return turn;
  }

  /// Index of a cell, vertex or edge in Boost's arrays.
  std::size_t index(const Cell* c) const {
    return static_cast<std::size_t>(c - vd_.cells().data());
  }
  std::size_t index(const Vertex* v) const {
    return static_cast<std::size_t>(v - vd_.vertices().data());
  }
  std::size_t index(const Edge* e) const {
    return static_cast<std::size_t>(e - vd_.edges().data());
  }

  /// The boundary site of every cell: a segment cell is its segment, a point cell (the start
  /// or end point of an input segment; Boost keeps one cell per distinct point) its corner.
  void cell_sites() {
    site_.resize(vd_.cells().size());
    for (const Cell& c : vd_.cells()) {
      if (c.source_index() >= flat_.size()) {
        throw InternalError("medial axis (Boost backend): a Voronoi cell has no origin");
      }
      const BoundarySite seg = flat_[c.source_index()];
      const auto n = static_cast<std::uint32_t>(polygon_.loops[seg.loop].size());
      BoundarySite& s = site_[index(&c)];
      switch (c.source_category()) {
        case bp::SOURCE_CATEGORY_SEGMENT_START_POINT:
          s = {BoundarySite::Kind::Corner, seg.loop, seg.index};
          break;
        case bp::SOURCE_CATEGORY_SEGMENT_END_POINT:
          s = {BoundarySite::Kind::Corner, seg.loop, (seg.index + 1) % n};
          break;
        case bp::SOURCE_CATEGORY_INITIAL_SEGMENT:
        case bp::SOURCE_CATEGORY_REVERSE_SEGMENT:
          s = seg;
          break;
        default:
          throw InternalError("medial axis (Boost backend): a Voronoi cell of an unknown kind");
      }
    }
  }

  /// The boundary site of a Boost cell (after cell_sites()).
  const BoundarySite& site(const Cell* c) const { return site_[index(c)]; }

  /// Marks the half-edges on the inner (left) side of every segment site. A segment's cell is
  /// a strip around it whose boundary, counter-clockwise, runs along its right side from its
  /// start corner to its end corner, then back along its left side. The boundary meets the
  /// segment's line only at the two end points, on the normal to the segment's own end point
  /// (a secondary edge: one per end point, whether that corner is convex, reflex or straight)
  /// or at a vertex where that normal ends. So the half-edges strictly after the end point's
  /// normal and before the start point's normal are on the left: combinatorial, hence exact on
  /// the grid, and independent of the computed positions. Where that pattern is not found (a
  /// degenerate cell), the side is read from Boost's vertices instead.
  void mark_left_edges() {
    left_.assign(vd_.edges().size(), 0);
    std::vector<const Edge*> ring;
    for (const Cell& c : vd_.cells()) {
      const BoundarySite& s = site(&c);
      if (s.kind != BoundarySite::Kind::Segment || c.is_degenerate()) continue;
      ring.clear();
      const Edge* e = c.incident_edge();
      do {
        ring.push_back(e);
        e = e->next();
      } while (e != c.incident_edge() && e != nullptr);
      const auto n = static_cast<std::uint32_t>(polygon_.loops[s.loop].size());
      const BoundarySite start{BoundarySite::Kind::Corner, s.loop, s.index};
      const BoundarySite end{BoundarySite::Kind::Corner, s.loop, (s.index + 1) % n};
      std::size_t at_start = ring.size();
      std::size_t at_end = ring.size();
      bool unique = e != nullptr;
      for (std::size_t k = 0; k < ring.size(); ++k) {
        const BoundarySite& other = site(ring[k]->twin()->cell());
        if (other == start) {
          unique = unique && at_start == ring.size();
          at_start = k;
        } else if (other == end) {
          unique = unique && at_end == ring.size();
          at_end = k;
        }
      }
      if (unique && at_start != ring.size() && at_end != ring.size()) {
        for (std::size_t k = (at_end + 1) % ring.size(); k != at_start; k = (k + 1) % ring.size()) {
          left_[index(ring[k])] = 1;
        }
        continue;
      }
      for (const Edge* r : ring) {
        if (r->is_finite() && on_left_by_position(*r, s)) left_[index(r)] = 1;
      }
    }
  }

  /// Fallback: whether a bounded edge of segment s's cell is on s's left, from the end point of
  /// the edge farther from s's line (Boost's vertices are accurate to a few ulps on the grid).
  bool on_left_by_position(const Edge& e, const BoundarySite& s) const {
    const std::size_t n = polygon_.loops[s.loop].size();
    const GridPoint& a = point(s.loop, s.index);
    const GridPoint& b = point(s.loop, (s.index + 1) % n);
    const double dx = double(b.x()) - double(a.x());
    const double dy = double(b.y()) - double(a.y());
    const auto side = [&](const Vertex* v) {
      return dx * (v->y() - double(a.y())) - dy * (v->x() - double(a.x()));
    };
    const double s0 = side(e.vertex0());
    const double s1 = side(e.vertex1());
    return (std::fabs(s0) >= std::fabs(s1) ? s0 : s1) > 0.0;
  }

  /// One VoronoiVertex per Boost vertex: its cells counter-clockwise (rot_next turns
  /// counter-clockwise around a vertex, and the cell of an outgoing half-edge is on its left).
  void collect_vertices(VoronoiDiagram& out) {
    out.vertices.resize(vd_.vertices().size());
    ccw_.resize(vd_.vertices().size());
    for (const Vertex& v : vd_.vertices()) {
      VoronoiVertex& vv = out.vertices[index(&v)];
      vv.position = grid_.unround(v.x(), v.y());
      const Edge* e = v.incident_edge();
      do {
        vv.sites.push_back(site(e->cell()));
        e = e->rot_next();
      } while (e != v.incident_edge());
      remove_repeats(vv.sites);
      if (vv.sites.size() > 3) {
        ccw_[index(&v)] = vv.sites;
        spread_first_three(vv);
      }
    }
  }

  /// Removes later repetitions of a site, keeping the cyclic order of the first occurrences.
  static void remove_repeats(std::vector<BoundarySite>& sites) {
    std::vector<BoundarySite> sorted = sites;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end()) return;
    std::vector<BoundarySite> unique;
    for (const BoundarySite& s : sites) {
      if (std::find(unique.begin(), unique.end(), s) == unique.end()) unique.push_back(s);
    }
    sites = std::move(unique);
  }

  /// Puts first, in counter-clockwise order, three sites of a cocircular vertex whose touching
  /// points span a large triangle (refine_vertex computes the disk from those three); the
  /// others follow in their order. Greedy: site 0, the site touching farthest from it, then the
  /// one farthest from the line through both.
  void spread_first_three(VoronoiVertex& vv) const {
    const std::size_t k = vv.sites.size();
    std::vector<Vec2> touch(k);
    for (std::size_t i = 0; i < k; ++i) touch[i] = site_foot(polygon_, vv.sites[i], vv.position);
    std::size_t j = 1;
    for (std::size_t i = 2; i < k; ++i) {
      if (distance(touch[i], touch[0]) > distance(touch[j], touch[0])) j = i;
    }
    std::size_t m = j == 1 ? 2 : 1;
    const auto area = [&](std::size_t i) {
      return std::fabs(cross(touch[j] - touch[0], touch[i] - touch[0]));
    };
    for (std::size_t i = 1; i < k; ++i) {
      if (i != j && area(i) > area(m)) m = i;
    }
    std::size_t picks[3] = {0, std::min(j, m), std::max(j, m)};
    std::vector<BoundarySite> ordered;
    ordered.reserve(k);
    for (std::size_t p : picks) ordered.push_back(vv.sites[p]);
    for (std::size_t i = 0; i < k; ++i) {
      if (i != picks[0] && i != picks[1] && i != picks[2]) ordered.push_back(vv.sites[i]);
    }
    vv.sites = std::move(ordered);
  }

  /// Each bounded edge once, walking from vertex0 to vertex1 (its cell on the left).
  void collect_edges(VoronoiDiagram& out) const {
    for (const Edge& e : vd_.edges()) {
      if (e.twin() < &e || !e.is_finite()) continue;
      VoronoiEdge ve;
      ve.a = static_cast<std::uint32_t>(index(e.vertex0()));
      ve.b = static_cast<std::uint32_t>(index(e.vertex1()));
      ve.left = site(e.cell());
      ve.right = site(e.twin()->cell());
      ve.medial = is_medial(e, ve, out.turn);
      out.edges.push_back(ve);
    }
  }

  /// Whether a bounded Voronoi edge belongs to the medial axis (the rules of the CGAL backend).
  bool is_medial(const Edge& e,
                 const VoronoiEdge& ve,
                 const std::vector<std::vector<std::int8_t>>& turn) const {
    // Two segments: inside when the edge is on the left (inner) side of both. The two cells
    // agree on a consistent diagram; should they not, Boost's vertices decide.
    const bool left_of_cell = left_[index(&e)] != 0;
    const bool left_of_twin = left_[index(e.twin())] != 0;
    const bool inner =
        left_of_cell == left_of_twin ? left_of_cell : on_left_by_position(e, ve.left);
    return medial_by_sites(ve.left, ve.right, turn, inner);
  }

  /// The medial rule from an edge's two sites: never the normal between a segment and its own
  /// end point; with a corner, medial when every corner is reflex (its cell is then inside);
  /// between two segments, `inner` (whether the edge is on their inner side).
  bool medial_by_sites(const BoundarySite& left,
                       const BoundarySite& right,
                       const std::vector<std::vector<std::int8_t>>& turn,
                       bool inner) const {
    const auto is_corner = [](const BoundarySite& s) {
      return s.kind == BoundarySite::Kind::Corner;
    };
    if (is_endpoint_of(polygon_, left, right) || is_endpoint_of(polygon_, right, left)) {
      return false;
    }
    if (is_corner(left) || is_corner(right)) {
      for (const BoundarySite& s : {left, right}) {
        if (is_corner(s) && turn[s.loop][s.index] >= 0) return false;
      }
      return true;
    }
    return inner;
  }

  /// Refines every vertex against the input doubles (refine_vertex), then mends the folds: the
  /// grid moves each corner by up to a grid unit, which turns a short segment's normal by up to
  /// about a unit over its length in units, and far from it (at a distance r) that moves the
  /// Voronoi vertices it ends by r / length units. Where two such vertices were closer than
  /// that, Boost's order of them along their bisector can be the reverse of the input's: once
  /// refined, the medial edge between them points backwards. That is one Delaunay edge on the
  /// wrong side of a near-cocircular quadrilateral of sites, and one flip mends it (Lawson's
  /// flip, with "points backwards" as the test; a cocircular vertex is split first). False when
  /// a fold cannot be mended that way (edges that do not match their vertices' sites, or no end
  /// to the flips).
  bool unfold(VoronoiDiagram& out) {
    Box2 box;
    for (const auto& loop : polygon_.loops) {
      for (Vec2 p : loop) box.add(p);
    }
    size_ = box.diagonal();
    centre_ = lerp(box.lo, box.hi, 0.5);
    for (auto& v : out.vertices) {
      v.position = refine_vertex(polygon_, v.sites, v.position, centre_, size_);
    }
    incident_.assign(out.vertices.size(), {});
    for (std::uint32_t i = 0; i < out.edges.size(); ++i) {
      incident_[out.edges[i].a].push_back(i);
      incident_[out.edges[i].b].push_back(i);
    }
    std::vector<std::uint32_t> queue;
    for (std::uint32_t i = 0; i < out.edges.size(); ++i) {
      if (points_backwards(out, i)) queue.push_back(i);
    }
    std::size_t budget = 4 * queue.size() + 16;
    while (!queue.empty()) {
      const std::uint32_t i = queue.back();
      queue.pop_back();
      if (!points_backwards(out, i)) continue;
      if (budget == 0 || !flip(out, i)) return false;
      --budget;
      for (const std::uint32_t v : {out.edges[i].a, out.edges[i].b}) {
        for (const std::uint32_t k : incident_[v]) {
          if (points_backwards(out, k)) queue.push_back(k);
        }
      }
    }
    return true;
  }

  /// Whether medial edge i, once refined, runs against its sites: its left site on its right
  /// or the reverse. Tested at the chord's middle, so only for edges short next to their
  /// distance to the sites (folds are), and not for edges below the merge tolerance.
  bool points_backwards(const VoronoiDiagram& out, std::uint32_t i) const {
    const VoronoiEdge& e = out.edges[i];
    if (!e.medial) return false;
    const Vec2 a = out.vertices[e.a].position;
    const Vec2 b = out.vertices[e.b].position;
    const Vec2 d = b - a;
    const double length = norm(d);
    if (!(length > kMergeRel * size_)) return false;
    const Vec2 mid = lerp(a, b, 0.5);
    const Vec2 fl = site_foot(polygon_, e.left, mid);
    const Vec2 fr = site_foot(polygon_, e.right, mid);
    if (length > 0.1 * std::min(distance(fl, mid), distance(fr, mid))) return false;
    return !(cross(d, fl - mid) > 0.0) || !(cross(d, fr - mid) < 0.0);
  }

  /// Flips medial edge i between vertices a (sites L, A, R counter-clockwise) and b (R, B, L),
  /// L on its left: it becomes the edge A|B between a (now L, A, B) and b (now R, B, A), B on
  /// its left; the edge L|B moves from b to a and A|R from a to b. False when the vertices are
  /// not of that form.
  bool flip(VoronoiDiagram& out, std::uint32_t i) {
    for (const std::uint32_t v : {out.edges[i].a, out.edges[i].b}) {
      if (out.vertices[v].sites.size() > 3 && !split(out, v)) return false;
    }
    VoronoiEdge& e = out.edges[i];
    const std::uint32_t a = e.a;
    const std::uint32_t b = e.b;
    if (out.vertices[a].sites.size() != 3 || out.vertices[b].sites.size() != 3 ||
        incident_[a].size() != 3 || incident_[b].size() != 3) {
      return false;
    }
    const BoundarySite l = e.left;
    const BoundarySite r = e.right;
    const auto third = [&](std::uint32_t v, BoundarySite* s) {
      int found = 0;
      for (const BoundarySite& x : out.vertices[v].sites) {
        if (x != l && x != r) {
          *s = x;
          ++found;
        }
      }
      return found == 1;
    };
    BoundarySite sa;
    BoundarySite sb;
    if (!third(a, &sa) || !third(b, &sb) || sa == sb) return false;
    const auto joins = [&](std::uint32_t k, const BoundarySite& p, const BoundarySite& q) {
      const VoronoiEdge& f = out.edges[k];
      return (f.left == p && f.right == q) || (f.left == q && f.right == p);
    };
    std::uint32_t lb = i;
    std::uint32_t ar = i;
    for (std::uint32_t k : incident_[b]) {
      if (k != i && joins(k, l, sb)) lb = k;
    }
    for (std::uint32_t k : incident_[a]) {
      if (k != i && joins(k, sa, r)) ar = k;
    }
    if (lb == i || ar == i) return false;
    (out.edges[lb].a == b ? out.edges[lb].a : out.edges[lb].b) = a;
    (out.edges[ar].a == a ? out.edges[ar].a : out.edges[ar].b) = b;
    std::replace(incident_[b].begin(), incident_[b].end(), lb, ar);
    std::replace(incident_[a].begin(), incident_[a].end(), ar, lb);
    e.left = sb;
    e.right = sa;
    e.medial = medial_by_sites(sb, sa, out.turn, true);  // a fold is inside
    out.vertices[a].sites = {l, sa, sb};
    out.vertices[b].sites = {r, sb, sa};
    for (const std::uint32_t v : {a, b}) {
      VoronoiVertex& vv = out.vertices[v];
      vv.position = refine_vertex(polygon_, vv.sites, vv.position, centre_, size_);
    }
    return true;
  }

  /// Splits vertex v of k > 3 (cocircular) sites into k - 2 vertices of three sites, a fan
  /// around its first site in counter-clockwise order, joined by zero-length edges: the form in
  /// which CGAL reports such a vertex, and one flip() can work on. False when v's bounded edges
  /// do not match its sites.
  bool split(VoronoiDiagram& out, std::uint32_t v) {
    const std::vector<BoundarySite> s = v < ccw_.size() ? ccw_[v] : std::vector<BoundarySite>{};
    const std::size_t k = s.size();
    if (k <= 3) return false;
    // Fan triangle j in [1, k - 2] is (s0, s_j, s_j+1); triangle 1 keeps index v.
    std::vector<std::uint32_t> id(k - 1, v);
    for (std::size_t j = 2; j + 1 < k; ++j) {
      id[j] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back({out.vertices[v].position, {s[0], s[j], s[j + 1]}});
      incident_.emplace_back();
    }
    out.vertices[v].sites = {s[0], s[1], s[2]};
    const std::vector<std::uint32_t> edges = incident_[v];
    incident_[v].clear();
    for (const std::uint32_t e : edges) {
      VoronoiEdge& f = out.edges[e];
      std::size_t j = k;  // the edge between cells s_j and s_j+1
      for (std::size_t c = 0; c < k && j == k; ++c) {
        const BoundarySite& p = s[c];
        const BoundarySite& q = s[(c + 1) % k];
        if ((f.left == p && f.right == q) || (f.left == q && f.right == p)) j = c;
      }
      if (j == k) return false;
      const std::uint32_t t = id[std::clamp<std::size_t>(j, 1, k - 2)];
      (f.a == v ? f.a : f.b) = t;
      incident_[t].push_back(e);
    }
    for (std::size_t j = 2; j + 1 < k; ++j) {
      const auto e = static_cast<std::uint32_t>(out.edges.size());
      out.edges.push_back(
          {id[j - 1], id[j], s[0], s[j], medial_by_sites(s[0], s[j], out.turn, true)});
      incident_[id[j - 1]].push_back(e);
      incident_[id[j]].push_back(e);
    }
    for (std::size_t j = 1; j + 1 < k; ++j) {
      VoronoiVertex& vv = out.vertices[id[j]];
      vv.position = refine_vertex(polygon_, vv.sites, vv.position, centre_, size_);
    }
    ccw_[v].clear();
    return true;
  }

  const Polygon2& polygon_;
  Grid grid_;
  std::vector<GridPoint> points_;                // every corner on the grid, loop after loop
  std::vector<std::size_t> loop_start_;          // index in points_ of each loop's corner 0
  std::vector<BoundarySite> flat_;               // the segment site of each input segment
  std::vector<std::vector<std::int8_t>> exact_;  // turn signs on the input doubles
  Diagram vd_;
  std::vector<BoundarySite> site_;  // by cell index
  std::vector<std::uint8_t> left_;  // by half-edge index: on the left of its cell's segment
  std::vector<std::vector<std::uint32_t>> incident_;  // by output vertex: its output edges
  std::vector<std::vector<BoundarySite>> ccw_;        // sites of a vertex of more than 3, in order
  double size_ = 0.0;                                 // the polygon's box diagonal
  Vec2 centre_;                                       // and centre
};

}  // namespace

std::optional<VoronoiDiagram> segment_voronoi_boost(const Polygon2& polygon, std::string* why) {
  std::string ignored;
  return Builder(polygon).run(why ? why : &ignored);
}

}  // namespace laytracks::medial_detail
