// Rule 11 of build_part(): patches meet only along the edges they share. An edge of one patch
// that crosses another patch, lies inside it, or ends inside it, is refused with both names and
// the place (brep-json.md: "Patches connect only through shared edges"); so are two patches
// that share an edge and lie on top of each other there (one plane, the same side of it).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "build_state.hpp"
#include "describe.hpp"
#include "predicates.hpp"

namespace laytracks::detail {
namespace {

enum class Where : std::uint8_t { Outside, Boundary, Inside };

/// Where a point of a patch's plane (in its frame) lies: on its boundary (within `tol` of a
/// boundary segment), strictly inside the region, or outside it (in a hole, or beyond).
Where locate(const Polygon2& poly, Vec2 x, double tol) {
  bool inside = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& loop : poly.loops) {
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const Vec2 p = loop[j], q = loop[i];
      const Vec2 d = q - p;
      nearest = std::min(nearest, segment_distance(x, p, q));
      if ((p.y > x.y) != (q.y > x.y) && x.x < p.x + (x.y - p.y) * d.x / d.y) inside = !inside;
    }
  }
  if (nearest <= tol) return Where::Boundary;
  return inside ? Where::Inside : Where::Outside;
}

/// The parameters along ab where it meets the segments of the polygon's loops (2D).
std::vector<double> crossings(const Polygon2& poly, Vec2 a, Vec2 b) {
  std::vector<double> t{0.0, 1.0};
  const Vec2 ab = b - a;
  for (const auto& loop : poly.loops) {
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const Vec2 p = loop[j], q = loop[i];
      if (!segments_intersect(a, b, p, q)) continue;
      const Vec2 pq = q - p;
      const double den = cross(ab, pq);
      if (den != 0.0) {
        t.push_back(std::clamp(cross(p - a, pq) / den, 0.0, 1.0));
      } else {  // collinear overlap: its ends
        for (const Vec2 e : {p, q}) t.push_back(std::clamp(dot(e - a, ab) / dot(ab, ab), 0.0, 1.0));
      }
    }
  }
  std::sort(t.begin(), t.end());
  return t;
}

/// Two patches sharing an edge overlap there when they lie in one plane on the same side of
/// it: their inward directions at the edge (in each patch's plane, perpendicular to the edge,
/// towards its interior: left of its loops as oriented) agree. Every other check passes them
/// (a patch given twice shares all its edges and vertices with its copy), and the mesh then
/// holds two nodes at every place. Coplanar within the planarity tolerance: the sine of the
/// angle between the inward directions, times the larger patch's extent (its diagonal), within
/// the larger of the two patches' plane tolerances (`plane_tol`, check_patch_contacts').
void check_overlaps_at_edges(const BuildState& s,
                             const std::vector<double>& extent,
                             const std::vector<double>& plane_tol) {
  const Part& part = s.part;
  // Per edge shared by two or more patches: each patch's inward direction there.
  struct Side {
    std::size_t patch;
    Vec3 inward;
  };
  std::vector<std::vector<Side>> sides(part.edges.size());
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    const Vec3 n = part.patches[p].frame.n;
    for (const Loop& loop : part.patches[p].loops) {
      const std::size_t m = loop.vertices.size();
      for (std::size_t j = 0; j < m; ++j) {
        const EdgeId e = loop.edges[j];
        if (part.edges[e.index()].patches.size() < 2) continue;
        const Vec3 along = part.vertices[loop.vertices[(j + 1) % m].index()].position -
                           part.vertices[loop.vertices[j].index()].position;
        sides[e.index()].push_back({p, normalized(cross(n, along))});
      }
    }
  }
  // The overlap reported is the one at the edge of least vertex pair, the first pair of its
  // patches in their order.
  std::optional<std::pair<std::size_t, std::pair<Side, Side>>> found;
  const auto before = [&](std::size_t e, std::size_t f) {
    const BrepEdge &x = part.edges[e], &y = part.edges[f];
    return std::pair(x.a.value, x.b.value) < std::pair(y.a.value, y.b.value);
  };
  for (std::size_t e = 0; e < sides.size(); ++e) {
    if (found && !before(e, found->first)) continue;
    const std::vector<Side>& list = sides[e];
    for (std::size_t i = 0; i < list.size() && !(found && found->first == e); ++i) {
      for (std::size_t k = i + 1; k < list.size(); ++k) {
        const Side& x = list[i];
        const Side& y = list[k];
        if (dot(x.inward, y.inward) <= 0.0) continue;
        const double sine = norm(cross(x.inward, y.inward));
        const double reach = std::max(extent[x.patch], extent[y.patch]);
        if (sine * reach > std::max(plane_tol[x.patch], plane_tol[y.patch])) continue;
        found = {e, {x, y}};
        break;
      }
    }
  }
  if (!found) return;
  const BrepEdge& edge = part.edges[found->first];
  const auto& [x, y] = found->second;
  const Vec3 a = part.vertices[edge.a.index()].position;
  const Vec3 b = part.vertices[edge.b.index()].position;
  fail(patch_name(s, x.patch) + " and " + patch_name(s, y.patch) + " overlap: they share " +
       edge_name(s, edge.a, edge.b) + " and lie in one plane on the same side of it, near " +
       point(0.5 * (a + b)) + " (a patch given twice, or folded back onto its neighbour)");
}

}  // namespace

