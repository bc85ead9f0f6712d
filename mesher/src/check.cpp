// The mesh validator: the six rules of ../shared/spec/quality.md ("A whole mesh").
#include "laytracks/mesher/check.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "laytracks/mesher/quality.hpp"
#include "node_grid.hpp"
#include "patch_index.hpp"

namespace laytracks {
namespace {

using detail::BoundarySegment;
using detail::NodeGrid;
using detail::PatchIndex;

constexpr std::uint32_t kNone = 0xffffffffu;

std::string fmt(Vec3 p) {
  std::ostringstream s;
  s.precision(10);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

/// Neumaier's compensated sum: patch areas are compared at 1e-9 relative over a million terms.
struct Sum {
  double sum = 0.0;
  double carry = 0.0;
  void add(double v) {
    const double t = sum + v;
    carry += std::fabs(sum) >= std::fabs(v) ? (sum - t) + v : (v - t) + sum;
    sum = t;
  }
  double value() const { return sum + carry; }
};

/// Distance from x to the segment ab, and the parameter of the nearest point.
std::pair<double, double> segment_distance(Vec3 x, Vec3 a, Vec3 b) {
  const Vec3 d = b - a;
  const double dd = dot(d, d);
  double t = dd > 0.0 ? dot(x - a, d) / dd : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return {distance(x, a + t * d), t};
}

/// Where a node is on a patch's B-Rep boundary.
struct OnBrep {
  enum Kind : std::uint8_t { kNowhere, kVertex, kEdge };
  Kind kind = kNowhere;
  std::uint32_t id = 0;  ///< VertexId or EdgeId value
};

/// A mesh edge side of an element, filed under its smaller node.
struct HalfEdge {
  std::uint32_t hi;
  std::uint32_t element;
};

class Checker {
 public:
  Checker(const Part& part, const QuadMesh& mesh, const MeshCheckOptions& options)
      : part_(part), mesh_(mesh), options_(options), size_(part.size) {}

  MeshCheck run() {
    out_.elements = mesh_.elements.size();
    out_.min_node_distance = MeshTolerances::kMinNodeDistance * size_;
    index_patches();
    check_elements();  // rules 1, 2, 3 and the element areas
    check_edges();     // rules 5 and 6 along mesh edges (and the arcs' chords, for rule 4)
    check_areas();     // rule 4
    check_nodes();     // rule 5 (close and hanging nodes) and rule 6 (B-Rep vertices)
    for (int r = 1; r <= 6; ++r) {
      for (MeshFailure& f : by_rule_[static_cast<std::size_t>(r)])
        out_.failures.push_back(std::move(f));
    }
    return std::move(out_);
  }

 private:
  /// Counts a failure of `rule`; builds its sentence only while under the per-rule cap.
  template <class F>
  void fail(int rule, F&& make_message) {
    const auto r = static_cast<std::size_t>(rule);
    ++out_.counts[r];
    if (by_rule_[r].size() < options_.max_messages_per_rule) {
      by_rule_[r].push_back({rule, "rule " + std::to_string(rule) + ": " + make_message()});
    }
  }

  std::string patch_label(std::size_t p) const {
    if (p < part_.patches.size()) return part_.patch_label(PatchId(p));
    if (!PatchId(p).valid()) return "no patch (its patch id is unset)";
    return "patch index " + std::to_string(p) + " (out of range)";
  }
  std::string node_text(std::uint32_t n) const {
    return "node " + std::to_string(n) + " at " + fmt(mesh_.nodes[n]);
  }
  /// "node 7 at (x, y, z) of patch ..." naming the patch of the first element that uses it.
  std::string node_place(std::uint32_t n) const {
    std::string s = node_text(n);
    if (node_element_[n] != kNone) s += " of " + patch_label(element_patch(node_element_[n]));
    return s;
  }
  std::size_t element_patch(std::uint32_t e) const { return mesh_.elements[e].patch.index(); }
  std::size_t corner_count(const MeshElement& e) const { return e.is_quad() ? 4 : 3; }
  Vec3 centroid(const MeshElement& e) const {
    const std::size_t m = corner_count(e);
    Vec3 c;
    for (std::size_t k = 0; k < m; ++k) c = c + mesh_.nodes[e.nodes[k]];
    return (1.0 / static_cast<double>(m)) * c;
  }
  /// "element 12 of patch "wall" (index 1), at (x, y, z)" (its centroid, when its nodes exist).
  std::string element_place(std::uint32_t i, bool nodes_ok = true) const {
    const MeshElement& e = mesh_.elements[i];
    std::string s = "element " + std::to_string(i) + " of " + patch_label(e.patch.index());
    if (nodes_ok) s += ", at " + fmt(centroid(e));
    return s;
  }
  std::string edge_text(std::uint32_t a, std::uint32_t b) const {
    return "mesh edge from " + node_text(a) + " to " + node_text(b);
  }

  /// True when point c (patch frame), outside the patch's polygon, lies between one of its
  /// chords of an arc and the mesh's own chord of that arc, which may be coarser (rule 4: the
  /// polygons the mesher used, each chord's sagitta within the chord tolerance): within the
  /// circle, beyond the polygon's chord; for a concave arc (the centre on the far side, a
  /// hole's rounded corner) no deeper into the circle than the chord tolerance. (Fuzz seed
  /// 52052's extreme_059: a hole's corner rounded by 0.3 at h = 0.8, one chord in the mesh.)
  bool in_arc_segment(std::size_t p, Vec2 c) const {
    const Patch& patch = part_.patches[p];
    bool inside = false;
    indices_[p].for_each_near(c, 2.0 * part_.chord_tol, [&](std::uint32_t si) {
      const BoundarySegment& s = indices_[p].segments()[si];
      const std::int64_t arc = part_.edges[s.edge.index()].arc;
      if (arc < 0 || inside) return;
      const PartArc& a = part_.arcs[static_cast<std::size_t>(arc)];
      const Vec2 centre = patch.frame.to_2d(a.center);
      const Vec2 d = s.b - s.a;
      const double len2 = dot(d, d);
      if (!(len2 > 0.0)) return;
      const double t = dot(c - s.a, d) / len2;
      const bool convex = cross(d, centre - s.a) > 0.0;  // the material side holds the centre
      const double from_centre = distance(c, centre);
      inside = cross(d, c - s.a) <= 0.0 &&  // c beyond the chord
               t >= 0.0 && t <= 1.0 && from_centre <= a.radius &&
               (convex || from_centre >= a.radius - part_.chord_tol);
    });
    return inside;
  }

  void index_patches() {
    const double slack = MeshTolerances::kOnPlane * size_;
    for (const Patch& patch : part_.patches) {
      indices_.emplace_back(patch);
      double off = 0.0;
      for (const Loop& loop : patch.loops) {
        for (VertexId v : loop.vertices) {
          const Vec3 x = part_.vertices[v.index()].position;
          off = std::fmax(off, std::fabs(dot(x - patch.frame.origin, patch.frame.n)));
        }
      }
      plane_tol_.push_back(off + slack);
    }
    area_.assign(part_.patches.size(), Sum{});
    // An arc is one B-Rep edge for the check, named by its first discretisation edge; its
    // discretisation points are not B-Rep vertices (the mesh has its own chords of the circle).
    arc_edge_.assign(part_.arcs.size(), kNone);
    for (std::size_t i = 0; i < part_.edges.size(); ++i) {
      const BrepEdge& e = part_.edges[i];
      if (e.arc >= 0) {
        std::uint32_t& first = arc_edge_[static_cast<std::size_t>(e.arc)];
        if (first == kNone) first = static_cast<std::uint32_t>(i);
        continue;
      }
      edge_by_vertices_.emplace(pair_key(e.a.value, e.b.value), static_cast<std::uint32_t>(i));
    }
    for (std::size_t a = 0; a < part_.arcs.size(); ++a) {
      if (arc_edge_[a] == kNone) continue;
      edge_by_vertices_.emplace(pair_key(part_.arcs[a].from.value, part_.arcs[a].to.value),
                                arc_edge_[a]);
    }
    // Rule 4 compares with the patch bounded by the mesh's own chords of its arcs: the
    // polygon's area, plus the circular segments between the discretisation chords and the
    // circle, minus those between the mesh's chords and the circle (check_edges subtracts).
    expected_.assign(part_.patches.size(), Sum{});
    for (std::size_t p = 0; p < part_.patches.size(); ++p) {
      const Patch& patch = part_.patches[p];
      expected_[p].add(patch.area);
      for (std::size_t l = 0; l < patch.loops.size(); ++l) {
        const Loop& loop = patch.loops[l];
        const auto& poly = patch.polygon.loops[l];
        for (std::size_t i = 0; i < loop.edges.size(); ++i) {
          const std::int64_t arc = part_.edges[loop.edges[i].index()].arc;
          if (arc < 0) continue;
          const PartArc& pa = part_.arcs[static_cast<std::size_t>(arc)];
          const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
          // The centre on the inner side of the chord: the arc bulges out of the patch.
          const double sign = cross(b - a, patch.frame.to_2d(pa.center) - a) > 0.0 ? 1.0 : -1.0;
          arc_sign_[std::uint64_t{static_cast<std::uint64_t>(arc)} * part_.patches.size() + p] = sign;
          expected_[p].add(sign * circular_segment(pa.radius, distance(a, b)));
        }
      }
    }
  }

  /// Area between a chord of length c and its circle of radius r (the smaller side).
  static double circular_segment(double r, double c) {
    const double theta = 2.0 * std::asin(std::fmin(1.0, 0.5 * c / r));
    return 0.5 * r * r * (theta - std::sin(theta));
  }

  /// The ends of a B-Rep edge as the check sees it: an arc's from and to.
  std::pair<std::uint32_t, std::uint32_t> ends(std::uint32_t edge) const {
    const BrepEdge& e = part_.edges[edge];
    if (e.arc < 0) return {e.a.value, e.b.value};
    const PartArc& a = part_.arcs[static_cast<std::size_t>(e.arc)];
    return {a.from.value, a.to.value};
  }

  /// Distance from x to an arc (its circle, where the angle lies within the arc's span).
  static double arc_distance(Vec3 x, const PartArc& a) {
    const Vec3 w = x - a.center;
    const double u = dot(w, a.e1), v = dot(w, a.e2);
    const Vec3 axis = cross(a.e1, a.e2);
    const double off = dot(w, axis);
    double angle = std::atan2(v, u);
    if (angle < 0.0) angle += 2.0 * kPi;
    if (angle > a.span + 1e-9 && angle < 2.0 * kPi - 1e-9) return std::numeric_limits<double>::infinity();
    const double radial = std::hypot(u, v) - a.radius;
    return std::hypot(radial, off);
  }

  static std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
  }

  // ---- rules 1, 2, 3 -------------------------------------------------------------------

  void check_elements() {
    const std::size_t n = mesh_.elements.size();
    skip_.assign(n, 0);
    node_element_.assign(mesh_.nodes.size(), kNone);
    double edge_sum = 0.0;
    std::size_t edge_count = 0;
    for (std::size_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::uint32_t>(ii);
      const MeshElement& e = mesh_.elements[i];
      const std::size_t m = corner_count(e);
      bool ids_ok = true;
      for (std::size_t k = 0; k < m; ++k) ids_ok = ids_ok && e.nodes[k] < mesh_.nodes.size();
      const bool patch_ok = e.patch.index() < part_.patches.size();
      if (e.is_quad()) {
        ++out_.quads;
      } else {
        ++out_.triangles;
        fail(1, [&] { return element_place(i, ids_ok) + " is a triangle, not a quadrilateral"; });
      }
      if (!ids_ok || !patch_ok) {
        ++out_.malformed;
        skip_[i] = 1;
        fail(1, [&] {
          return element_place(i, ids_ok) + " is malformed: " +
                 (ids_ok ? std::string("its patch id is out of range")
                         : "a node id is out of range (the mesh has " +
                               std::to_string(mesh_.nodes.size()) + " nodes)");
        });
        continue;
      }
      for (std::size_t k = 0; k < m; ++k) {
        if (node_element_[e.nodes[k]] == kNone) node_element_[e.nodes[k]] = i;
      }
      bool finite = true;
      for (std::size_t k = 0; k < m; ++k) finite = finite && is_finite(mesh_.nodes[e.nodes[k]]);
      if (!finite) {
        skip_[i] = 1;
        fail(3,
             [&] { return element_place(i, false) + " has a node with non-finite coordinates"; });
        continue;
      }
      check_element(i);
      for (std::size_t k = 0; k < m; ++k) {
        edge_sum += distance(mesh_.nodes[e.nodes[k]], mesh_.nodes[e.nodes[(k + 1) % m]]);
        ++edge_count;
      }
    }
    for (std::uint32_t v : node_element_) out_.unused_nodes += v == kNone ? 1 : 0;
    mean_edge_ = edge_count > 0 ? edge_sum / static_cast<double>(edge_count) : 0.0;
  }

  void check_element(std::uint32_t i) {
    const MeshElement& e = mesh_.elements[i];
    const std::size_t p = e.patch.index();
    const Frame& f = part_.patches[p].frame;
    const std::size_t m = corner_count(e);
    std::array<Vec2, 4> q{};
    Vec2 c;
    double worst_off = 0.0;
    std::size_t worst_node = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const Vec3 x = mesh_.nodes[e.nodes[k]];
      q[k] = f.to_2d(x);
      c = c + q[k];
      const double off = std::fabs(dot(x - f.origin, f.n));
      if (off > worst_off) {
        worst_off = off;
        worst_node = k;
      }
    }
    c = (1.0 / static_cast<double>(m)) * c;
    // Rule 3: on the patch plane.
    if (worst_off > plane_tol_[p]) {
      fail(3, [&] {
        return element_place(i) + " is off its patch's plane: its " +
               node_text(e.nodes[worst_node]) + " is " + fmt(worst_off) + " " + part_.units +
               " from it (tolerance " + fmt(plane_tol_[p]) + ")";
      });
    }
    // Rules 2 and 3: the turn at every corner, in the patch frame (the projection of
    // quality.md: only the in-plane components matter).
    int positive = 0;
    int negative = 0;
    for (std::size_t k = 0; k < m; ++k) {
      const double turn = cross(q[(k + 1) % m] - q[k], q[(k + m - 1) % m] - q[k]);
      positive += turn > 0.0 ? 1 : 0;
      negative += turn < 0.0 ? 1 : 0;
    }
    const int corners = static_cast<int>(m);
    if (negative == corners) {
      ++out_.flipped;
      fail(3, [&] {
        return element_place(i) +
               " is oriented against its patch's normal: its nodes turn clockwise about it";
      });
    } else if (positive != corners) {
      ++out_.inverted;
      fail(2, [&] {
        std::string why = "it has a zero-area corner";
        if (e.is_quad()) {
          std::array<Vec3, 4> x{};
          for (std::size_t k = 0; k < 4; ++k) x[k] = mesh_.nodes[e.nodes[k]];
          why = "its scaled Jacobian is " + fmt(measure_quad(x, f.n).scaled_jacobian);
        }
        return element_place(i) + " is inverted or degenerate: " + why;
      });
    }
    // Rule 3: inside the patch: its polygon, or a circular segment between a chord of a convex
    // arc and the arc (the true boundary there).
    if (!indices_[p].contains(c) && !in_arc_segment(p, c)) {
      fail(3, [&] { return element_place(i) + " has its centroid outside its patch's polygon"; });
    }
    // Rule 4: the signed area in the patch frame.
    const double twice_area =
        m == 4 ? cross(q[2] - q[0], q[3] - q[1]) : cross(q[1] - q[0], q[2] - q[0]);
    area_[p].add(0.5 * twice_area);
  }

