// The medial axis (MA) of one patch's polygon, as a plain graph, with the two-way mapping
// boundary -> MA -> other boundary that the rail stage relies on (paper, sections 2-3).
// No CGAL type leaves medial/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/geometry.hpp"
#include "laytracks/brep/polygon.hpp"

namespace laytracks {

using MaVertexId = Id<struct MaVertexTag>;
using MaEdgeId = Id<struct MaEdgeTag>;

/// A Voronoi site of the boundary: an open segment (vertex `index` to `index + 1` of the loop)
/// or a single corner (vertex `index` of the loop). Only reflex corners are sites of MA edges.
struct BoundarySite {
  enum class Kind : std::uint8_t { Segment, Corner };
  Kind kind = Kind::Segment;
  std::uint32_t loop = 0;
  std::uint32_t index = 0;

  friend bool operator==(const BoundarySite& a, const BoundarySite& b) {
    return a.kind == b.kind && a.loop == b.loop && a.index == b.index;
  }
  friend bool operator!=(const BoundarySite& a, const BoundarySite& b) { return !(a == b); }
  /// Loop-major order: loop, then index, then segment before corner.
  friend bool operator<(const BoundarySite& a, const BoundarySite& b) {
    if (a.loop != b.loop) return a.loop < b.loop;
    if (a.index != b.index) return a.index < b.index;
    return a.kind < b.kind;
  }
};

/// A point of the boundary: on a segment site at parameter s in [0, 1] from its first vertex,
/// or a corner site (s = 0).
struct BoundaryPoint {
  BoundarySite site;
  double s = 0.0;
  Vec2 position;
};

struct MaVertex {
  Vec2 position;
  double radius = 0.0;  ///< distance to the boundary; 0 at a convex corner
  std::uint32_t degree = 0;
  /// Set when the vertex sits on a convex corner of the polygon (an end point of the MA).
  std::optional<BoundarySite> corner;
  /// Every site the vertex's maximal disk touches (sorted, unique). A branch point touches >= 3;
  /// so can a vertex whose extra branches were pruned at smooth corners.
  std::vector<BoundarySite> sites;
};

enum class MaEdgeKind : std::uint8_t {
  Line,     ///< bisector of two segments, or of two corners
  Parabola  ///< points equidistant from a reflex corner and a segment
};

/// An MA edge from vertex a to vertex b. Walking from a to b, `left` is the site on the left
/// and `right` the site on the right; every point of the edge is equidistant from both.
struct MaEdge {
  MaVertexId a;
  MaVertexId b;
  BoundarySite left;
  BoundarySite right;
  MaEdgeKind kind = MaEdgeKind::Line;
};

enum class Side : std::uint8_t { Left, Right };

/// A point of the MA on an edge, at parameter t in [0, 1] from its vertex a to its vertex b.
/// For a line t is linear in arc length; for a parabola t is linear in the position of the
/// touching point along its segment site. When the axis is a single point (a polygonised
/// disk), `edge` is invalid and the point is that vertex.
struct MaPoint {
  MaEdgeId edge;
  double t = 0.0;
  Vec2 position;
  double radius = 0.0;
  /// Set by project() where the boundary point is not where this point's disk touches it, and
  /// the rail between them leans: in a spread zone, or where a pruned corner's or arc's
  /// boundary maps to one vertex (MedialAxis::project).
  bool off_normal = false;
};

/// Which segment Voronoi diagram the medial axis is extracted from. Both give the same axis
/// (tests/medial/test_backends.cpp); docs/medial-backends.md has the timings and the rules.
enum class VoronoiBackend : std::uint8_t {
  /// CGAL's Segment_Delaunay_graph_2: exact on the input doubles; slow where sites are nearly
  /// degenerate (polygonised circles).
  Cgal,
  /// Boost.Polygon's voronoi, exact on the corners rounded to a grid of 2^31 units across the
  /// polygon; 4x to 40x faster. Where the rounding changes the diagram beyond local repair, two
  /// corners share a grid point, or the axis fails its self-check, CGAL does the polygon again.
  Boost,
  /// Boost without that fallback: throws InternalError instead (for tests and benchmarks).
  BoostOnly
};

/// MedialAxis::choose_round_holes: a concave circle is mapped along rays from its centre where
/// a chord end's fan may hold more rails than this.
inline constexpr double kRoundHoleFanRails = 3.0;

/// A convex corner where the boundary turns by less than this (25 degrees) is nearly flat: the
/// medial axis prunes its branch as an arc point's (docs/medial.md, step 5).
inline constexpr double kFlatCornerTurn = 25.0 * 3.14159265358979323846 / 180.0;

struct MedialOptions {
  /// Sagitta bound used to discretise the arcs of this polygon (part units). Structure smaller
  /// than a few times this, left over after pruning smooth branches, is an artefact of the
  /// discretisation and is pruned too. 0 disables that step.
  double chord_tol = 0.0;
  /// A convex corner where the boundary turns by less than this (radians) is treated as smooth:
  /// its branch, from the corner to the first junction, is pruned as an arc point's is. A
  /// polygonised curve given as straight edges (a 60-gon ellipse: turns of 5-20 degrees) has
  /// a branch at every vertex, each a long thin corridor of its own. 0 disables it.
  double flat_turn = kFlatCornerTurn;
  /// The largest magnitude of a coordinate of the polygon's corners as the part gives them (in
  /// 3D, before the projection to the patch's plane). Their rounding, about DBL_EPSILON x this,
  /// makes a corner's turn uncertain by about that over its shorter side: a corner turning by
  /// less than kStraightNoise x that is straight (docs/medial.md, step 5). 0: only the
  /// polygon's own coordinates count.
  double coordinate_scale = 0.0;
  /// The Voronoi backend (see VoronoiBackend).
  VoronoiBackend backend = VoronoiBackend::Boost;
};

class MedialAxis {
 public:
  MedialAxis() = default;
  MedialAxis(Polygon2 polygon, std::vector<MaVertex> vertices, std::vector<MaEdge> edges);

