// The validator of a quad mesh against its part (the six rules of ../shared/spec/quality.md,
// "A whole mesh") and the quality summary of a mesh (its "Summary figures").
#pragma once

#include <array>
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

/// Named tolerances of the mesh validator, each relative to Part::size unless said otherwise.
struct MeshTolerances {
  /// Rule 5: two nodes closer than this x size are too close (quality.md).
  static constexpr double kMinNodeDistance = 1e-9;
  /// Rule 5: a node within this x size of the inside of a mesh edge (and farther than that
  /// from both its ends) hangs on it.
  static constexpr double kHanging = 1e-9;
  /// Rules 5 and 6: a node within this x size of a B-Rep vertex is at that vertex; one within
  /// this x size of a B-Rep edge lies on that edge.
  static constexpr double kOnBrep = 1e-9;
  /// Rule 3: a node lies on its patch's plane when it is within this x size of it, plus the
  /// distance of the patch's own farthest B-Rep vertex from that plane (brep accepts vertices
  /// up to Tolerances::kPlanarity x the patch diagonal off the fitted plane).
  static constexpr double kOnPlane = 1e-9;
  /// Rule 4: the element areas of a patch add up to its area within this x the patch area.
  static constexpr double kArea = 1e-9;
};

struct MeshCheckOptions {
  /// At most this many failure sentences are kept per rule; all are counted.
  std::size_t max_messages_per_rule = 20;
};

/// One broken rule at one place.
struct MeshFailure {
  int rule = 0;         ///< 1..6, the rule of quality.md
  std::string message;  ///< "rule N: ..." naming the element or node, its patch and position
};

/// What check_mesh found. Counts cover the whole mesh even when messages were capped.
struct MeshCheck {
  std::vector<MeshFailure> failures;    ///< in rule order, then in the order found
  std::array<std::size_t, 7> counts{};  ///< counts[r]: failures of rule r (r = 1..6)
  std::size_t elements = 0;
  std::size_t quads = 0;
  std::size_t triangles = 0;       ///< elements with nodes[3] == kNoNode (rule 1)
  std::size_t malformed = 0;       ///< a node id out of range or kNoNode early, a bad patch id
  std::size_t inverted = 0;        ///< rule 2: inverted or degenerate quads and triangles
  std::size_t flipped = 0;         ///< rule 3: elements turning clockwise about their patch normal
  std::size_t unused_nodes = 0;    ///< nodes no element uses: counted, not a failure
  double min_node_distance = 0.0;  ///< rule 5's kMinNodeDistance x size, in the part's units

  bool valid() const;
  /// The kept failure sentences, one per line.
  std::string report() const;
};

/// Checks `mesh` against `part` by the six rules of quality.md and returns every failure.
/// Never throws on a bad mesh (node ids out of range, non-finite coordinates and bad patch ids
/// are failures too); the mesh must fit in memory a few times over. Each failure is a sentence
/// "rule N: ..." naming the element or node index, its patch (Part::patch_label) and its 3D
/// position. How each rule is decided:
/// 1. every element has four valid node ids (a triangle, nodes[3] == kNoNode, is counted and
///    reported; any other bad id, or a patch id out of range, makes the element malformed).
///    Malformed elements take no further part; triangles do (area, conformity, orientation).
/// 2. no element is inverted or degenerate: the scaled Jacobian, with the corners projected on
///    the patch plane, is > 0 at every corner. A quad whose four corners all turn the wrong
///    way is a valid quad facing the wrong way, and is reported by rule 3 instead.
/// 3. each node of an element is on its patch's plane (MeshTolerances::kOnPlane) with finite
///    coordinates; the element's centroid, projected in the patch frame, is inside the patch
///    polygon (crossing test: a centroid exactly on the boundary may go either way); the
///    element turns counter-clockwise about the patch normal.
/// 4. per patch, the signed areas of its elements in the patch frame add up, within
///    MeshTolerances::kArea relative, to the area of the patch with its arcs replaced by the
///    mesh's own chords (the spec's "polygons that the mesher used"): Patch::area, plus the
///    circular segments between the discretisation's chords and the circle, minus those
///    between the mesh's boundary edges on arcs and the circle. Any mesher's chords will do.
/// 5. mesh edges are grouped by their unordered node pair. A group used by one element of a
///    patch p is on p's boundary and must lie on a B-Rep edge E of p (both ends on E or at its
///    vertices); then the group must hold exactly one element of each patch of E and no
///    other. A group with two elements of p is inside p; more than two is a failure. No node
///    lies inside a mesh edge (hanging node, MeshTolerances::kHanging); no two nodes are
///    closer than MeshTolerances::kMinNodeDistance x size (spatial hashing, not O(n^2)).
/// 6. every node at an end of a boundary group of patch p is on a B-Rep edge or vertex of p
///    (on an arc: on its circle, within kOnBrep x size), and every vertex of every patch loop
///    has a mesh node within kOnBrep x size. An arc is one B-Rep edge here: the points that
///    discretise it are not vertices, and need not be nodes.
/// Runs in O(n) expected time: about half a second for a million quads (test_mesher times it).
MeshCheck check_mesh(const Part& part, const QuadMesh& mesh, const MeshCheckOptions& options = {});

