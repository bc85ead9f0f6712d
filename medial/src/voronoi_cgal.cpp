// The segment Voronoi diagram through CGAL's Segment_Delaunay_graph_2 (the CGAL backend): the
// only translation unit of medial/ that includes CGAL.
//
// Choices, measured (see docs/medial.md):
// - filtered traits without intersections on EPICK with Field_with_sqrt_tag: exact predicates
//   (interval filter, Gmpq fallback), so the topology is decided exactly on the input doubles;
// - Voronoi vertex positions from the same formulas in plain doubles, never the filtered
//   construction: its exact path divided by zero in GMP (SIGFPE, the process dies) on nearly
//   collinear runs of corners. refine_vertex() recomputes every position from its sites anyway.
//   (CORE::Expr as the exact kernel avoided the crash too, and its predicates were 1.6x to 1.9x
//   faster, but CORE appends warnings to a file "Core_Diagnostics" in the working directory,
//   and calls exit(1) when it cannot open it or meets a zero divisor: not for a library);
// - points are inserted spatially sorted, then the segments in a shuffled order (in polygon
//   order a 20k-segment star took 17 s, shuffled 0.7 s). The shuffle uses a fixed seed and our
//   own Fisher-Yates, so the result is the same on every run and every platform.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Segment_Delaunay_graph_2.h>
#include <CGAL/Segment_Delaunay_graph_filtered_traits_2.h>
#include <CGAL/Segment_Delaunay_graph_traits_2.h>
#include <CGAL/Spatial_sort_traits_adapter_2.h>
#include <CGAL/spatial_sort.h>

#include <cstdint>
#include <random>
#include <set>
#include <unordered_map>
#include <utility>

#include "laytracks/brep/error.hpp"
#include "voronoi.hpp"

namespace laytracks::medial_detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Gt =
    CGAL::Segment_Delaunay_graph_filtered_traits_without_intersections_2<K,
                                                                         CGAL::Field_with_sqrt_tag>;
using Sdg = CGAL::Segment_Delaunay_graph_2<Gt>;
// The same construction in plain doubles, for the Voronoi vertex positions (see collect()).
using DoubleGt =
    CGAL::Segment_Delaunay_graph_traits_without_intersections_2<K, CGAL::Field_with_sqrt_tag>;
using Point = K::Point_2;

Point to_cgal(Vec2 p) { return Point(p.x, p.y); }

struct Corner {
  std::uint32_t loop;
  std::uint32_t index;
};

class Builder {
 public:
  explicit Builder(const Polygon2& polygon) : polygon_(polygon) {}

  VoronoiDiagram run() {
    insert_sites();
    mark_left_edges();
    VoronoiDiagram out;
    out.turn = exact_turns(polygon_);
    collect(out);
    return out;
  }

