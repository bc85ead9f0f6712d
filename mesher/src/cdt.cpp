#include "cdt.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <deque>
#include <map>
#include <utility>

namespace laytracks::mesher_detail {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;  // -1 unknown, 0 out, 1 in
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// No constraint may cross another: the polygon is simple, or there is no triangulation.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

/// Marks every face of `cdt` inside (1) or outside (0) its constraints: faces reached from the
/// infinite one across an odd number of constraints are inside.
void mark_inside(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::deque<std::pair<Cdt::Face_handle, int>> todo{{cdt.infinite_face(), 0}};
  while (!todo.empty()) {
    const auto [f, level] = todo.front();
    todo.pop_front();
    if (f->info() != -1) continue;
    f->info() = level;
    for (int k = 0; k < 3; ++k) {
      const Cdt::Face_handle g = f->neighbor(k);
      if (g->info() == -1) todo.push_back({g, cdt.is_constrained({f, k}) ? 1 - level : level});
    }
  }
}
/// Inserts every point of `pts` (its info its index) and the closed polygon pts[0 .. loop - 1]
/// as constraints. False when two points are one vertex or a constraint runs through another
/// vertex (the polygon touches itself): no such triangulation.
bool insert_polygon(Cdt& cdt, const std::vector<Vec2>& pts, std::uint32_t loop) {
  std::vector<Cdt::Vertex_handle> vh(pts.size());
  for (std::uint32_t i = 0; i < pts.size(); ++i) {
    vh[i] = cdt.insert(K::Point_2(pts[i].x, pts[i].y));
    if (cdt.number_of_vertices() != i + 1) return false;
    vh[i]->info() = i;
  }
  for (std::uint32_t i = 0; i < loop; ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % loop]);
  std::size_t constrained = 0;
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e)
    if (cdt.is_constrained(*e)) ++constrained;
  return constrained == loop;
}
}  // namespace

std::vector<std::array<std::uint32_t, 3>> constrained_triangulation(const std::vector<Vec2>& pts,
                                                                    std::uint32_t loop) {
  if (loop < 3 || pts.size() < loop) return {};
  try {
    Cdt cdt;
    if (!insert_polygon(cdt, pts, loop)) return {};
    mark_inside(cdt);
    std::vector<std::array<std::uint32_t, 3>> tris;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      if (f->info() != 1) continue;
      tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    }
    // In a fixed order (CGAL's face order follows its memory), each from its least index.
    for (auto& t : tris) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    std::sort(tris.begin(), tris.end());
    // Every polygon edge in exactly one inside triangle, running the polygon's way; every
    // inner point used.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(3 * tris.size());
    std::vector<bool> used(pts.size(), false);
    for (const auto& t : tris)
      for (std::size_t k = 0; k < 3; ++k) {
        edges.push_back({t[k], t[(k + 1) % 3]});
        used[t[k]] = true;
      }
    std::sort(edges.begin(), edges.end());
    for (std::uint32_t i = 0; i < loop; ++i) {
      const std::pair<std::uint32_t, std::uint32_t> e{i, (i + 1) % loop};
      const auto range = std::equal_range(edges.begin(), edges.end(), e);
      if (range.second - range.first != 1) return {};
    }
    if (!std::all_of(used.begin(), used.end(), [](bool u) { return u; })) return {};
    if (tris.size() != 2 * pts.size() - loop - 2) return {};
    return tris;
  } catch (const std::exception&) {
    return {};  // crossing constraints
  }
}

namespace {

/// A triangle's circumradius in units of the target size is refined above this (an
/// equilateral triangle of side s has radius s / sqrt 3: 0.75 lets sides reach 1.3 x size).
constexpr double kRefineRadius = 0.75;
/// A new point keeps at least this x size from the polygon's edges and from the other points
/// of its pass.
constexpr double kRefineClear = 0.55;
/// At most this many passes.
constexpr int kRefinePasses = 40;

double squared_segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0.0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  const Vec2 q = p - (a + t * d);
  return dot(q, q);
}

}  // namespace

std::vector<Vec2> refinement_points(const std::vector<Vec2>& polygon,
                                    const std::function<double(Vec2)>& size,
                                    std::size_t max_points) {
  const std::size_t loop = polygon.size();
  if (loop < 3) return {};
  std::vector<Vec2> added;
  try {
    Cdt cdt;
    if (!insert_polygon(cdt, polygon, static_cast<std::uint32_t>(loop))) return {};
    for (int pass = 0; pass < kRefinePasses && added.size() < max_points; ++pass) {
      mark_inside(cdt);
      struct Candidate {
        double ratio;
        Vec2 c;
        double size;
      };
      std::vector<Candidate> candidates;
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (f->info() != 1) continue;
        const K::Point_2 cc =
            CGAL::circumcenter(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
        const Vec2 c{cc.x(), cc.y()};
        const double radius = std::sqrt(CGAL::squared_distance(cc, f->vertex(0)->point()));
        const double s = size(c);
        if (!(s > 0.0) || radius <= kRefineRadius * s) continue;
        candidates.push_back({radius / s, c, s});
      }
      std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        if (a.ratio != b.ratio) return a.ratio > b.ratio;
        if (a.c.x != b.c.x) return a.c.x < b.c.x;
        return a.c.y < b.c.y;
      });
      std::vector<Vec2> taken;
      for (const Candidate& cand : candidates) {
        if (added.size() + taken.size() >= max_points) break;
        const double clear = kRefineClear * cand.size, clear2 = clear * clear;
        bool ok = true;
        for (std::size_t i = 0; i < loop && ok; ++i)
          ok = squared_segment_distance(cand.c, polygon[i], polygon[(i + 1) % loop]) >= clear2;
        for (std::size_t i = 0; i < taken.size() && ok; ++i) {
          const Vec2 d = taken[i] - cand.c;
          ok = dot(d, d) >= clear2;
        }
        if (!ok) continue;
        const Cdt::Face_handle f = cdt.locate(K::Point_2(cand.c.x, cand.c.y));
        if (f == nullptr || cdt.is_infinite(f) || f->info() != 1) continue;
        taken.push_back(cand.c);
      }
      if (taken.empty()) break;
      for (const Vec2& t : taken) cdt.insert(K::Point_2(t.x, t.y));
      added.insert(added.end(), taken.begin(), taken.end());
    }
  } catch (const std::exception&) {
    return {};
  }
  return added;
}

}  // namespace laytracks::mesher_detail
