// Rule 4 of build_part(): arcs are validated, discretised once each, and spliced into loops.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "build_state.hpp"
#include "describe.hpp"

namespace laytracks::detail {
namespace {


/// The unordered vertex pair of an edge as one key.
std::uint64_t edge_key(std::int64_t a, std::int64_t b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

/// Maps every arc's edge to the arc; refuses an arc with equal ends or a second arc on an edge.
std::unordered_map<std::uint64_t, std::size_t> index_arcs(const BuildState& s) {
  std::unordered_map<std::uint64_t, std::size_t> by_edge;
  for (std::size_t a = 0; a < s.raw.arcs.size(); ++a) {
    const RawArc& arc = s.raw.arcs[a];
    if (arc.from == arc.to) {
      fail("arc " + std::to_string(a) + " starts and ends at the same vertex " +
           std::to_string(arc.from) + "; a full circle needs at least three vertices and arcs");
    }
    const auto [it, inserted] = by_edge.emplace(edge_key(arc.from, arc.to), a);
    if (!inserted) {
      fail("arcs " + std::to_string(it->second) + " and " + std::to_string(a) +
           " both describe edge " + std::to_string(arc.from) + "-" + std::to_string(arc.to) +
           "; an edge can have at most one arc");
    }
  }
  return by_edge;
}

/// Records which patches use each arc; refuses an arc whose edge is in no loop.
void find_arc_users(BuildState& s, const std::unordered_map<std::uint64_t, std::size_t>& by_edge) {
  s.patch_arcs.assign(s.raw.patches.size(), {});
  for (std::size_t p = 0; p < s.raw.patches.size(); ++p) {
    for (const auto& loop : s.raw.patches[p].loops) {
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const auto it = by_edge.find(edge_key(loop[i], loop[(i + 1) % loop.size()]));
        if (it == by_edge.end()) continue;
        auto& users = s.arcs[it->second].users;
        if (users.empty() || users.back() != p) users.push_back(p);
        s.patch_arcs[p].push_back(it->second);
      }
    }
    std::sort(s.patch_arcs[p].begin(), s.patch_arcs[p].end());
    s.patch_arcs[p].erase(std::unique(s.patch_arcs[p].begin(), s.patch_arcs[p].end()),
                          s.patch_arcs[p].end());
  }
  for (std::size_t a = 0; a < s.arcs.size(); ++a) {
    if (s.arcs[a].users.empty()) {
      const RawArc& arc = s.raw.arcs[a];
      fail("arc " + std::to_string(a) + " joins vertices " + std::to_string(arc.from) + " and " +
           std::to_string(arc.to) + ", but no loop has the edge " + std::to_string(arc.from) + "-" +
           std::to_string(arc.to));
    }
  }
}

/// The circle through from, via and to (in that order); refuses a via point that coincides
/// with an end or is collinear with them.
void fit_circle(const BuildState& s, std::size_t index, ArcInfo& arc) {
  const RawArc& raw = s.raw.arcs[index];
  const Vec3 A = s.raw.vertices[static_cast<std::size_t>(raw.from)];
  const Vec3 B = s.raw.vertices[static_cast<std::size_t>(raw.to)];
  const Vec3 V = raw.via;
  const double min_distance = Tolerances::kMinVertexDistance * s.part.size;
  const std::string where = arc_name(s, index) + ": its via point " + point(V);
  if (distance(V, A) < min_distance || distance(V, B) < min_distance) {
    const std::int64_t end = distance(V, A) < min_distance ? raw.from : raw.to;
    fail(where + " coincides with vertex " + std::to_string(end));
  }
  const Vec3 va = A - V;
  const Vec3 vb = B - V;
  const Vec3 n = cross(va, vb);
  if (norm(n) / distance(A, B) <= min_distance) {
    fail(where + " is collinear with vertices " + std::to_string(raw.from) + " and " +
         std::to_string(raw.to) + ", so no circle passes through the three");
  }
  const Vec3 offset = (1.0 / (2.0 * dot(n, n))) * cross(dot(va, va) * vb - dot(vb, vb) * va, n);
  arc.from = VertexId(static_cast<std::size_t>(raw.from));
  arc.to = VertexId(static_cast<std::size_t>(raw.to));
  arc.center = V + offset;
  arc.radius = distance(A, arc.center);
  arc.axis = normalized(cross(V - A, B - V));
  const Vec3 e1 = normalized(A - arc.center);
  const Vec3 e2 = cross(arc.axis, e1);
  arc.span = std::atan2(dot(B - arc.center, e2), dot(B - arc.center, e1));
  if (arc.span <= 0.0) arc.span += 2.0 * kPi;
}

/// Number of segments for an arc: sagitta <= chord_tol and at most 90 degrees each, >= 2.
std::size_t segment_count(const BuildState& s, std::size_t index, const ArcInfo& arc) {
  const double theta_max = max_chord_angle(arc.radius, s.part.chord_tol);
  const double needed = std::ceil(arc.span / theta_max - 1e-9);
  if (!(needed <= static_cast<double>(kMaxArcSegments))) {
    const std::string count =
        needed < 1e15 ? std::to_string(static_cast<long long>(needed)) : "more than " + num(1e15);
    fail(arc_name(s, index) + " would need " + count +
         " segments to stay within the chord tolerance of " + len(s, s.part.chord_tol) +
         " (radius " + len(s, arc.radius) + "); at most " + std::to_string(kMaxArcSegments) +
         " are allowed");
  }
  return std::max<std::size_t>(2, static_cast<std::size_t>(needed));
}

/// Appends the interior points of arc `index` to the part, uniform in angle.
void discretise(BuildState& s, std::size_t index, ArcInfo& arc) {
  const std::size_t n = segment_count(s, index, arc);
  const Vec3 e1 = normalized(s.part.vertices[arc.from.index()].position - arc.center);
  const Vec3 e2 = cross(arc.axis, e1);
  for (std::size_t k = 1; k < n; ++k) {
    const double t = arc.span * static_cast<double>(k) / static_cast<double>(n);
    const Vec3 p = arc.center + arc.radius * (std::cos(t) * e1 + std::sin(t) * e2);
    arc.points.emplace_back(s.part.vertices.size());
    s.part.vertices.push_back({p, -1, true});
    s.arc_point_of.emplace_back(index, k);
  }
}

/// The loop with its arc edges replaced by their points, in the loop's direction.
Chain make_chain(const BuildState& s,
                 const std::vector<std::int64_t>& loop,
                 const std::unordered_map<std::uint64_t, std::size_t>& by_edge) {
  Chain c;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const std::int64_t u = loop[i];
    const std::int64_t w = loop[(i + 1) % loop.size()];
    c.vertices.emplace_back(static_cast<std::size_t>(u));
    const auto it = by_edge.find(edge_key(u, w));
    if (it == by_edge.end()) {
      c.seg_arc.push_back(-1);
      c.seg_forward.push_back(1);
      continue;
    }
    const ArcInfo& arc = s.arcs[it->second];
    const bool forward = arc.from.index() == static_cast<std::size_t>(u);
    if (forward) {
      c.vertices.insert(c.vertices.end(), arc.points.begin(), arc.points.end());
    } else {
      c.vertices.insert(c.vertices.end(), arc.points.rbegin(), arc.points.rend());
    }
    c.seg_arc.insert(c.seg_arc.end(), arc.points.size() + 1, static_cast<std::int64_t>(it->second));
    c.seg_forward.insert(c.seg_forward.end(), arc.points.size() + 1, forward ? 1 : 0);
  }
  return c;
}

}  // namespace