  const Polygon2& polygon() const { return polygon_; }
  const std::vector<MaVertex>& vertices() const { return vertices_; }
  const std::vector<MaEdge>& edges() const { return edges_; }
  const MaVertex& vertex(MaVertexId v) const { return vertices_[v.index()]; }
  const MaEdge& edge(MaEdgeId e) const { return edges_[e.index()]; }
  /// The edges incident to a vertex, in ascending id order.
  const std::vector<MaEdgeId>& incident(MaVertexId v) const { return incident_[v.index()]; }
  /// Branch points: vertices of degree >= 3.
  std::vector<MaVertexId> branch_points() const;

  /// Point and radius at parameter t of an edge (exact for lines, and for parabolas through
  /// their focus-directrix form).
  MaPoint point_on_edge(MaEdgeId e, double t) const;
  /// Points along an edge for drawing, chords no longer than max_chord (at least the two ends).
  std::vector<Vec2> sample_edge(MaEdgeId e, double max_chord) const;

  /// Boundary -> MA: the centre of the maximal disk that touches the boundary at point p of a
  /// segment site. At a convex corner this is the MA end point there (radius 0). On or beside
  /// a polygonised convex arc, whose branches were pruned, it is the vertex whose circle passes
  /// closest to p (the arc's centre, within the chord tolerance). Empty only when p is not on
  /// a segment or the axis has no vertex of positive radius.
  /// In a spread zone (a pruned corner whose boundary would all map to one vertex where the
  /// axis runs on both ways, docs/medial.md) the zone's boundary is mapped in proportion to
  /// arc length onto the axis round that vertex, and the point is marked `off_normal`.
  std::optional<MaPoint> project(const BoundaryPoint& p) const;
  /// The side of p's MA point m (from project) across the axis from p: the side whose site is
  /// not p's own (in a spread zone, not the zone's site along m's edge).
  Side far_side(const MaPoint& m, const BoundaryPoint& p) const;
  /// True when p lies in a spread zone: its rail leans, longer than the radius at its MA point.
  bool in_spread_zone(const BoundaryPoint& p) const { return zone_of(p) != nullptr; }
  /// Boundary -> MA at a reflex corner, whose maximal disks form a fan: w in [0, 1] sweeps the
  /// fan from the normal of the incoming segment (w = 0) to that of the outgoing one (w = 1).
  std::optional<MaPoint> project_corner(std::uint32_t loop, std::uint32_t vertex, double w) const;
  /// MA -> boundary: where the maximal disk at p touches the boundary on the given side.
  BoundaryPoint touching_point(const MaPoint& p, Side side) const;
  /// MA -> boundary at a vertex: every distinct touching point of its maximal disk
  /// (>= 3 at a branch point).
  std::vector<BoundaryPoint> touching_points(MaVertexId v) const;
  /// The two-way mapping: boundary -> MA -> the other side (none when the axis is one point).
  std::optional<BoundaryPoint> opposite(const BoundaryPoint& p) const;