 private:
  void insert_sites() {
    std::vector<Point> points;
    std::vector<Corner> corners;
    for (std::uint32_t l = 0; l < polygon_.loops.size(); ++l) {
      const auto& loop = polygon_.loops[l];
      for (std::uint32_t i = 0; i < loop.size(); ++i) {
        points.push_back(to_cgal(loop[i]));
        corners.push_back({l, i});
      }
    }
    // Points first, spatially sorted, remembering the handle of each corner.
    std::vector<std::size_t> order(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    using Pmap = CGAL::Pointer_property_map<Point>::const_type;
    CGAL::Spatial_sort_traits_adapter_2<K, Pmap> sort_traits(
        CGAL::make_property_map(std::as_const(points)));
    CGAL::spatial_sort(order.begin(), order.end(), sort_traits);
    std::vector<Sdg::Vertex_handle> handles(points.size());
    Sdg::Vertex_handle hint;
    for (std::size_t i : order) {
      hint = sdg_.insert(points[i], hint);
      handles[i] = hint;
      site_of_[&*hint] = {BoundarySite::Kind::Corner, corners[i].loop, corners[i].index};
    }
    if (sdg_.number_of_vertices() != points.size()) {
      throw InternalError("medial axis: two corners of the polygon coincide");
    }
    // Then the segments, shuffled with a fixed seed.
    std::vector<std::size_t> segs(points.size());
    for (std::size_t i = 0; i < segs.size(); ++i) segs[i] = i;
    std::mt19937_64 rng(0x1a7'7acc5ULL);
    for (std::size_t i = segs.size(); i > 1; --i) {
      const std::size_t j = static_cast<std::size_t>(rng() % i);
      std::swap(segs[i - 1], segs[j]);
    }
    std::vector<std::size_t> loop_start(polygon_.loops.size(), 0);
    for (std::size_t l = 1; l < polygon_.loops.size(); ++l) {
      loop_start[l] = loop_start[l - 1] + polygon_.loops[l - 1].size();
    }
    for (std::size_t s : segs) {
      const Corner c = corners[s];
      const std::size_t next = loop_start[c.loop] + (c.index + 1) % polygon_.loops[c.loop].size();
      Sdg::Vertex_handle v = sdg_.insert(handles[s], handles[next]);
      site_of_[&*v] = {BoundarySite::Kind::Segment, c.loop, c.index};
      segments_.push_back({v, handles[s], handles[next]});
    }
  }

  /// Marks the dual edges on the inner (left) side of every segment site. Around a segment's
  /// vertex the Delaunay neighbours come in counter-clockwise order: its source, the sites on
  /// its right, its target, the sites on its left. This is combinatorial, hence exact, and
  /// does not look at the (inexact) Voronoi vertex positions, which can be far off for the
  /// nearly degenerate faces outside a gently curved boundary.
  void mark_left_edges() {
    for (const SegmentSite& seg : segments_) {
      std::vector<Sdg::Edge> ring;
      auto ec = sdg_.incident_edges(seg.v);
      const auto done = ec;
      do {
        ring.push_back(*ec);
      } while (++ec != done);
      const std::size_t n = ring.size();
      std::size_t at_source = n;
      std::size_t at_target = n;
      for (std::size_t k = 0; k < n; ++k) {
        const Sdg::Vertex_handle other = other_end(ring[k], seg.v);
        if (other == seg.source) at_source = k;
        if (other == seg.target) at_target = k;
      }
      if (at_source == n || at_target == n) {
        throw InternalError("medial axis: a segment is not adjacent to its end points");
      }
      for (std::size_t k = (at_target + 1) % n; k != at_source; k = (k + 1) % n) {
        left_.insert(key(ring[k]));
        left_.insert(key(mirror(ring[k])));
      }
    }
  }

  static Sdg::Vertex_handle other_end(const Sdg::Edge& e, Sdg::Vertex_handle v) {
    const Sdg::Vertex_handle a = e.first->vertex(Sdg::ccw(e.second));
    return a == v ? e.first->vertex(Sdg::cw(e.second)) : a;
  }

  static Sdg::Edge mirror(const Sdg::Edge& e) {
    const Sdg::Face_handle g = e.first->neighbor(e.second);
    return {g, g->index(e.first)};
  }

  static std::pair<const void*, int> key(const Sdg::Edge& e) { return {&*e.first, e.second}; }

  BoundarySite site(Sdg::Vertex_handle v) const {
    const auto it = site_of_.find(&*v);
    if (it == site_of_.end()) throw InternalError("medial axis: a Voronoi site has no origin");
    return it->second;
  }

  void collect(VoronoiDiagram& out) {
    std::unordered_map<const void*, std::uint32_t> face_index;
    for (auto f = sdg_.finite_faces_begin(); f != sdg_.finite_faces_end(); ++f) {
      VoronoiVertex vv;
      // Not sdg_.primal(f): its exact fallback (Gmpq, ring-type formulas) divided by zero
      // inside GMP, which raises SIGFPE and kills the process, on grid outlines rotated in 3D
      // (tests/data/parts/grid_outline_*.json). The position is only a first guess that
      // refine_vertex() recomputes from the three sites; where the doubles are far off it
      // picks the right root without it.
      const Point p =
          construct_vertex_(f->vertex(0)->site(), f->vertex(1)->site(), f->vertex(2)->site());
      vv.position = {CGAL::to_double(p.x()), CGAL::to_double(p.y())};
      for (int i = 0; i < 3; ++i) vv.sites.push_back(site(f->vertex(i)));
      face_index[&*f] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(vv);
    }
    for (auto e = sdg_.finite_edges_begin(); e != sdg_.finite_edges_end(); ++e) {
      const Sdg::Face_handle f = e->first;
      const int i = e->second;
      const Sdg::Face_handle g = f->neighbor(i);
      if (sdg_.is_infinite(f) || sdg_.is_infinite(g)) continue;  // unbounded: outside
      VoronoiEdge ve;
      // The dual edge runs from vertex ccw(i) to cw(i) with f on its left; its Voronoi edge
      // runs from f's centre to g's, so cw(i)'s site is on the left of the walk.
      ve.a = face_index.at(&*f);
      ve.b = face_index.at(&*g);
      ve.left = site(f->vertex(Sdg::cw(i)));
      ve.right = site(f->vertex(Sdg::ccw(i)));
      ve.medial = is_medial(ve, *e, out.turn);
      out.edges.push_back(ve);
    }
  }

  /// Whether a bounded Voronoi edge belongs to the medial axis.
  bool is_medial(const VoronoiEdge& ve,
                 const Sdg::Edge& e,
                 const std::vector<std::vector<std::int8_t>>& turn) const {
    const auto is_corner = [](const BoundarySite& s) {
      return s.kind == BoundarySite::Kind::Corner;
    };
    const auto own_end = [&](const BoundarySite& c, const BoundarySite& s) {
      if (!is_corner(c) || is_corner(s) || c.loop != s.loop) return false;
      const std::size_t n = polygon_.loops[c.loop].size();
      return c.index == s.index || c.index == (s.index + 1) % n;
    };
    // The normal between a segment and its own end point is not medial.
    if (own_end(ve.left, ve.right) || own_end(ve.right, ve.left)) return false;
    // A corner's Voronoi cell is inside the polygon exactly when the corner is reflex.
    if (is_corner(ve.left) || is_corner(ve.right)) {
      for (const BoundarySite& s : {ve.left, ve.right}) {
        if (is_corner(s) && turn[s.loop][s.index] >= 0) return false;
      }
      return true;
    }
    // Two segments: inside when the edge is on the left (inner) side of its segments.
    return left_.count(key(e)) > 0;
  }

  struct SegmentSite {
    Sdg::Vertex_handle v;
    Sdg::Vertex_handle source;
    Sdg::Vertex_handle target;
  };

  const Polygon2& polygon_;
  Sdg sdg_;
  DoubleGt::Construct_svd_vertex_2 construct_vertex_;
  std::vector<SegmentSite> segments_;
  std::set<std::pair<const void*, int>> left_;
  std::unordered_map<const void*, BoundarySite> site_of_;
};

}  // namespace

std::vector<std::vector<std::int8_t>> exact_turns(const Polygon2& polygon) {
  std::vector<std::vector<std::int8_t>> turn(polygon.loops.size());
  for (std::size_t l = 0; l < polygon.loops.size(); ++l) {
    const auto& loop = polygon.loops[l];
    const std::size_t n = loop.size();
    turn[l].resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto o = CGAL::orientation(to_cgal(loop[(i + n - 1) % n]), to_cgal(loop[i]),
                                       to_cgal(loop[(i + 1) % n]));
      turn[l][i] = static_cast<std::int8_t>(o == CGAL::LEFT_TURN    ? 1
                                            : o == CGAL::RIGHT_TURN ? -1
                                                                    : 0);
    }
  }
  return turn;
}

VoronoiDiagram segment_voronoi_cgal(const Polygon2& polygon) { return Builder(polygon).run(); }

}  // namespace laytracks::medial_detail