void build_arcs(BuildState& s, const BuildOptions& options) {
  s.part.chord_tol = options.chord_tol.value_or(Tolerances::kDefaultChord * s.part.size);
  s.arcs.assign(s.raw.arcs.size(), {});
  const auto by_edge = index_arcs(s);
  find_arc_users(s, by_edge);
  for (std::size_t a = 0; a < s.arcs.size(); ++a) {
    fit_circle(s, a, s.arcs[a]);
    discretise(s, a, s.arcs[a]);
  }
  s.chains.assign(s.raw.patches.size(), {});
  for (std::size_t p = 0; p < s.raw.patches.size(); ++p) {
    for (const auto& loop : s.raw.patches[p].loops)
      s.chains[p].push_back(make_chain(s, loop, by_edge));
  }
  for (const ArcInfo& arc : s.arcs) {
    PartArc out;
    out.from = arc.from;
    out.to = arc.to;
    out.center = arc.center;
    out.radius = arc.radius;
    out.e1 = normalized(s.part.vertices[arc.from.index()].position - arc.center);
    out.e2 = cross(arc.axis, out.e1);
    out.span = arc.span;
    out.points = arc.points;
    s.part.arcs.push_back(std::move(out));
  }
  if (s.arcs.empty()) return;
  std::vector<VertexId> ids;
  for (std::size_t i = 0; i < s.used.size(); ++i) {
    if (s.used[i]) ids.emplace_back(i);
  }
  for (std::size_t i = s.file_vertex_count(); i < s.part.vertices.size(); ++i) ids.emplace_back(i);
  check_vertex_spacing(s, ids);
}

}  // namespace laytracks::detail

namespace laytracks {

double max_chord_angle(double radius, double chord_tol) {
  const double x = chord_tol / radius;
  // 2 acos(1 - x) written as 4 asin(sqrt(x / 2)): no cancellation when x is tiny.
  const double theta_max = x >= 1.0 ? kPi : 4.0 * std::asin(std::sqrt(0.5 * x));
  return std::min(theta_max, 0.5 * kPi);
}

Vec3 PartArc::at(double u) const {
  const double t = span * u;
  return center + radius * (std::cos(t) * e1 + std::sin(t) * e2);
}

}  // namespace laytracks