  // ---- rule 4 ----------------------------------------------------------------------------

  void check_areas() {
    for (std::size_t p = 0; p < part_.patches.size(); ++p) {
      const double want = expected_[p].value();
      const double got = area_[p].value();
      const double rel = std::fabs(got - want) / want;
      if (!(rel <= MeshTolerances::kArea)) {
        fail(4, [&] {
          return "the elements of " + patch_label(p) + " (centred at " +
                 fmt(part_.patches[p].frame.origin) + ") cover " + fmt(got) + " " + part_.units +
                 "^2 but the patch has area " + fmt(want) +
                 (part_.arcs.empty() ? "" : " (its arcs cut by the mesh's chords)") +
                 " (relative difference " + fmt(rel) +
                 ", tolerance " + fmt(MeshTolerances::kArea) + ")";
        });
      }
    }
  }

  // ---- rules 5 and 6 along the mesh edges ------------------------------------------------

  /// Node n against the B-Rep boundary of patch p (rule 6 fails when it is on neither).
  OnBrep classify(std::uint32_t n, std::size_t p) {
    const std::uint64_t key = std::uint64_t{n} * part_.patches.size() + p;
    const auto found = on_brep_.find(key);
    if (found != on_brep_.end()) return found->second;
    const Vec3 x = mesh_.nodes[n];
    const double r = MeshTolerances::kOnBrep * size_;
    OnBrep best;
    double best_vertex = r;
    double best_edge = r;
    const std::vector<BoundarySegment>& segments = indices_[p].segments();
    // The 2D distance is at most the 3D one, so a 2D search of radius r misses nothing; a point
    // of an arc is within the chord tolerance of its discretisation.
    const double search = r + (part_.arcs.empty() ? 0.0 : part_.chord_tol);
    indices_[p].for_each_near(part_.patches[p].frame.to_2d(x), search, [&](std::uint32_t si) {
      const BoundarySegment& s = segments[si];
      const Vec3 a = part_.vertices[s.va.index()].position;
      const Vec3 b = part_.vertices[s.vb.index()].position;
      for (const auto& [v, y] : {std::pair{s.va, a}, std::pair{s.vb, b}}) {
        if (part_.vertices[v.index()].from_arc) continue;
        const double d = distance(x, y);
        if (d <= best_vertex) {
          best_vertex = d;
          best = {OnBrep::kVertex, v.value};
        }
      }
      if (best.kind != OnBrep::kVertex) {
        const std::int64_t arc = part_.edges[s.edge.index()].arc;
        const double d = arc < 0 ? segment_distance(x, a, b).first
                                 : arc_distance(x, part_.arcs[static_cast<std::size_t>(arc)]);
        if (d <= best_edge) {
          best_edge = d;
          best = {OnBrep::kEdge, arc < 0 ? s.edge.value : arc_edge_[static_cast<std::size_t>(arc)]};
        }
      }
    });
    on_brep_.emplace(key, best);
    if (best.kind == OnBrep::kNowhere) {
      fail(6, [&] {
        return node_text(n) + " is on the boundary of the mesh of " + patch_label(p) +
               " but on no B-Rep edge of it (tolerance " + fmt(r) + ")";
      });
    }
    return best;
  }

