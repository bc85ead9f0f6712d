// Rules 9-11 of build_part(): B-Rep edges, vertices lying inside edges, the file's dual graph.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

#include "build_state.hpp"
#include "describe.hpp"
#include "laytracks/brep/dual_graph.hpp"
#include "predicates.hpp"

namespace laytracks::detail {
namespace {

/// The unordered vertex pair as one key.
std::uint64_t pair_key(VertexId a, VertexId b) {
  return (static_cast<std::uint64_t>(std::min(a, b).value) << 32) | std::max(a, b).value;
}

/// The first patch, other than `avoid` when possible, whose loops use vertex v.
std::size_t patch_using(const BuildState& s, VertexId v, std::size_t avoid) {
  std::optional<std::size_t> found;
  for (std::size_t p = 0; p < s.chains.size(); ++p) {
    for (const Chain& c : s.chains[p]) {
      if (std::find(c.vertices.begin(), c.vertices.end(), v) == c.vertices.end()) continue;
      if (p != avoid) return p;
      found = p;
    }
  }
  return found.value_or(avoid);
}

/// The distance from p to the open segment ab, or nothing when the nearest
/// point of the line is not strictly inside the segment.
std::optional<double> distance_inside(Vec3 p, Vec3 a, Vec3 b) {
  const Vec3 ab = b - a;
  const double t = dot(p - a, ab) / dot(ab, ab);
  if (!(t > 0.0 && t < 1.0)) return std::nullopt;
  return norm((p - a) - t * ab);
}

/// The distance from p to the piece of `arc`'s circle between its points a and b, or nothing
/// when p's angle about the centre is not strictly between theirs (a vertex on an arc lies on
/// the circle, not on the chord the medial axis uses). Angles are measured from the piece's
/// middle, in (-pi, pi]: a piece spans at most 90 degrees (max_chord_angle). (Measured in
/// [0, 2 pi) from e1, the arc's own start came out just below 2 pi in some poses, and its first
/// piece then took in the rest of the circle.)
std::optional<double> distance_inside_arc(Vec3 p, const PartArc& arc, Vec3 a, Vec3 b) {
  const Vec3 axis = cross(arc.e1, arc.e2);
  const Vec3 mid = (a - arc.center) + (b - arc.center);
  const Vec3 m1 = (1.0 / norm(mid)) * mid;
  const Vec3 m2 = cross(axis, m1);
  auto angle = [&](Vec3 x) {
    const Vec3 w = x - arc.center;
    return std::atan2(dot(w, m2), dot(w, m1));
  };
  const double ta = angle(a), tb = angle(b), tp = angle(p);
  if (!(tp > std::min(ta, tb) && tp < std::max(ta, tb))) return std::nullopt;
  const Vec3 w = p - arc.center;
  const double off = dot(w, axis);
  const double radial = norm(w - off * axis);
  return std::hypot(off, radial - arc.radius);
}

/// The message for vertex v lying inside edge e.
std::string on_edge_message(const BuildState& s, VertexId v, EdgeId e) {
  const BrepEdge& edge = s.part.edges[e.index()];
  const std::size_t edge_patch = edge.patches[0].index();
  const std::size_t vertex_patch = patch_using(s, v, edge_patch);
  return vertex_name(s, v) + " lies on " + edge_name(s, edge.a, edge.b) + " of " +
         patch_name(s, edge_patch) + " but that edge is not split there (the vertex is at " +
         point(s.part.vertices[v.index()].position) + ", on " + patch_name(s, vertex_patch) + ")";
}

}  // namespace

void build_edges(BuildState& s) {
  std::unordered_map<std::uint64_t, EdgeId> by_pair;
  std::vector<std::size_t> loop_of;  // per edge: the loop of its last patch that uses it
  for (std::size_t p = 0; p < s.chains.size(); ++p) {
    for (std::size_t l = 0; l < s.chains[p].size(); ++l) {
      const Chain& c = s.chains[p][l];
      Loop& loop = s.part.patches[p].loops[l];
      const std::size_t m = c.vertices.size();
      loop.edges.clear();
      for (std::size_t i = 0; i < m; ++i) {
        const VertexId a = c.vertices[i];
        const VertexId b = c.vertices[(i + 1) % m];
        const auto [it, inserted] = by_pair.emplace(pair_key(a, b), EdgeId(s.part.edges.size()));
        if (inserted) {
          s.part.edges.push_back({std::min(a, b), std::max(a, b), {}, c.seg_arc[i]});
          loop_of.push_back(l);
        }
        BrepEdge& edge = s.part.edges[it->second.index()];
        if (!edge.patches.empty() && edge.patches.back() == PatchId(p)) {
          fail(patch_name(s, p) + " uses " + edge_name(s, a, b) + " twice (in " +
               loop_name(loop_of[it->second.index()]) + " and " + loop_name(l) + ")");
        }
        edge.patches.emplace_back(p);
        loop_of[it->second.index()] = l;
        loop.edges.push_back(it->second);
      }
    }
  }
}

void check_vertices_on_edges(const BuildState& s) {
  const double tol = Tolerances::kOnEdge * s.part.size;
  const Vec3 pad{tol, tol, tol};
  std::vector<VertexId> ids;
  std::vector<Box3> points;
  for (std::size_t i = 0; i < s.part.vertices.size(); ++i) {
    if (i < s.file_vertex_count() && !s.used[i]) continue;
    ids.emplace_back(i);
    Box3 box;
    box.add(s.part.vertices[i].position - pad);
    box.add(s.part.vertices[i].position + pad);
    points.push_back(box);
  }
  std::vector<Box3> edges;
  for (const BrepEdge& e : s.part.edges) {
    Box3 box;
    const Vec3 a = s.part.vertices[e.a.index()].position, b = s.part.vertices[e.b.index()].position;
    box.add(a);
    box.add(b);
    if (e.arc >= 0) {
      // A piece of an arc bulges out of its chord by the sagitta.
      const double r = s.part.arcs[static_cast<std::size_t>(e.arc)].radius;
      const double half = 0.5 * norm(b - a);
      const double sagitta = r - std::sqrt(std::max(0.0, r * r - half * half));
      const Vec3 bulge{sagitta, sagitta, sagitta};
      box.add(a - bulge);
      box.add(b + bulge);
      box.add(a + bulge);
      box.add(b - bulge);
    }
    edges.push_back(box);
  }
  std::optional<std::pair<VertexId, EdgeId>> first;
  for (const auto& [i, k] : overlapping_boxes(points, edges)) {
    const BrepEdge& e = s.part.edges[k];
    const VertexId v = ids[i];
    if (v == e.a || v == e.b) continue;
    const auto d =
        e.arc >= 0
            ? distance_inside_arc(s.part.vertices[v.index()].position,
                                  s.part.arcs[static_cast<std::size_t>(e.arc)],
                                  s.part.vertices[e.a.index()].position,
                                  s.part.vertices[e.b.index()].position)
            : distance_inside(s.part.vertices[v.index()].position, s.part.vertices[e.a.index()].position,
                              s.part.vertices[e.b.index()].position);
    if (!d || *d > tol) continue;
    const std::pair<VertexId, EdgeId> found{v, EdgeId(k)};
    if (!first || found < *first) first = found;
  }
  if (first) fail(on_edge_message(s, first->first, first->second));
}

void check_dual_graph_and_shells(BuildState& s) {
  std::map<std::pair<std::size_t, std::size_t>, EdgeId> shared;  // patch pair -> first edge
  for (std::size_t e = 0; e < s.part.edges.size(); ++e) {
    const auto& ps = s.part.edges[e].patches;
    for (std::size_t i = 0; i < ps.size(); ++i) {
      for (std::size_t j = i + 1; j < ps.size(); ++j) {
        shared.emplace(std::make_pair(ps[i].index(), ps[j].index()), EdgeId(e));
      }
    }
  }
  const auto names = [&](std::size_t a, std::size_t b) {
    return " (\"" + s.part.patches[a].name + "\" and \"" + s.part.patches[b].name + "\")";
  };
  if (s.raw.dual_graph) {
    std::map<std::pair<std::size_t, std::size_t>, bool> listed;
    for (const auto& entry : *s.raw.dual_graph) {
      const auto a = static_cast<std::size_t>(entry[0]);
      const auto b = static_cast<std::size_t>(entry[1]);
      if (!shared.count({std::min(a, b), std::max(a, b)})) {
        fail("dual_graph lists patches " + std::to_string(a) + " and " + std::to_string(b) +
             " as neighbours, but they share no edge" + names(a, b));
      }
      listed[{std::min(a, b), std::max(a, b)}] = true;
    }
    for (const auto& [pair, e] : shared) {
      if (listed.count(pair)) continue;
      const BrepEdge& edge = s.part.edges[e.index()];
      fail("patches " + std::to_string(pair.first) + " and " + std::to_string(pair.second) +
           " share " + edge_name(s, edge.a, edge.b) + " but dual_graph does not list them" +
           names(pair.first, pair.second));
    }
  }
  const std::vector<std::size_t> shell = shells_of(build_dual_graph(s.part), s.part.shell_count);
  for (std::size_t p = 0; p < shell.size(); ++p) s.part.patches[p].shell = shell[p];
}

}  // namespace laytracks::detail
