// Private: quads inside one face of a patch cut by its rails (docs/mesher.md, "Filling a face").
// Everything here is 2D, in the patch frame, and local to the face.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/geometry.hpp"

namespace laytracks::mesher_detail {

/// A run of face-boundary edges of one kind: a piece of the patch boundary, or a rail chain
/// (one or more rail segments end to end, through MA points).
struct FaceSide {
  enum class Kind : std::uint8_t { Boundary, Rail };
  Kind kind = Kind::Boundary;
  std::uint32_t first = 0;  ///< index in the face cycle of its first node
  std::uint32_t edges = 0;  ///< mesh edges along it
  /// For a rail chain: cycle offsets (from `first`) of the MA points it passes inside it.
  std::vector<std::uint32_t> joints;
};

/// The boundary of a face: its mesh nodes counter-clockwise (the face on the left), and how the
/// cycle splits into sides. The node count is even (the parity stage sees to it).
struct FaceInput {
  std::vector<Vec2> cycle;
  std::vector<FaceSide> sides;
  /// Per cycle node, when known (a patch's face, a re-fill's cavity; empty for the pieces a
  /// template cuts): true for a node off the part's boundary (an MA node, a rail's inner node,
  /// a cavity node that may move). The reflex cut halves only such corners (kReflexHalveMin).
  std::vector<bool> free_nodes;
};

enum class FillKind : std::uint8_t {
  Grid,     ///< two rails and two boundary pieces, matching counts: a structured grid
  Diamond,  ///< a strip whose rails differ by two edges: rows, and one quad across the axis
  Quad,     ///< four nodes: the face itself
  Ring,     ///< four nodes with a flat corner: an inner quad and four around it
  Split,    ///< any other face: a coarse triangulation, each triangle split into three quads
  Rows,     ///< rows from a one-edge cap, the rest by another template
  Cut,      ///< any simple polygon: cut by chords into smaller polygons, down to quads
  Pairs,    ///< any simple polygon: triangulated, triangles paired or split into quads
  Strip,    ///< a long strip whose caps or rails differ: rows from both caps, a short remainder
  Ogrid,    ///< a round face: a rectangle of quads in the middle, rings of quads round it
  Arms,     ///< a junction of three or more arms: rows from each arm's cap, the rest inside
  Taper,    ///< a strip whose caps differ by 4 edges or more: rows narrowing step by step
  Reflex,   ///< a face cut in two at a reflex corner, each piece filled by any template
  Three,    ///< four sides, the two longer ones meeting: three grids round one inner node
  Lattice,  ///< split with inner coarse nodes on a square lattice: quads of the face's edge size
  Match,    ///< a graded triangulation inside, its triangles paired into quads
  Sided,    ///< three or five corners: as many grids round one inner node
  Kites,    ///< the needle-tip attempt's last resort: cut, and corners cut off as kites
};
const char* to_string(FillKind kind);

/// Quads of a face. Node index i < cycle.size() is cycle node i; i >= cycle.size() is
/// interior[i - cycle.size()]. Quads run counter-clockwise.
struct FaceMesh {
  FillKind kind = FillKind::Quad;
  std::vector<Vec2> interior;
  std::vector<std::array<std::uint32_t, 4>> quads;
  double min_jacobian = 0.0;  ///< smallest corner scaled Jacobian of its quads
};

/// A polygon's own frame: a similarity taking its node cycle[0] to the origin, the direction to
/// cycle[1] to +x and its mean edge to length 1, positions rounded to multiples of kLocalGrid.
/// A cavity (refill_cavities) posed in it is the same problem, bit for bit, in every pose of
/// the part (turned, mirrored, scaled: its positions in the patch frame differ only by
/// rounding), so the templates and the relaxations, which amplify any difference, decide alike
/// (a cut template gave a worst corner of 0.61 in one pose of cgal_Detmier and 0.41 in the other
/// from inputs 1e-14 apart).
class LocalFrame {
 public:
  /// The frame of the closed polygon of `pos[ids[i]]` (at least two distinct points).
  LocalFrame(const std::vector<Vec2>& pos, const std::vector<std::uint32_t>& ids);
  /// The frame of the closed polygon `cycle` itself.
  explicit LocalFrame(const std::vector<Vec2>& cycle);
  /// p in this frame, rounded to the grid.
  Vec2 to_local(Vec2 p) const;
  /// Back to the patch frame.
  Vec2 to_patch(Vec2 q) const;