  bool edge_has_vertex(std::uint32_t edge, std::uint32_t vertex) const {
    const auto [a, b] = ends(edge);
    return a == vertex || b == vertex;
  }
  bool edge_in_patch(std::uint32_t edge, std::size_t p) const {
    const auto& ps = part_.edges[edge].patches;
    return std::binary_search(ps.begin(), ps.end(), PatchId(p));
  }

  /// The B-Rep edge of patch p that the mesh edge (a, b) lies on, if any.
  std::optional<std::uint32_t> brep_edge(std::uint32_t a, std::uint32_t b, std::size_t p) {
    const OnBrep ca = classify(a, p);
    const OnBrep cb = classify(b, p);
    if (ca.kind == OnBrep::kNowhere || cb.kind == OnBrep::kNowhere) return std::nullopt;
    if (ca.kind == OnBrep::kEdge && cb.kind == OnBrep::kEdge) {
      if (ca.id == cb.id) return ca.id;
      return std::nullopt;
    }
    if (ca.kind == OnBrep::kEdge) {
      if (edge_has_vertex(ca.id, cb.id)) return ca.id;
      return std::nullopt;
    }
    if (cb.kind == OnBrep::kEdge) {
      if (edge_has_vertex(cb.id, ca.id)) return cb.id;
      return std::nullopt;
    }
    const auto range = edge_by_vertices_.equal_range(pair_key(ca.id, cb.id));
    for (auto it = range.first; it != range.second; ++it) {
      if (edge_in_patch(it->second, p)) return it->second;
    }
    return std::nullopt;
  }

