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
}  // namespace

std::vector<std::array<std::uint32_t, 3>> constrained_triangulation(const std::vector<Vec2>& pts,
                                                                    std::uint32_t loop) {
  if (loop < 3 || pts.size() < loop) return {};
  try {
    Cdt cdt;
    std::vector<Cdt::Vertex_handle> vh(pts.size());
    for (std::uint32_t i = 0; i < pts.size(); ++i) {
      vh[i] = cdt.insert(K::Point_2(pts[i].x, pts[i].y));
      // Two equal points are one vertex: no triangulation of these points.
      if (cdt.number_of_vertices() != i + 1) return {};
      vh[i]->info() = i;
    }
    for (std::uint32_t i = 0; i < loop; ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % loop]);
    // A constraint through another vertex is split there: the polygon touches itself.
    std::size_t constrained = 0;
    for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e)
      if (cdt.is_constrained(*e)) ++constrained;
    if (constrained != loop) return {};
    // Inside: faces reached from the infinite one across an odd number of constraints.
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
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> edge;
    std::vector<bool> used(pts.size(), false);
    for (const auto& t : tris)
      for (std::size_t k = 0; k < 3; ++k) {
        ++edge[{t[k], t[(k + 1) % 3]}];
        used[t[k]] = true;
      }
    for (std::uint32_t i = 0; i < loop; ++i)
      if (edge[{i, (i + 1) % loop}] != 1) return {};
    if (!std::all_of(used.begin(), used.end(), [](bool u) { return u; })) return {};
    if (tris.size() != 2 * pts.size() - loop - 2) return {};
    return tris;
  } catch (const std::exception&) {
    return {};  // crossing constraints
  }
}

}  // namespace laytracks::mesher_detail