/// A histogram with fixed bins: bin i holds the values in [lower_bounds[i], lower_bounds[i+1]),
/// the first bin also everything below lower_bounds[0] and the last everything from
/// lower_bounds.back() up (infinities included).
struct Histogram {
  std::vector<double> lower_bounds;
  std::vector<std::size_t> counts;  ///< same size as lower_bounds
};

/// Figures of one measure over the measured quads.
struct MeasureSummary {
  std::string name;      ///< the JSON key, e.g. "skew_deg"
  std::string bad_when;  ///< the 'bad' threshold as text, e.g. ">= 30"
  double mean = 0.0;
  double worst = 0.0;        ///< largest or smallest value, whichever is worse for the measure
  double p5 = 0.0;           ///< 5th percentile (linear between closest ranks)
  double p95 = 0.0;          ///< 95th percentile
  double bad_percent = 0.0;  ///< % of the measured quads beyond the 'bad' threshold
  Histogram histogram;
};

/// quality.md's summary figures of a mesh.
struct QualitySummary {
  std::size_t elements = 0;
  std::size_t nodes = 0;
  std::size_t quads = 0;
  std::size_t triangles = 0;
  /// Inverted or degenerate quads (QuadQuality::inverted), triangles (quality.md counts them
  /// as such) and malformed elements (a node or patch id out of range, a non-finite node).
  std::size_t invalid_elements = 0;
  /// Quads whose measures are taken: all quads but the malformed ones (inverted ones too).
  std::size_t measured = 0;
  /// skew_deg, aspect_ratio, taper, warp_deg, min_angle_deg, max_angle_deg, scaled_jacobian,
  /// edge_ratio, in this order.
  std::array<MeasureSummary, 8> measures;
  /// % of the measured quads with an interior angle < 45 or > 135 degrees.
  double bad_angle_percent = 0.0;
  /// Element size: the square root of the quad's area (measured quads).
  double min_size = 0.0;
  double max_size = 0.0;
  /// The mean size of the finest tenth of the quads over that of the coarsest tenth (1 for a
  /// uniform mesh; small when the mesh grades).
  double fine_coarse_ratio = 1.0;
  /// Size grading: over every pair of measured quads sharing an edge, the larger size over
  /// the smaller; the worst pair and the 95th percentile (1 with no pair).
  double worst_neighbour_ratio = 1.0;
  double p95_neighbour_ratio = 1.0;
};

/// Measures every quad of `mesh` with measure_quad and its patch's normal, and gathers the
/// summary figures. Statistics are over the measured quads; with none, they are 0. An
/// infinite value (a degenerate quad's ratio) makes the mean and worst infinite. Histogram
/// bins (lower bounds):
///   skew_deg          0, 5, ..., 85
///   aspect_ratio      1, 1.1, 1.25, 1.5, 2, 3, 5, 10
///   taper             0, 0.1, ..., 0.9
///   warp_deg          0, 1, 2, 5, 10, 20, 45, 90
///   min_angle_deg     0, 5, ..., 175, 180
///   max_angle_deg     0, 5, ..., 175, 180
///   scaled_jacobian   -1, -0.9, ..., 0.9
///   edge_ratio        1, 1.1, 1.25, 1.5, 2, 3, 5, 10
/// Deterministic: the same mesh gives the same figures.
QualitySummary summarize(const Part& part, const QuadMesh& mesh);

/// Writes the summary as one JSON object, keys in a fixed order: elements, nodes, quads,
/// triangles, invalid_elements, measured, bad_angle_percent, "size" ({min, max,
/// worst_neighbour_ratio, p95_neighbour_ratio}), then "measures": an object with
/// one entry per measure in the order above, each {bad_when, mean, worst, p5, p95,
/// bad_percent} and, when `histograms` is true, "histogram": {lower_bounds, counts}.
/// Non-finite numbers are written as null. Numbers are the shortest text that reads back
/// to the same double, so the output is byte-identical for identical input.
void write_quality_json(std::ostream& out, const QualitySummary& summary, bool histograms);

/// The same summary followed by the check of the same mesh, for `laytracks quality --json`:
/// "valid" (true or false), "failure_counts" ({"1": n1, ..., "6": n6}, every failure of each
/// rule counted) and "failures" (an array of {rule, message} in MeshCheck::failures' order:
/// rule order, then as found; the sentences kept by MeshCheckOptions::max_messages_per_rule).
/// Byte-identical for identical input, like the summary.
void write_quality_json(std::ostream& out, const QualitySummary& summary, const MeshCheck& check,
                        bool histograms);

}  // namespace laytracks