  void check_edges() {
    const std::size_t node_count = mesh_.nodes.size();
    // Every side of every element, filed under its smaller node (CSR), then sorted per node.
    offsets_.assign(node_count + 1, 0);
    auto for_each_side = [&](auto&& f) {
      for (std::size_t ii = 0; ii < mesh_.elements.size(); ++ii) {
        if (skip_[ii] != 0) continue;
        const MeshElement& e = mesh_.elements[ii];
        const std::size_t m = corner_count(e);
        for (std::size_t k = 0; k < m; ++k) {
          const std::uint32_t a = e.nodes[k];
          const std::uint32_t b = e.nodes[(k + 1) % m];
          if (a != b) f(std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(ii));
        }
      }
    };
    for_each_side([&](std::uint32_t lo, std::uint32_t, std::uint32_t) { ++offsets_[lo + 1]; });
    for (std::size_t i = 0; i < node_count; ++i) offsets_[i + 1] += offsets_[i];
    half_edges_.resize(offsets_[node_count]);
    {
      std::vector<std::size_t> fill(offsets_.begin(), offsets_.end() - 1);
      for_each_side([&](std::uint32_t lo, std::uint32_t hi, std::uint32_t el) {
        half_edges_[fill[lo]++] = {hi, el};
      });
    }
    std::vector<std::pair<std::size_t, std::uint32_t>> counts;  // (patch, elements)
    for (std::size_t lo = 0; lo < node_count; ++lo) {
      const auto first = half_edges_.begin() + static_cast<std::ptrdiff_t>(offsets_[lo]);
      const auto last = half_edges_.begin() + static_cast<std::ptrdiff_t>(offsets_[lo + 1]);
      std::sort(first, last, [](const HalfEdge& x, const HalfEdge& y) {
        return x.hi != y.hi ? x.hi < y.hi : x.element < y.element;
      });
      for (auto g = first; g != last;) {
        auto g_end = g;
        while (g_end != last && g_end->hi == g->hi) ++g_end;
        check_edge_group(static_cast<std::uint32_t>(lo), g, g_end, counts);
        g = g_end;
      }
    }
  }