  /// Round holes (docs/medial.md): the concave circles of the polygon (Polygon2::circles whose
  /// region is outside: holes, concave fillets) that the mapping takes along rays from their
  /// centres at this element size: those where a chord end's fan, the rails a polygon vertex
  /// would gather, may hold more than kRoundHoleFanRails, (R + r) delta / h (R the radius,
  /// delta the chord angle, r the largest radius of the axis beside the circle). The others,
  /// and every circle until this is called, map as the polygon does. Returns how many.
  std::size_t choose_round_holes(double element_size);
  /// The circles choose_round_holes chose.
  std::vector<Circle2> round_circles() const;
  /// Whether it chose Polygon2::circles[k].
  bool is_round(std::size_t k) const { return k < round_.size() && round_[k] != 0; }

  /// Self-check: radii equal the distance to the boundary (1e-9 relative), vertices inside the
  /// polygon, degrees consistent, edges equidistant from their sites, the axis in one piece.
  /// Returns the problems found, each a sentence; empty when valid.
  std::vector<std::string> validate() const;

 private:
  Polygon2 polygon_;
  std::vector<MaVertex> vertices_;
  std::vector<MaEdge> edges_;
  std::vector<std::vector<MaEdgeId>> incident_;
  /// For each site, the MA edges having it as a site (its Voronoi cell's medial boundary).
  /// Indexed by cell_index(); corners and segments of loop l at 2 * (offset of l + i) + kind.
  std::vector<std::vector<MaEdgeId>> cells_;
  std::vector<std::size_t> loop_offset_;
  double size_ = 0.0;  ///< the polygon's bounding-box diagonal
  /// A spread zone: loop pieces (segment, parameter range, arc length at its start), mapped in
  /// proportion to arc length onto its steps along the axis, from the image's end on one side
  /// of the root through the root to its end on the other (two steps, the root's own edges,
  /// unless the zone is extended: docs/medial.md).
  struct SpreadZone {
    struct Piece {
      std::uint32_t segment = 0;
      double s0 = 0.0, s1 = 0.0, at = 0.0;
    };
    /// A piece of the axis image: edge `edge` from t0 to t1 takes the zone's fractions f0 to
    /// f1 of its boundary length; `near` is the edge's site on the zone's side.
    struct Step {
      MaEdgeId edge;
      double t0 = 0.0, t1 = 0.0, f0 = 0.0, f1 = 0.0;
      BoundarySite near;
    };
    std::uint32_t loop = 0;
    std::vector<Piece> pieces;
    double length = 0.0;
    /// From the image's end on the first side, through the root, to its end on the second.
    std::vector<Step> steps;
  };
  std::vector<SpreadZone> zones_;
  /// Per Polygon2 circle: mapped along rays from its centre (choose_round_holes).
  std::vector<char> round_;
  /// Per segment (by loop_offset_): the circle it is a chord of with the region outside it,
  /// or -1; empty when the polygon names no circles.
  std::vector<std::int32_t> chord_circle_;
  /// Indices into zones_, ascending: per segment (by cell_index / 2) the zones with a piece on
  /// it, per edge the zones mapped onto it (project and touching_point look up only these).
  std::vector<std::vector<std::uint32_t>> zones_on_segment_, zones_on_edge_;

  void find_spread_zones();
  const SpreadZone* zone_of(const BoundaryPoint& p) const;

  /// The circle (Polygon2::circles) a site lies on when the region is outside it, a round
  /// hole's or a concave fillet's, and choose_round_holes chose it: a segment that is a chord
  /// of it with its centre on the right, or a corner between two such chords. -1 otherwise
  /// (docs/medial.md, "Round holes").
  int concave_circle(const BoundarySite& s) const;
  /// The same whether chosen or not (choose_round_holes picks among these).
  int site_circle(const BoundarySite& s) const;
  /// Where the ray from circle k's centre through x crosses its chords in loop l, searched
  /// from segment `hint` both ways along the run of them; where the ray passes the run, the
  /// run's end nearer the ray. Empty only when no chord of k is next to `hint`.
  std::optional<BoundaryPoint> radial_foot(std::uint32_t loop,
                                           std::uint32_t hint,
                                           int k,
                                           Vec2 x) const;
  /// The nearest MA point on the ray from circle k's centre through boundary point x of
  /// segment site `site`, among the edges of the cells of that run of chords and corners.
  std::optional<MaPoint> radial_project(const BoundarySite& site, int k, Vec2 x) const;

  std::size_t cell_index(const BoundarySite& s) const;
  /// Parameter of x along edge e (unclamped), and the MA point there if x lies on the edge.
  std::optional<MaPoint> locate(MaEdgeId e, Vec2 x) const;
};

/// Computes the medial axis of a polygon with holes (outer CCW, holes CW, simple, as build_part
/// guarantees). Throws InternalError if the result fails its own validation.
MedialAxis compute_medial_axis(const Polygon2& polygon, const MedialOptions& options = {});

}  // namespace laytracks