void check_patch_contacts(const BuildState& s) {
  const Part& part = s.part;
  const double tol = Tolerances::kOnEdge * part.size;
  const Vec3 pad{tol, tol, tol};
  std::vector<Box3> patch_boxes(part.patches.size());
  std::vector<double> extent(part.patches.size()), plane_tol(part.patches.size());
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    for (const Chain& c : s.chains[p])
      for (VertexId v : c.vertices) patch_boxes[p].add(part.vertices[v.index()].position);
    // A point is in a patch's plane within the planarity its own vertices were allowed.
    extent[p] = norm(patch_boxes[p].hi - patch_boxes[p].lo);
    plane_tol[p] = std::max(tol, Tolerances::kPlanarity * extent[p]);
    const Vec3 grow{plane_tol[p], plane_tol[p], plane_tol[p]};
    patch_boxes[p].add(patch_boxes[p].lo - grow);
    patch_boxes[p].add(patch_boxes[p].hi + grow);
  }
  check_overlaps_at_edges(s, extent, plane_tol);
  std::vector<Box3> edge_boxes;
  for (const BrepEdge& e : part.edges) {
    Box3 box;
    box.add(part.vertices[e.a.index()].position - pad);
    box.add(part.vertices[e.b.index()].position + pad);
    edge_boxes.push_back(box);
  }
  IndexPairs pairs = overlapping_boxes(edge_boxes, patch_boxes);
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [k, p] : pairs) {
    const BrepEdge& e = part.edges[k];
    if (std::find(e.patches.begin(), e.patches.end(), PatchId(p)) != e.patches.end()) continue;
    const Patch& patch = part.patches[p];
    const Vec3 a = part.vertices[e.a.index()].position, b = part.vertices[e.b.index()].position;
    const double da = dot(a - patch.frame.origin, patch.frame.n);
    const double db = dot(b - patch.frame.origin, patch.frame.n);
    const double pt = plane_tol[p];
    const std::string whose = edge_name(s, e.a, e.b) + " of " + patch_name(s, e.patches[0].index());
    const std::string rule =
        ": patches may meet only along edges they share (split the patch there, or move it)";
    // An end of the edge in the patch's plane, inside it.
    for (const auto& [v, d] : {std::pair{e.a, da}, std::pair{e.b, db}}) {
      const Vec3 x = part.vertices[v.index()].position;
      if (std::abs(d) <= pt && locate(patch.polygon, patch.frame.to_2d(x), tol) == Where::Inside) {
        fail(vertex_name(s, v) + " (of " + whose + ") lies inside " + patch_name(s, p) + " at " +
             point(x) + rule);
      }
    }
    if (std::abs(da) <= pt && std::abs(db) <= pt) {
      // In the plane: any stretch of it strictly inside the patch.
      const Vec2 a2 = patch.frame.to_2d(a), b2 = patch.frame.to_2d(b);
      const std::vector<double> t = crossings(patch.polygon, a2, b2);
      for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        if (!(t[i + 1] - t[i] > 1e-9)) continue;
        const double m = 0.5 * (t[i] + t[i + 1]);
        if (locate(patch.polygon, lerp(a2, b2, m), tol) == Where::Inside) {
          fail(whose + " lies inside " + patch_name(s, p) + " near " + point(a + m * (b - a)) + rule);
        }
      }
    } else if ((da > pt && db < -pt) || (da < -pt && db > pt)) {
      // Through the plane: where it pierces it.
      const Vec3 x = a + (da / (da - db)) * (b - a);
      if (locate(patch.polygon, patch.frame.to_2d(x), tol) == Where::Inside)
        fail(whose + " passes through " + patch_name(s, p) + " at " + point(x) + rule);
    }
  }
}

}  // namespace laytracks::detail