  using HalfEdgeIt = std::vector<HalfEdge>::const_iterator;

  std::string element_list(HalfEdgeIt first, HalfEdgeIt last) const {
    std::string s;
    for (auto it = first; it != last; ++it) {
      if (it != first) s += ", ";
      s += "element " + std::to_string(it->element) + " of " +
           patch_label(element_patch(it->element));
    }
    return s;
  }

  void check_edge_group(std::uint32_t a,
                        HalfEdgeIt first,
                        HalfEdgeIt last,
                        std::vector<std::pair<std::size_t, std::uint32_t>>& counts) {
    const std::uint32_t b = first->hi;
    counts.clear();
    for (auto it = first; it != last; ++it) {
      const std::size_t p = element_patch(it->element);
      auto c =
          std::find_if(counts.begin(), counts.end(), [&](const auto& x) { return x.first == p; });
      if (c == counts.end()) {
        counts.emplace_back(p, 1);
      } else {
        ++c->second;
      }
    }
    std::sort(counts.begin(), counts.end());
    std::optional<std::uint32_t> on_edge;
    for (const auto& [p, count] : counts) {
      if (count > 2) {
        fail(5, [&, p = p, count = count] {
          return edge_text(a, b) + " of " + patch_label(p) + " is shared by " +
                 std::to_string(count) + " elements of the patch (" + element_list(first, last) +
                 "); an edge inside a patch has exactly two";
        });
      }
      if (count != 1) continue;
      const std::optional<std::uint32_t> e = brep_edge(a, b, p);
      if (!e) {
        auto it = first;
        while (element_patch(it->element) != p) ++it;
        const std::uint32_t el = it->element;
        fail(5, [&, p = p] {
          return edge_text(a, b) + " of " + patch_label(p) + " is used by one element (element " +
                 std::to_string(el) +
                 ") but does not lie on a B-Rep edge of the patch: a crack or a hanging node";
        });
      } else {
        const std::int64_t arc = part_.edges[*e].arc;
        if (arc >= 0) {  // a chord of the arc: the region it cuts off is not the patch's
          const auto it = arc_sign_.find(std::uint64_t{static_cast<std::uint64_t>(arc)} *
                                             part_.patches.size() + p);
          const double sign = it == arc_sign_.end() ? 1.0 : it->second;
          expected_[p].add(-sign * circular_segment(part_.arcs[static_cast<std::size_t>(arc)].radius,
                                                    distance(mesh_.nodes[a], mesh_.nodes[b])));
        }
        if (!on_edge) on_edge = e;
      }
    }
    if (!on_edge) return;
    const BrepEdge& edge = part_.edges[*on_edge];
    bool ok = counts.size() == edge.patches.size();
    for (std::size_t k = 0; ok && k < counts.size(); ++k) {
      ok = counts[k].first == edge.patches[k].index() && counts[k].second == 1;
    }
    if (!ok) {
      fail(5, [&] {
        std::string users;
        for (PatchId p : edge.patches)
          users += (users.empty() ? "" : ", ") + patch_label(p.index());
        return edge_text(a, b) + " lies on B-Rep edge " + std::to_string(*on_edge) + " (vertices " +
               std::to_string(ends(*on_edge).first) + " and " + std::to_string(ends(*on_edge).second) +
               ", used by " + std::to_string(edge.patches.size()) +
               (edge.patches.size() == 1 ? " patch: " : " patches: ") + users +
               ") but is used by " + element_list(first, last) +
               "; it needs exactly one element of each of those patches";
      });
    }
  }

