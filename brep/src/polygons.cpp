// Rule 8 of build_part(): exact checks of every patch's loops in its 2D frame. Candidate
// segment pairs come from CGAL::box_intersection_d; each is decided with exact predicates.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <tuple>

#include "build_state.hpp"
#include "describe.hpp"
#include "predicates.hpp"

namespace laytracks::detail {
namespace {

/// Segment i of loop l: from loops[l][i] to loops[l][i + 1] (cyclically).
struct SegmentRef {
  std::size_t loop;
  std::size_t index;
};

enum class Contact { Folds, Crosses, Touches };

/// Two segments that meet where they must not; `first` precedes `second` in loop order. They
/// meet at `where`, which is an end point of one of them unless `endpoint` is -1: 0 and 1 for
/// the start and end of `first`, 2 and 3 for those of `second`.
struct Conflict {
  SegmentRef first;
  SegmentRef second;
  Contact contact;
  Vec2 where;
  int endpoint = -1;
};

using Loops2 = std::vector<std::vector<Vec2>>;

Vec2 start(const Loops2& loops, SegmentRef s) { return loops[s.loop][s.index]; }
Vec2 end(const Loops2& loops, SegmentRef s) {
  return loops[s.loop][(s.index + 1) % loops[s.loop].size()];
}

bool precedes(SegmentRef a, SegmentRef b) {
  return std::tie(a.loop, a.index) < std::tie(b.loop, b.index);
}

/// Refuses a loop whose vertices all lie on one line (exact).
void check_area(const BuildState& s, std::size_t p, std::size_t l) {
  const std::vector<Vec2>& loop = s.loops2d[p][l];
  for (std::size_t i = 2; i < loop.size(); ++i) {
    if (orientation(loop[0], loop[1], loop[i]) != 0) return;
  }
  fail(patch_name(s, p) + ": " + loop_name(l) + " has zero area: its vertices lie on one line");
}

/// How two intersecting non-adjacent segments ab and cd meet: a proper crossing (endpoint -1,
/// at the computed point) or a touch at an end point (0..3 for a, b, c, d).
Conflict meeting(SegmentRef x, SegmentRef y, Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const int oc = orientation(a, b, c);
  const int od = orientation(a, b, d);
  const int oa = orientation(c, d, a);
  const int ob = orientation(c, d, b);
  if (oc * od < 0 && oa * ob < 0) {
    const double t = cross(c - a, d - c) / cross(b - a, d - c);
    return {x, y, Contact::Crosses, a + t * (b - a), -1};
  }
  if (oc == 0 && collinear_are_ordered(a, c, b)) return {x, y, Contact::Touches, c, 2};
  if (od == 0 && collinear_are_ordered(a, d, b)) return {x, y, Contact::Touches, d, 3};
  if (oa == 0 && collinear_are_ordered(c, a, d)) return {x, y, Contact::Touches, a, 0};
  return {x, y, Contact::Touches, b, 1};
}

/// The conflict between two segments, if any: adjacent ones must not fold back, others must not
/// meet at all.
std::optional<Conflict> conflict(const Loops2& loops, SegmentRef x, SegmentRef y) {
  if (precedes(y, x)) std::swap(x, y);
  if (x.loop == y.loop) {
    const std::size_t m = loops[x.loop].size();
    if (y.index == x.index + 1 || (x.index == 0 && y.index == m - 1)) {
      // Adjacent: the shared vertex is q, the others p and r.
      const bool x_first = y.index == x.index + 1;
      const Vec2 p = x_first ? start(loops, x) : start(loops, y);
      const Vec2 q = x_first ? end(loops, x) : end(loops, y);
      const Vec2 r = x_first ? end(loops, y) : end(loops, x);
      if (orientation(p, q, r) == 0 && !collinear_are_ordered(p, q, r)) {
        return Conflict{x, y, Contact::Folds, q, x_first ? 1 : 0};
      }
      return std::nullopt;
    }
  }
  const Vec2 a = start(loops, x), b = end(loops, x), c = start(loops, y), d = end(loops, y);
  if (!segments_intersect(a, b, c, d)) return std::nullopt;
  return meeting(x, y, a, b, c, d);
}

/// The vertex of patch p at which a conflict is (endpoint >= 0 only).
VertexId conflict_vertex(const BuildState& s, std::size_t p, const Conflict& c) {
  const SegmentRef seg = c.endpoint < 2 ? c.first : c.second;
  const auto& vertices = s.chains[p][seg.loop].vertices;
  return vertices[(seg.index + (c.endpoint % 2 == 1 ? 1 : 0)) % vertices.size()];
}

/// The message for a conflict in patch p.
std::string describe(const BuildState& s, std::size_t p, const Conflict& c) {
  const std::string prefix = patch_name(s, p) + ": ";
  if (c.contact == Contact::Folds) {
    const VertexId q = conflict_vertex(s, p, c);
    return prefix + loop_name(c.first.loop) + " folds back on itself at " + vertex_name(s, q) +
           " " + point(s.part.vertices[q.index()].position);
  }
  const Vec3 where = c.endpoint < 0 ? s.part.patches[p].frame.to_3d(c.where)
                                    : s.part.vertices[conflict_vertex(s, p, c).index()].position;
  const std::string verb = c.contact == Contact::Crosses ? " crosses " : " touches ";
  const std::string object = c.first.loop == c.second.loop ? "itself" : loop_name(c.first.loop);
  return prefix + loop_name(c.second.loop) + verb + object + " near " + point(where, s.part.size);
}

/// Every segment of the loops, in loop order, with its bounding box.
void segment_boxes(const Loops2& loops,
                   std::vector<SegmentRef>& segments,
                   std::vector<Box2>& boxes) {
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (std::size_t i = 0; i < loops[l].size(); ++i) {
      segments.push_back({l, i});
      Box2 box;
      box.add(start(loops, segments.back()));
      box.add(end(loops, segments.back()));
      boxes.push_back(box);
    }
  }
}

/// The first (in loop order) pair of segments of the loops that meet where they must not.
std::optional<Conflict> first_conflict(const Loops2& loops) {
  std::vector<SegmentRef> segments;
  std::vector<Box2> boxes;
  segment_boxes(loops, segments, boxes);
  std::optional<Conflict> first;
  for (const auto& [i, j] : overlapping_boxes(boxes)) {
    const auto c = conflict(loops, segments[i], segments[j]);
    if (!c) continue;
    if (!first || precedes(c->first, first->first) ||
        (!precedes(first->first, c->first) && precedes(c->second, first->second))) {
      first = c;
    }
  }
  return first;
}

/// Refuses the first (in loop order) pair of segments of patch p that meet where they must not.
void check_segments(const BuildState& s, std::size_t p) {
  if (const std::optional<Conflict> first = first_conflict(s.loops2d[p]))
    fail(describe(s, p, *first));
}

/// Exact ray-crossing test: does the ray from p towards +x cross segment ab (half-open rule)?
bool ray_crosses(Vec2 p, Vec2 a, Vec2 b) {
  if (a.y <= p.y && p.y < b.y) return orientation(a, b, p) > 0;
  if (b.y <= p.y && p.y < a.y) return orientation(a, b, p) < 0;
  return false;
}

/// Refuses a hole outside the outer loop or inside another hole. Loops neither touch nor cross
/// (check_segments), so testing one vertex of each hole decides: exact ray parity, with the
/// segments each ray may cross found by box intersection.
void check_hole_placement(const BuildState& s, std::size_t p) {
  const Loops2& loops = s.loops2d[p];
  if (loops.size() < 2) return;
  std::vector<SegmentRef> segments;
  std::vector<Box2> boxes;
  segment_boxes(loops, segments, boxes);
  double right = -std::numeric_limits<double>::infinity();
  for (const Box2& box : boxes) right = std::max(right, box.hi.x);
  std::vector<Box2> rays(loops.size());  // rays[l]: from loops[l][0] to the right; 0 unused
  for (std::size_t l = 1; l < loops.size(); ++l) {
    rays[l].add(loops[l][0]);
    rays[l].add({right, loops[l][0].y});
  }
  std::vector<std::pair<std::size_t, std::size_t>> crossings;  // (hole, loop its ray crosses)
  for (const auto& [r, k] : overlapping_boxes(rays, boxes)) {
    const SegmentRef seg = segments[k];
    if (r == 0 || seg.loop == r) continue;
    if (ray_crosses(loops[r][0], start(loops, seg), end(loops, seg))) {
      crossings.emplace_back(r, seg.loop);
    }
  }
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::vector<std::size_t>> inside(loops.size());  // loops that contain each hole
  for (std::size_t i = 0; i < crossings.size();) {
    std::size_t j = i;
    while (j < crossings.size() && crossings[j] == crossings[i]) ++j;
    if ((j - i) % 2 == 1) inside[crossings[i].first].push_back(crossings[i].second);
    i = j;
  }
  for (std::size_t l = 1; l < loops.size(); ++l) {
    const VertexId v = s.chains[p][l].vertices[0];
    if (inside[l].empty() || inside[l][0] != 0) {
      fail(patch_name(s, p) + ": " + loop_name(l) + " lies outside the outer loop (its " +
           vertex_name(s, v) + " is at " + point(s.part.vertices[v.index()].position) + ")");
    }
    if (inside[l].size() > 1) {
      fail(patch_name(s, p) + ": " + loop_name(l) + " lies inside " + loop_name(inside[l][1]) +
           "; a hole cannot be inside another hole");
    }
  }
}

/// Pieces each chord of an arc is cut into for check_arc_circles: 8 pieces come within 1/64 of
/// the chord's sagitta (sagitta grows with the square of the angle), so within chord_tol / 64
/// of the circle.
constexpr std::size_t kCircleCheckPieces = 8;

/// Refuses a patch whose arcs, as circles, meet another edge or arc. The loops checked by
/// check_segments() run along the arcs' chords, but the mesh puts its nodes on the circles (the
/// boundary follows the arc): an edge that passes between a chord and its circle, or another
/// arc's circle that does, would give quads outside the patch. Each chord is replaced by
/// kCircleCheckPieces pieces on the circle and the loops are checked again, exactly, as polygons.
void check_arc_circles(const BuildState& s, std::size_t p) {
  if (s.patch_arcs[p].empty()) return;
  const Frame& frame = s.part.patches[p].frame;
  Loops2 fine(s.loops2d[p].size());
  std::vector<std::vector<std::int64_t>> arc_of(fine.size());  // fine segment -> arc, or -1
  for (std::size_t l = 0; l < fine.size(); ++l) {
    const Chain& chain = s.chains[p][l];
    const std::vector<Vec2>& loop = s.loops2d[p][l];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      fine[l].push_back(loop[i]);
      const std::int64_t a = chain.seg_arc[i];
      if (a < 0) {
        arc_of[l].push_back(-1);
        continue;
      }
      // The chord's ends as fractions of the arc's angle (its points are uniform in angle),
      // and the pieces between them on the circle (PartArc::at).
      const PartArc& arc = s.part.arcs[static_cast<std::size_t>(a)];
      const auto fraction = [&](VertexId v) {
        if (v == arc.from) return 0.0;
        if (v == arc.to) return 1.0;
        return static_cast<double>(s.arc_point_of[v.index() - s.file_vertex_count()].second) /
               static_cast<double>(arc.points.size() + 1);
      };
      const double u0 = fraction(chain.vertices[i]);
      const double u1 = fraction(chain.vertices[(i + 1) % loop.size()]);
      for (std::size_t k = 1; k < kCircleCheckPieces; ++k)
        fine[l].push_back(frame.to_2d(
            arc.at(u0 + (u1 - u0) * static_cast<double>(k) / kCircleCheckPieces)));
      arc_of[l].insert(arc_of[l].end(), kCircleCheckPieces, a);
    }
  }
  const std::optional<Conflict> first = first_conflict(fine);
  if (!first) return;
  // The arc, and what it meets: another arc or an edge of a loop.
  const std::int64_t a1 = arc_of[first->first.loop][first->first.index];
  const std::int64_t a2 = arc_of[first->second.loop][first->second.index];
  const std::int64_t arc = a1 >= 0 ? a1 : a2;
  const SegmentRef other = a1 >= 0 ? first->second : first->first;
  const std::int64_t other_arc = a1 >= 0 ? a2 : a1;
  const std::string what = other_arc >= 0 && other_arc != arc
                               ? arc_name(s, static_cast<std::size_t>(other_arc)) + " of " +
                                     loop_name(other.loop)
                           : other_arc == arc ? "itself"
                                              : "an edge of " + loop_name(other.loop);
  fail(patch_name(s, p) + ": " + arc_name(s, static_cast<std::size_t>(arc)) +
       ", as a circle, meets " + what + " near " +
       point(frame.to_3d(first->where), s.part.size) +
       " (between the points that discretise it, within the chord tolerance " +
       len(s, s.part.chord_tol) + " of its chords)");
}

}  // namespace

std::string loop_conflict(const BuildState& s, std::size_t p) {
  const Frame& frame = s.part.patches[p].frame;
  Loops2 loops;
  for (const Chain& c : s.chains[p]) {
    loops.emplace_back();
    for (VertexId v : c.vertices)
      loops.back().push_back(frame.to_2d(s.part.vertices[v.index()].position));
  }
  const std::optional<Conflict> first = first_conflict(loops);
  return first ? describe(s, p, *first) : std::string();
}

void check_polygons(const BuildState& s) {
  for (std::size_t p = 0; p < s.loops2d.size(); ++p) {
    for (std::size_t l = 0; l < s.loops2d[p].size(); ++l) check_area(s, p, l);
    check_segments(s, p);
    check_hole_placement(s, p);
    check_arc_circles(s, p);
  }
}

}  // namespace laytracks::detail