 private:
  Vec2 origin_;
  Vec2 ux_;
  double scale_ = 1.0;
};

/// LocalFrame's grid: 2^-20 of the polygon's mean edge; far below any size a mesh cares about,
/// far above rounding.
constexpr double kLocalGrid = 1.0 / 1048576.0;

/// The scaled Jacobian of a corner between edges e1 (to the next node) and e0 (to the previous
/// one), l2 = |e1|^2 |e0|^2 (one square root, not two hypot calls; callers that have the
/// squared lengths pass their product); -1 at a zero-length edge.
inline double corner_of_edges(Vec2 e1, Vec2 e0, double l2) {
  return l2 > 0.0 ? cross(e1, e0) / std::sqrt(l2) : -1.0;
}

/// The scaled Jacobian of a quad's corner at `at`, between its edges to `next` and `prev`
/// (counter-clockwise > 0); -1 at a zero-length edge.
inline double corner_jacobian(Vec2 at, Vec2 next, Vec2 prev) {
  const Vec2 e1 = next - at;
  const Vec2 e0 = prev - at;
  return corner_of_edges(e1, e0, dot(e1, e1) * dot(e0, e0));
}

/// Smallest scaled Jacobian over the four corners of quad abcd (counter-clockwise > 0).
double min_scaled_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

/// quality.md's taper of the quad a b c d (counter-clockwise): the smallest corner triangle
/// over their mean (0 for a quad of no positive area).
double quad_taper(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

/// quad_taper and min_scaled_jacobian of one quad at once, from the same corner products
/// (the same values to the last bit: an edge reversed is the same vector negated, exactly).
struct TaperJacobian {
  double taper;
  double jacobian;
};
TaperJacobian quad_taper_jacobian(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

/// True when the open segments pq and rt cross or touch (a shared end point does not count;
/// collinear ones only when they overlap, within rounding).
bool segments_meet(Vec2 p, Vec2 q, Vec2 r, Vec2 t);

/// Whether x lies inside the polygon `poly` (the even-odd rule).
bool inside_polygon(Vec2 x, const std::vector<Vec2>& poly);

/// The templates' quads of the faces mesh_part's attempts fill, by the bytes of each face (its
/// cycle, sides and free nodes: all the templates read). After a face that no template fills,
/// the next attempt (drop_sliver_caps, then needle_tips) lays the rails again and meets most
/// faces unchanged: they take the quads the templates gave them before, the same to the bit.
/// Faces filled by a grid or as one quad are not held (they cost less than their key).
/// Shared by the threads that fill faces.
class FaceFillMemo {
 public:
  FaceFillMemo();
  ~FaceFillMemo();
  FaceFillMemo(const FaceFillMemo&) = delete;
  FaceFillMemo& operator=(const FaceFillMemo&) = delete;
  /// The templates' quads for `face`: remembered, else computed (and remembered).
  std::optional<FaceMesh> fill(const FaceInput& face);

 private:
  struct Held;
  std::unique_ptr<Held> held_;
};

/// Meshes one face: the first template that applies and gives quads whose scaled Jacobian is
/// above kAcceptJacobian wins; otherwise the best valid one. Throws InternalError (with `where`
/// in the message) when no template gives valid quads. With `memo`, the templates' quads are
/// looked for there first.
FaceMesh fill_face(const FaceInput& face,
                   const std::string& where,
                   bool needle_tips = false,
                   FaceFillMemo* memo = nullptr);

/// The quads of a cavity of a finished mesh (a polygon of any shape, read as one boundary
/// side): the quad and ring templates, corner grids, then split from either parity and cut
/// (the best acceptable on average, as fill_face), pairs when none is acceptable. No strips or
/// O-grid (a cavity has no rails), no fan split, and the templates' relaxation is skipped (the
/// caller relaxes the quads with those round the cavity). Nothing when no template gives
/// valid quads.
std::optional<FaceMesh> fill_cavity(const FaceInput& face);

/// The re-fill's passes (refill_cavities) on one face's quads, `cycle` its boundary nodes
/// (held), `m` its quads: the quads below `below` re-filled where that beats their relaxation.
/// Returns the count of cavities kept; m is renumbered (cycle nodes first, as before), its
/// min_jacobian not updated.
std::size_t refill_face(const std::vector<Vec2>& cycle, FaceMesh& m, double below, int iterations);

/// The needle-tip attempt's last resort (fill_face with needle_tips, where no template's
/// quads are above the face's bar): cut by chords as the cut template is, and where a piece
/// is a needle's tip, the corner cut off as a kite through one new node (FillKind::Kites).
/// Nothing when it gives no quads.
std::optional<FaceMesh> fill_kites(const FaceInput& face);

/// Faces of at least this many nodes are looked for among the faces filled before them
/// (face_motion): filling one takes 10-70 ms when it goes to the unstructured templates, and
/// parts repeat their features (a row of bosses, a symmetric cover: cover_bosses has four
/// copies each of a 46-node and a 56-node face).
constexpr std::size_t kSharedFaceNodes = 32;

/// Smaller faces of at least this many nodes are looked for too, but only as the same face
/// turned, scaled and shifted with its cycle from the same node (face_motion's turned_only):
/// the templates read a cycle from its first node, so such a copy filled on its own would get
/// the same quads moved (up to rounding), and sharing changes no choice. A shell of equal
/// facets (a cylinder's sides, a torus of triangles) has thousands of these, and the facets'
/// corners go to the unstructured templates (torus_48_16_tri: 2452 faces of 8 nodes, 0.96 s
/// of the quads stage's 1.66 s on one thread). Four nodes are the quad itself.
constexpr std::size_t kSharedSmallFaceNodes = 6;

/// Two faces are one moved onto the other when every node lands within this x the mean edge
/// of the second: far above rounding (1e-15), far below any difference of shape a template
/// reads.
constexpr double kCongruentTolerance = 1e-7;

/// How face `to` is face `from` moved: turned, perhaps mirrored, scaled and shifted (a
/// similarity fitted to all the nodes), its cycle node k being from's node `node[k]`.
struct FaceMotion {
  std::vector<std::uint32_t> node;
  bool mirrored = false;
  Vec2 from_centre, to_centre;
  double c = 1.0, s = 0.0;  ///< scale x cos and scale x sin of the turn, after the mirror
  Vec2 apply(Vec2 p) const;
};

/// The motion taking `from` to `to`, when there is one: the same node count, the same sides
/// (kinds, corners, joints) and free nodes in the same places, and every node within
/// kCongruentTolerance of its image. Cycles may start at any node; a mirror runs them the
/// other way. With `turned_only`, no mirror and each node k onto node k.
std::optional<FaceMotion> face_motion(const FaceInput& from,
                                      const FaceInput& to,
                                      bool turned_only = false);

/// The first edge's squared length over the squared perimeter: with face_shape_key, the
/// lookup key of a face whose copies must start where it does.
double leading_edge_key(const FaceInput& face);

/// A number two faces of the same shape (turned, mirrored, scaled, shifted) share but for
/// rounding: the nodes' mean squared distance from their centre over the squared perimeter
/// (times n). Faces whose keys differ by more than kCongruentTolerance in ratio are not one
/// moved onto the other.
double face_shape_key(const FaceInput& face);

/// `filled` (the quads of face `from`) moved onto face `to`: interior nodes by the motion,
/// cycle nodes renamed, quads turned back counter-clockwise after a mirror, and scored on `to`.
FaceMesh moved_fill(const FaceMesh& filled, const FaceInput& to, const FaceMotion& motion);

/// Templates are tried in order while their worst corner is below this scaled Jacobian.
constexpr double kAcceptJacobian = 0.3;

/// The order in which the node sweeps of a large patch visit its nodes, in groups that may run
/// at once (docs/mesher.md, "Sweeps in blocks"). The nodes are levelled breadth-first (two nodes
/// are neighbours when they share a quad), per component from the node that a search from its
/// lowest-numbered node reaches last (narrow levels, across its longest way), and the levels cut
/// into blocks of about kSweepBlockNodes movable nodes, at least kSweepBlockLevels levels
/// thick. A pass visits first the interior of every block, then the two levels at each cut (a
/// seam). A visit at a node reads the nodes at most two levels from it (its quads and the
/// quads across their edges) and writes its own: no block's interior reads another's, nor a
/// seam another seam. So running the groups of a phase at once, each in ascending node order,
/// gives what visiting them one after another gives, to the last bit, on any number of
/// threads. Empty (the sweeps visit every node in index order) when the patch has too few
/// nodes for two blocks.
struct SweepSchedule {
  std::vector<std::vector<std::uint32_t>> blocks;  ///< the blocks' interiors
  std::vector<std::vector<std::uint32_t>> seams;   ///< the levels at each cut
  bool empty() const { return blocks.empty(); }
};

/// Movable nodes per block of a SweepSchedule (below two blocks' worth, no schedule), and the
/// most blocks. A block's work in a pass is far more than handing it to a thread costs, and
/// many blocks balance the threads, since a pass's work gathers round the worst quads
/// (cover_bosses' smoothing, best of 10 on two threads: 0.031 s with 200, 0.035 s with 400 or
/// 120, 0.049 s on one thread).
constexpr std::size_t kSweepBlockNodes = 200;
constexpr std::size_t kSweepBlocks = 16;
/// A block is at least this many levels thick: a seam (two levels) and the levels its visits
/// read (two either side) never reach the next seam.
constexpr std::size_t kSweepBlockLevels = 6;

/// The schedule of the sweeps over `quads` (nodes 0 .. n - 1; `fixed` ones are not visited).
SweepSchedule sweep_schedule(std::size_t n, const std::vector<bool>& fixed,
                             const std::vector<std::array<std::uint32_t, 4>>& quads);

/// Puts nodes back where `before` has them until no quad is below min(the worst quad at
/// `before`, kKeepWorstAbove) (scaled Jacobians settled): the smoothing's sweeps each keep the
/// worst quad round a moving node above a floor (kSmoothFloor), not above the mesh's worst,
/// and star_5 at 2x finer ended at 0.38 from 0.57. Returns how many nodes it put back.
constexpr double kKeepWorstAbove = 0.6;
std::size_t keep_worst(std::vector<Vec2>& pos, const std::vector<Vec2>& before,
                       const std::vector<std::array<std::uint32_t, 4>>& quads);

/// Moves the interior nodes of a quad set towards the average of their neighbours, `iterations`
/// times, never letting any quad's scaled Jacobian fall below min(its value before the move,
/// kSmoothFloor). `fixed` says which nodes stay.
void smooth_nodes(std::vector<Vec2>& pos,
                  const std::vector<bool>& fixed,
                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                  int iterations,
                  const SweepSchedule* schedule = nullptr);

constexpr double kSmoothFloor = 0.2;
/// smooth_nodes refuses a move that brings the node closer to a neighbour than this x its
/// shortest edge when the sweeps began. The scaled Jacobian of a corner whose edge has
/// closed to rounding is rounding itself, of either sign: where the quads round a node were
/// inverted (a template's first guess), the Laplacian point could land on a neighbour and be
/// taken in one pose, refused in another (fuzz seed 60060's blob_046, translated: an edge of
/// a lattice fill's 0.2 closed to 1.8e-15, and the mesh had 3,493 quads, not 3,327).
constexpr double kSmoothEdgeFloor = 0.01;

/// Moves each interior node by Newton steps on the sum of the condition numbers of the quad
/// corners it belongs to, edges measured against their lengths before the sweeps (convex in
/// the node: only the angles are improved, sizes stay), at most `iterations` sweeps. A step is
/// halved until the sum falls and no quad round the node goes below min(its worst before,
/// kSmoothFloor), so no element is ever inverted. `fixed` says which nodes stay.
void optimize_nodes(std::vector<Vec2>& pos,
                    const std::vector<bool>& fixed,
                    const std::vector<std::array<std::uint32_t, 4>>& quads,
                    int iterations,
                    const SweepSchedule* schedule = nullptr);

/// The untangler keeps every edge at a node at least this x their mean length before it.
constexpr double kMinEdgeFraction = 0.2;

/// Moves each interior node whose worst quad is below `target` by a compass search that
/// raises the smallest scaled Jacobian of the quads around it (it untangles inverted quads).
/// A node may not come closer to a neighbour than min_edge_fraction x its mean edge before the
/// sweeps; one already closer takes a position that lengthens the edge, but none that takes
/// its worst quad below min(its value before, kSmoothFloor): no quad is ever inverted. When
/// `strict`, not below its value before either (no move lowers the worst quad of the mesh),
/// and no move stretches a quad round the node to a bad aspect ratio (quality.md) it had not.
void untangle_nodes(std::vector<Vec2>& pos,
                    const std::vector<bool>& fixed,
                    const std::vector<std::array<std::uint32_t, 4>>& quads,
                    int iterations,
                    double target = kAcceptJacobian,
                    double min_edge_fraction = kMinEdgeFraction,
                    bool strict = false,
                    const SweepSchedule* schedule = nullptr);

/// The relaxations' accept / reject tests (and the cavity re-fill's) compare scaled Jacobians
/// rounded to this: a quad's value that is exact by construction (a flat corner at a midpoint
/// placed on a diagonal: 0, or a right angle: 1) comes out as +-1e-16 or 1 - 1e-16 depending on
/// the pose's last bits, and `after >= before` then took a move in one pose and refused it in
/// another (a pairs face of a generated part relaxed to a worst corner of 0.154 in one pose and
/// 0.142 in the other). Far above rounding at any scale, far below any difference the sweeps
/// care about. A move must still keep a quad that had positive corners positive (`keeps_sign`):
/// the grain alone would let +2e-10 become -2e-10. A power of two (2^-32, session 38; it was
/// 1e-9): the values that come again and again on grid-like outlines, the corners between
/// small integer vectors, must lie far from the grain's rounding boundaries, and 1/sqrt(5) (a
/// grid edge against a 2:1 diagonal) lay 4.2e-14 from one of 1e-9's: the re-fill's candidates
/// changed order between poses (fuzz seed 42042's rect_024: 454 quads, 449 turned). On 2^-32
/// none of the corners between integer vectors up to 5 long lies within 1e-12 of a boundary.
constexpr double kJacobianGrain = 1.0 / 4294967296.0;

/// `jacobian` rounded to kJacobianGrain.
double settled(double jacobian);

/// The smallest norm() of `vs` (infinity for none), the very value of the min over every
/// norm() with hypot called only for the vectors whose squared length is within 1e-12 of the
/// least: one longer than that by its rounded square is longer by hypot too (whose error is
/// below one ulp, the square's a few). Squares near underflow or overflow take every hypot.
double shortest_norm(const std::vector<Vec2>& vs);

/// Interior angle of the counter-clockwise polygon `poly` at node i (radians, in (0, 2 pi)).
double interior_angle(const std::vector<Vec2>& poly, std::size_t i);

/// The corners of the counter-clockwise polygon `poly` (interior angle below 149.5 degrees),
/// in order; none when a node is reflex beyond 200.5 degrees. How corner_strip, fill_sided and
/// the re-fill's whole patches (refill_cavities) read a polygon.
std::optional<std::vector<std::uint32_t>> polygon_corners(const std::vector<Vec2>& poly);

/// A round polygon: every interior angle between kRoundMin and kRoundMax. The O-grid's faces
/// (fill_ogrid), and the loops whose rails drop_disk_rails drops when they nearly meet. Off
/// round values (120 and 200 until session 46): a regular hexagon's corners are 120 degrees
/// exactly, and an arc's 20-degree chords meet at 200, read either side by the pose's rounding.
constexpr double kRoundMin = 119.5 * kPi / 180.0;
constexpr double kRoundMax = 200.5 * kPi / 180.0;
/// Whether the counter-clockwise polygon `poly` is round.
bool is_round(const std::vector<Vec2>& poly);

/// Counter-clockwise angle from `from` to `to`, in [0, 2 pi).
double ccw_angle(Vec2 from, Vec2 to);

/// The final smoothing's untangler works on every node with a quad below this (the
/// templates' relaxation stops at kAcceptJacobian, the bound of their choice; 0.6 until
/// session 8, when 0.7 (past kFinalEscapeTarget) raised the worst corner of 47 of the 217
/// generated parts and lowered none (cover_bosses 0.622 -> 0.692, the tray at 10,668 quads
/// 0.606 -> 0.701) for +0.2 points of taper <= 0.8 on average; 0.8 raised more (cover_bosses
/// 0.758) but cost +0.6 points of taper and +0.2 of aspect >= 5); 0.75 since session 12:
/// worst corners between 0.70 and 0.75 (45-degree corners the smoothing left) rise, cgal_hole
/// 0.707 -> 0.750 (Gmsh 0.711), on the 217 generated parts 40 higher, 1 lower, mean worst
/// 0.721 -> 0.726, taper <= 0.8 +0.13 points, aspect >= 5 the same (0.72: 24 higher, none
/// lower, mean 0.723, +0.05 points) ...
constexpr double kFinalUntangleTarget = 0.75;
/// Up to this the final untangling may move a node with a too short edge at the cost of its
/// worst quad (the escape of untangle_nodes); from this to kFinalUntangleTarget only strictly
/// (no worst quad falls, no quad is stretched to aspect >= 5; with the escape all the way,
/// cover_bosses in adaptive mode fell 0.599 -> 0.532). A cavity (refill_cavities) is relaxed
/// towards this alone: the re-fill judges by the first stage (towards 0.7 there, other
/// re-fills were kept: cgal_hole 0.730 -> 0.700).
constexpr double kFinalEscapeTarget = 0.6;
/// ... and keeps a node's edges above this x their mean length before the sweeps.
constexpr double kFinalEdgeFraction = 0.3;

/// The sweeps of the final smoothing (docs/mesher.md, "Smoothing"): `iterations` Laplacian
/// sweeps, then as many of angle optimisation and of untangling towards `target`
/// (kFinalUntangleTarget, or kFinalEscapeTarget for a cavity). No quad is ever inverted;
/// `fixed` nodes stay. Every sweep of these (and of the four movers' own) visits the nodes in
/// index order, or in the order of `schedule` when one is given (SweepSchedule).
void final_sweeps(std::vector<Vec2>& pos,
                  const std::vector<bool>& fixed,
                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                  int iterations,
                  double target,
                  const SweepSchedule* schedule = nullptr);

/// Moves each interior node towards the mean of the positions that would make each quad round
/// it a parallelogram (the neighbours after and before it minus the opposite node), the whole
/// way, half or a quarter, the first that lowers the sum of (1 - taper)^2 over its quads by
/// kUntaperGain, lowers no quad's scaled Jacobian below the worst round the node before (nor
/// their sum by more than kUntaperJacobianSlack), and gives no quad a skew >= 30 degrees or an
/// aspect ratio >= 5 (quality.md) it did not have. Then as many sweeps again, in which a node
/// with a tapered quad where that move fails steps down the sum's gradient instead
/// (kUntaperDescent), and no move raises the count of tapered quads round the node.
/// At most `iterations` sweeps of each kind; `fixed` nodes stay. docs/mesher.md, "Taper".
void untaper_nodes(std::vector<Vec2>& pos,
                   const std::vector<bool>& fixed,
                   const std::vector<std::array<std::uint32_t, 4>>& quads,
                   int iterations,
                   const SweepSchedule* schedule = nullptr);

/// The angle at each fixed node (the outline's, when the fixed nodes are a patch's boundary):
/// the sum of its quads' corners there, 0 at the other nodes; with `counts`, how many quads
/// meet each. Only the quads with `alive` set, when given.
std::vector<double> pinned_angles(const std::vector<Vec2>& pos,
                                  const std::vector<bool>& fixed,
                                  const std::vector<std::array<std::uint32_t, 4>>& quads,
                                  const std::vector<bool>* alive = nullptr,
                                  std::vector<std::uint32_t>* counts = nullptr);

/// The best worst corner quads over these nodes can have at their fixed nodes, whatever the
/// others do: at a fixed node whose k quads' corners add up to the angle a there (the
/// outline's, when the fixed nodes are a patch's boundary), sin(a / k) at best; 1 when none is
/// below. Only the quads with `alive` set, when given.
double outline_bound(const std::vector<Vec2>& pos,
                     const std::vector<bool>& fixed,
                     const std::vector<std::array<std::uint32_t, 4>>& quads,
                     const std::vector<bool>* alive = nullptr);

/// Where a patch's outline forces a corner below this anyway (outline_bound: a ragged outline's
/// sharp corners, a corner under 48 degrees, a reflex corner of two quads), untaper_nodes
/// trades more of the other quads' shape for taper: a move may lower the worst quad round its
/// node to max(kLooseUntaperFloor, the outline's bound, the least of those quads' first worst
/// - kLooseUntaperDrop), and their sum by kLooseUntaperSlack. The mesh's worst corner stays
/// where the outline puts it. cgal_wiggly_03_cgal 12.2% -> 9.9% at taper <= 0.8,
/// cgal_complex_1 31.6% -> 26.8% (session 44).
constexpr double kLooseUntaperBelow = 0.75;
constexpr double kLooseUntaperFloor = 0.6;
constexpr double kLooseUntaperDrop = 0.1;
constexpr double kLooseUntaperSlack = 0.05;

/// The least fall of untaper_nodes' sum that moves a node: above rounding at any scale (the
/// sum is of ratios), so that a pose's last bits do not decide a move.
constexpr double kUntaperGain = 1e-9;

/// untaper_nodes takes no move that raises the largest area ratio between a quad round the
/// node and one across its edges above this, or above what it was when that was more:
/// untapering evens shapes, not sizes, and a graded mesh keeps its grading (quality.md's
/// neighbour ratio is of square roots of areas: 2.5 here is 1.58 there; without the bound
/// adaptive star_5 reached 2.11 there, with 1.5 half the taper gain was lost).
constexpr double kUntaperAreaRatio = 2.5;

/// untaper_nodes takes no move that lowers the sum of the scaled Jacobians of the quads round
/// the node by more than this: a parallelogram's corners are not right angles, and without the
/// bound the mean scaled Jacobian fell by 0.003-0.007 over the test sets; with it by at most
/// 0.0017, for most of the taper gain (the 20 parts 18.1% -> 16.0% instead of 15.5%; with no
/// fall allowed at all, 17.3%).
constexpr double kUntaperJacobianSlack = 0.01;

/// untaper_nodes leaves a node whose quads all have a taper of at least this (most nodes of a
/// structured region: they cost the sweeps' time and gain nothing that counts).
constexpr double kUntaperFrom = 0.95;

/// untaper_nodes' second sweeps, at a node with a tapered quad whose move towards the
/// parallelograms fails: steps down the gradient of its sum, of these fractions of the mean
/// length of the node's edges (halving from 0.4 to 0.4 / 256), the first that passes. The
/// gradient by central differences of kUntaperDifference times that length. On the 20 parts
/// taper <= 0.8 13.8% -> 12.6% with steps of 0.2 to 0.025, 11.9% from 0.4 to 0.0016 (the
/// bracket 14.1% -> 10.5%); on the 217 generated parts 9.3% -> 8.4%, then 7.9%
/// (docs/mesher.md, "Taper", "Descent").
constexpr std::array<double, 9> kUntaperDescent{0.4,    0.2,     0.1,      0.05,     0.025,
                                                0.0125, 0.00625, 0.003125, 0.0015625};
constexpr double kUntaperDifference = 1e-4;

/// A node whose Newton step promises less decrease of its objective than this stays.
constexpr double kOptimizeTolerance = 1e-4;
/// optimize_nodes: a step may not bring an edge at the node below this x the edge's length
/// when the sweeps began (the corners' condition numbers do not see size: on a fuzzed blob an
/// edge of 2e-5 at a micro-notch closed to 2.5e-7, two nodes closer than quality.md's rule 5
/// allows).
constexpr double kOptimizeEdgeFloor = 0.25;

/// A face's quads are accepted only when their smallest scaled Jacobian is above this (so
/// that the 3D check, which sees the nodes after the frame round trip, agrees).
constexpr double kMinValidJacobian = 1e-3;

/// A face that no template fills with quads above kMinValidJacobian still takes the best
/// template whose worst corner is above this, rather than the part being refused: a mesh with
/// a sliver is valid (quality.md: every corner's scaled Jacobian above 0), none is not. A gap
/// of 1/500 of an element between two holes (a 0.001 bridge) leaves 4.5e-4 at its ends.
/// Still five orders of magnitude above what the frame round trip changes.
constexpr double kLastResortJacobian = 1e-5;
/// Where the face's own outline has a corner whose sine is below kLastResortJacobian / kNeedleShare
/// (a needle's tip), the last resort is kNeedleShare x that sine (fill.cpp,
/// last_resort_jacobian), but never below kDegenerateJacobian: the frame round trip changes a
/// corner's sine by some 1e-12 on such parts, so this keeps three orders of margin. The fuzzed
/// tips' best templates came to 7.1e-4-0.45 of their sines (1e-2 left a blob of fuzz seed
/// 34034 refused, its best 8.8e-8 against a tip's 3.3e-5; 1e-3 one of seed 38038, a pile of
/// needles folded along one line, its best 2.4e-9 against a tip's 3.4e-6).
constexpr double kNeedleShare = 1e-4;
/// fill_face, before the needle-tip attempt: a face with a corner whose sine s is below
/// kLastResortJacobian / kSharpCornerShare takes its best template above kSharpCornerShare x s
/// (no quad does better than s at that corner) instead of kLastResortJacobian.
constexpr double kSharpCornerShare = 0.5;
constexpr double kDegenerateJacobian = 1e-9;

}  // namespace laytracks::mesher_detail