  // ---- rules 5 and 6 on the nodes --------------------------------------------------------

  void check_nodes() {
    double cell = 2.0 * mean_edge_;
    if (!(cell > 0.0) || !std::isfinite(cell)) cell = 1e-3 * size_;
    cell = std::fmax(cell, 1e-6 * size_);
    if (!(cell > 0.0)) cell = 1.0;
    const NodeGrid grid(mesh_.nodes, cell);

    // Rule 5: no two nodes closer than kMinNodeDistance x size.
    const double close = MeshTolerances::kMinNodeDistance * size_;
    for (const auto& [i, j] : grid.close_pairs(close)) {
      fail(5, [&, i = i, j = j] {
        return node_place(i) + " and " + node_text(j) + " are " +
               fmt(distance(mesh_.nodes[i], mesh_.nodes[j])) + " " + part_.units +
               " apart, closer than " + fmt(close) + " (" + fmt(MeshTolerances::kMinNodeDistance) +
               " x the part's size)";
      });
    }

    // Rule 5: no node inside a mesh edge (a hanging node).
    const double r = MeshTolerances::kHanging * size_;
    std::vector<std::uint32_t> hits;
    for (std::size_t lo = 0; lo + 1 < offsets_.size(); ++lo) {
      for (std::size_t k = offsets_[lo]; k < offsets_[lo + 1]; ++k) {
        if (k > offsets_[lo] && half_edges_[k].hi == half_edges_[k - 1].hi) continue;
        const auto a = static_cast<std::uint32_t>(lo);
        const std::uint32_t b = half_edges_[k].hi;
        const Vec3 xa = mesh_.nodes[a];
        const Vec3 xb = mesh_.nodes[b];
        hits.clear();
        grid.for_each_near_segment(xa, xb, r, [&](std::uint32_t n) {
          if (n == a || n == b) return;
          const Vec3 x = mesh_.nodes[n];
          if (segment_distance(x, xa, xb).first > r) return;
          if (distance(x, xa) <= r || distance(x, xb) <= r) return;  // too close: reported above
          hits.push_back(n);
        });
        std::sort(hits.begin(), hits.end());
        for (std::uint32_t n : hits) {
          const std::uint32_t el = half_edges_[k].element;
          fail(5, [&] {
            return node_place(n) + " hangs inside the mesh edge from node " + std::to_string(a) +
                   " to node " + std::to_string(b) + " of " + element_place(el);
          });
        }
      }
    }

    // Rule 6: every B-Rep vertex of a patch loop is a mesh node.
    const double on = MeshTolerances::kOnBrep * size_;
    std::vector<bool> seen(part_.vertices.size(), false);
    for (std::size_t p = 0; p < part_.patches.size(); ++p) {
      for (const Loop& loop : part_.patches[p].loops) {
        for (VertexId v : loop.vertices) {
          if (seen[v.index()] || part_.vertices[v.index()].from_arc) continue;
          seen[v.index()] = true;
          const Vec3 x = part_.vertices[v.index()].position;
          bool found = false;
          grid.for_each_in_box(x - Vec3{on, on, on}, x + Vec3{on, on, on}, [&](std::uint32_t n) {
            found = found || distance(mesh_.nodes[n], x) <= on;
          });
          if (!found) {
            fail(6, [&] {
              return "B-Rep vertex " + std::to_string(v.index()) + " at " + fmt(x) + " of " +
                     patch_label(p) + " is not a mesh node (no node within " + fmt(on) + " " +
                     part_.units + ")";
            });
          }
        }
      }
    }
  }

  const Part& part_;
  const QuadMesh& mesh_;
  const MeshCheckOptions& options_;
  const double size_;
  MeshCheck out_;
  std::array<std::vector<MeshFailure>, 7> by_rule_;
  std::vector<PatchIndex> indices_;
  std::vector<double> plane_tol_;
  std::vector<Sum> area_;
  std::unordered_multimap<std::uint64_t, std::uint32_t> edge_by_vertices_;
  std::vector<std::uint32_t> arc_edge_;  ///< per arc: the B-Rep edge that stands for it
  std::unordered_map<std::uint64_t, double> arc_sign_;  ///< (arc, patch): +1 arc bulges out
  std::vector<Sum> expected_;  ///< per patch: the area rule 4 expects
  std::vector<std::uint8_t> skip_;           ///< malformed or non-finite: left out
  std::vector<std::uint32_t> node_element_;  ///< first element using each node, or kNone
  double mean_edge_ = 0.0;
  std::vector<std::size_t> offsets_;  ///< CSR of half_edges_ by smaller node
  std::vector<HalfEdge> half_edges_;
  std::unordered_map<std::uint64_t, OnBrep> on_brep_;  ///< (node, patch) -> where it is
};

}  // namespace

bool MeshCheck::valid() const {
  for (std::size_t c : counts) {
    if (c != 0) return false;
  }
  return true;
}

std::string MeshCheck::report() const {
  std::string s;
  for (const MeshFailure& f : failures) s += f.message + "\n";
  return s;
}

MeshCheck check_mesh(const Part& part, const QuadMesh& mesh, const MeshCheckOptions& options) {
  return Checker(part, mesh, options).run();
}

}  // namespace laytracks
