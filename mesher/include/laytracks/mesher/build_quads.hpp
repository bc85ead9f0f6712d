// Quads from the rails: nodes on rails and boundary pieces, parity made even, every face of a
// patch cut by its rails filled with quads, shells conformal through shared boundary nodes
// (paper, section 4.3; the rules are in docs/mesher.md).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "laytracks/brep/error.hpp"
#include "laytracks/brep/part.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks {

namespace mesher_detail {
class FaceFillMemo;  // fill.hpp
}

/// A piece of a B-Rep edge between two boundary nodes that are ends of rails or vertices, as
/// build_quads numbers them: its unit (a straight edge, or a whole arc) and its place along it.
/// Meaningful only to build_quads with the same part, cut graph and options.
struct PieceRef {
  std::uint32_t unit = 0;
  std::uint32_t piece = 0;
};

struct QuadOptions {
  /// Element size h: the track width the rails were laid with (uniform mode).
  double size = 0.0;
  /// Adaptive mode: the width law the rails were laid with; boundary pieces are split at its
  /// local width and rail counts follow Eq. (2). Must outlive the call.
  const TrackWidthLaw* adaptive = nullptr;
  /// The second attempt after a face no template fills (mesh_part): the rails that cut off a
  /// needle go too (docs/mesher.md, "Sliver caps").
  bool drop_sliver_caps = false;
  /// The third attempt (mesh_part): a face whose outline has a needle's tip takes its best
  /// template down to a share of that tip's sine (mesher_detail::kNeedleShare).
  bool needle_tips = false;
  /// Boundary pieces given two more edges each (a piece may be listed more than once), after
  /// the parity is made even (two more keep it): mesh_part's answer to an UnfilledFace in the
  /// third attempt (docs/mesher.md, "Split boundary pieces").
  std::vector<PieceRef> split_pieces;
  /// Patches whose hub rails go (mesh_part's second build of a part with QuadResult::hubs;
  /// docs/mesher.md, "Hubs"): the rails that meet at a hub, as a disk's do (drop_disk_rails).
  std::vector<std::uint32_t> drop_hubs;
  /// The faces' fills of earlier attempts (mesh_part keeps one across its attempts); may be
  /// null. Must outlive the call.
  mesher_detail::FaceFillMemo* face_memo = nullptr;
};

/// build_quads' error when no template fills a face in the third attempt
/// (QuadOptions::needle_tips): which face (its place in the message), its node count and its
/// boundary pieces, the one of its longest mesh edge first (ties by unit, then piece), that
/// mesh_part may split (QuadOptions::split_pieces).
class UnfilledFace : public InternalError {
 public:
  UnfilledFace(const std::string& what,
               std::string face_where,
               std::size_t face_nodes,
               std::vector<PieceRef> by_length)
      : InternalError(what),
        where(std::move(face_where)),
        nodes(face_nodes),
        pieces(std::move(by_length)) {}
  std::string where;
  std::size_t nodes;
  std::vector<PieceRef> pieces;
};

/// refill_cavities tries quads below this in uniform mode, below the other in adaptive mode:
/// there, with re-fills between 0.5 and 0.7 the smoothing that follows ended lower on three
/// simple parts (open_box 0.758 -> 0.695, t_junction 0.747 -> 0.692, plate_with_hole 0.729 ->
/// 0.712) where uniform mode lost nothing (docs/mesher.md, "Cavity re-fill").
constexpr double kRefillBelowUniform = 0.7;
constexpr double kRefillBelowAdaptive = 0.5;

/// Names of the face templates, in mesher_detail::FillKind order (docs/mesher.md).
constexpr std::array<const char*, 18> kTemplateNames = {
    "grid",  "diamond", "quad",  "ring",   "split", "rows",    "cut",   "pairs", "strip",
    "ogrid", "arms",    "taper", "reflex", "three", "lattice", "match", "sided", "kites"};

/// What the quad stage did, for reports and tests.
struct QuadStats {
  std::size_t faces = 0;  ///< faces of the patches cut by their rails
  /// Faces per template, in mesher_detail::FillKind order (kTemplateNames).
  std::array<std::size_t, kTemplateNames.size()> by_template{};
  /// faces that took the quads of an earlier face of the same shape, moved (kSharedFaceNodes)
  std::size_t shared_faces = 0;
  std::size_t narrow_fans = 0;     ///< rails dropped: under 10 degrees from another at a node
  std::size_t crowded_feet = 0;    ///< rails dropped: feet too close on a round hole
  std::size_t unfolded_darts = 0;  ///< MA nodes moved beyond their feet's chord at a tip
  std::size_t twin_rails = 0;      ///< rails dropped: a second rail between the same two feet
  std::size_t graded_rails = 0;    ///< rails from a round hole with graded steps (graded_rail)
  std::size_t dangling_rails = 0;  ///< rail segments left out: their MA end met no other rail
  std::size_t outward_rails = 0;   ///< rails that left their boundary node outside the patch
  std::size_t slit_rails = 0;      ///< rails with one face on both sides: dropped
  std::size_t sliver_cap_rails = 0;  ///< rails that cut off a needle: dropped
  /// rails crossing another edge of their patch's graph: dropped, in the third attempt
  std::size_t crossing_rails = 0;
  /// faces kept with a corner as thin as a needle's tip of their outline (QuadOptions::needle_tips)
  std::size_t needle_tip_faces = 0;
  /// boundary pieces given two more edges after a face no template filled
  /// (QuadOptions::split_pieces)
  std::size_t split_pieces = 0;
  std::size_t fan_clusters = 0;    ///< MA nodes merged into a deeper one (merge_fan_clusters)
  /// rail feet moved onto a smooth B-Rep vertex within kTinyEndPiece x h of them
  std::size_t smooth_vertex_feet = 0;
  std::size_t parity_boundary = 0;  ///< boundary pieces given one more edge for parity
  std::size_t parity_rails = 0;     ///< rail segments given one more edge for parity
  /// odd strips whose run with fewer edges took their extra edge (docs/mesher.md, "Parity")
  std::size_t parity_strips = 0;
  std::size_t edge_flips = 0;       ///< quad pairs re-split by flip_edges
  std::size_t thin_rows = 0;        ///< chains merged by merge_thin_rows
  std::size_t corner_kites = 0;     ///< kites folded by fold_corner_kites
  std::size_t corner_reliefs = 0;   ///< reliefs folded by fold_corner_reliefs
  std::size_t thin_bends = 0;       ///< cells meshed again by square_thin_bends
  std::size_t slid_nodes = 0;       ///< boundary nodes moved by slide_boundary_nodes
  std::size_t late_rounds = 0;      ///< rounds of the late slides and flips kept (mesh_part)
  std::size_t cavity_refills = 0;   ///< cavities round bad quads filled again (refill_cavities)
  std::size_t regrids = 0;          ///< cavities round irregular nodes gridded again (same)
  std::size_t loop_bridges = 0;     ///< loops no rail reached, joined by two bridge rails
  std::size_t disk_patches = 0;     ///< patches whose rails all met at one point: one face
  std::size_t hub_patches = 0;      ///< patches whose hub's rails went (QuadOptions::drop_hubs)
};

struct QuadResult {
  QuadMesh mesh;
  QuadStats stats;
  /// Patches (ids) with a hub whose rails stayed (docs/mesher.md, "Hubs"); uniform mode only.
  std::vector<std::uint32_t> hubs;
};

/// Builds the all-quad mesh of the part from its cut graph (whose MA-CUT-VERTs carry the axis
/// points the quads need). Every node on a B-Rep edge is shared by all the patches of that
/// edge. Throws InternalError when a face cannot be meshed or the parity cannot be made even;
/// the mesh is not checked here (check_mesh is).
QuadResult build_quads(const Part& part, const CutGraph& graph, const QuadOptions& options);

/// Edge flips: two quads of one patch sharing an edge make a hexagon, which has three
/// diagonals that split it into two quads; where the pair's worse quad is below 0.5 and
/// another diagonal gives a worse quad better by 0.05, the pair is re-split along it (a flat
/// corner at a boundary node that one quad meets gets an edge into the patch this way). Nodes,
/// element count and the boundary are unchanged; no quad is made worse than the pair's worst.
/// Edges in map order, each quad once a pass, up to four passes. Returns the flips made;
/// `flipped`, when given, receives the elements re-split.
std::size_t flip_edges(const Part& part,
                       QuadMesh& mesh,
                       std::vector<std::uint32_t>* flipped = nullptr);

/// Thin rows merged (docs/mesher.md, "Thin rows"), run after the flips: where a chain of edges
/// runs along the middle of a strip from boundary to boundary (or round a ring) through
/// interior nodes of four quads each, its edges at least twice as long as the rungs across
/// it, the chain's nodes go (its end nodes too: on a straight boundary of one patch, no B-Rep
/// vertex) and each pair of quads across it becomes one quad, when no merged quad is worse in
/// its worst corner than its pair (to rounding), each is squarer or at most 3 in aspect, and
/// the chain's worst aspect falls. Returns the chains merged.
std::size_t merge_thin_rows(const Part& part, QuadMesh& mesh);

/// Corner kites folded (docs/mesher.md, "Corner kites"), run after the thin rows: where one
/// quad meets a B-Rep vertex (or two sharing an edge from it), and its (their) nodes beside the
/// vertex lie on straight boundary of one patch (no B-Rep vertex, two quads each, no farther
/// from the vertex than 1.5 x the next boundary edge), those two nodes go and the quads beyond
/// them take the vertex instead (the two quads at it become one), when the worst corner of the
/// quads made beats the worst of those replaced by 0.02. Returns the folds made.
std::size_t fold_corner_kites(const Part& part, QuadMesh& mesh);

/// Corner reliefs folded (docs/mesher.md, "Corner reliefs"), run after the kites: where a
/// B-Rep vertex p is in two quads sharing its edge to an inner node b of four quads, and the
/// two quads' nodes across from p (y1, y2) lie on straight boundary of one patch (as the
/// kites' side nodes), the four quads at b become two, (a, p1, p, d) and (p, p3, c, d): y1, y2
/// and b go. Kept when fewer of the quads are beyond Table III's thresholds and the worst
/// corner is no lower. Returns the folds made.
std::size_t fold_corner_reliefs(const Part& part, QuadMesh& mesh);

/// Bends of thin strips squared (docs/mesher.md, "Bends of thin strips"), run after the
/// reliefs, uniform mode (`size` the element size h): the mesh is cut into cells at edges from
/// boundary to boundary, and a cell with a reflex B-Rep vertex is meshed again as pieces
/// between cuts from that vertex straight across the strip (at most 1.5 h long): rows of
/// quads between two cuts, the face templates elsewhere. Kept when fewer quads are beyond
/// Table III's thresholds and the worst corner is no lower (or as many, and the worst corner
/// higher by 0.1), the old quads and the new each
/// relaxed inside the cell by `sweeps` of the final smoothing's sweeps. Returns the cells
/// meshed again.
std::size_t square_thin_bends(const Part& part, QuadMesh& mesh, double size, int sweeps);

/// Boundary nodes slid apart (docs/mesher.md, "Sliding boundary nodes"), run after the
/// smoothing (mesh_part then smooths round the nodes moved): a node of the mesh's boundary or
/// of a seam (no B-Rep vertex; on a seam, the same two seam neighbours in every patch at it,
/// its quads scored each in its own patch's plane) whose shorter boundary edge is below 0.2 x its
/// longer one on an arc (0.05 x on a straight edge), or, when `tapered`, a node (on a line or an
/// arc) with a quad of taper 0.8 or less, moves along its boundary (the line, or the circle through
/// it and its two boundary neighbours) to the one of 15 even positions between them where the worst
/// min(scaled Jacobian, taper) of its quads is best, when that beats where it is by 0.05 and
/// leaves their worst scaled Jacobian no lower (or, for a short edge, at least 0.6). Nodes and
/// quads are not added or removed. Returns how many nodes moved; `moved`, when given,
/// receives them; `for_taper`, when given, gets how many of them moved for a taper alone.
std::size_t slide_boundary_nodes(const Part& part,
                                 QuadMesh& mesh,
                                 std::vector<std::uint32_t>* moved = nullptr,
                                 bool tapered = false,
                                 std::size_t* for_taper = nullptr);

/// Cavity re-fill (docs/mesher.md, "Cavity re-fill"), run after the flips and before the
/// smoothing: round the worst quads below `below` of each patch (at most 32 + 1/50 of its
/// quads a pass, two passes, the second near what the first changed), the quads across a
/// quad's edges, else those at its nodes, else those at their nodes, are taken out as one
/// polygon, filled again by the face templates (fill_cavity) and relaxed with the quads round
/// them (`iterations` sweeps, at most 4); the new quads are kept when their worst beats the
/// worst of the old ones relaxed the same way by 0.02. Before those passes, a patch of at most
/// 4,000 quads without a hole whose outline has three to five corners is tried whole, as three
/// or five grids round one centre or one grid (docs/mesher.md, "Whole patches"), kept when
/// fewer quads are beyond a threshold of taper, skew or aspect and the worst corner is no
/// lower; counted as a regrid. Then the regrid pass (docs/mesher.md,
/// "Regrid"): round each irregular interior node (not in four quads), rings of quads whose
/// boundary turns as a rectangle's, a triangle's or a pentagon's are filled again by a grid
/// with no irregular node inside, or one, kept when that leaves fewer tapered quads (taper <=
/// 0.8) and a worst corner no lower (or at least `below`); `regrids`, when given, receives how
/// many. Each cavity is posed in its own gridded frame (LocalFrame), so every pose of a part
/// makes the same choices. Boundary and seam nodes stay; the cavity's boundary, hence
/// conformity, is unchanged; nodes that no element uses any more are removed (node and
/// element order otherwise kept). Returns the re-fills kept (the regrids not counted).
std::size_t refill_cavities(const Part& part,
                            QuadMesh& mesh,
                            int iterations,
                            double below = kRefillBelowUniform,
                            std::size_t* regrids = nullptr);

/// refill_cavities answers a cavity whose problem (in the cavity's own frame, to the bit) it
/// has met before from memory, in every patch of the part (docs/mesher.md, "Cavity re-fill":
/// the congruent facets of a faceted shell): the same answer it would compute. On unless
/// turned off here, which the tests do to check that the meshes are the same without it.
void set_cavity_memo(bool on);
/// How many cavities the memo has answered so far in this process (on several threads the
/// count depends on their timing, the meshes do not).
std::size_t cavity_memo_hits();

/// mesh_part's attempts after a face that no template fills take the quads the templates
/// gave a face in an earlier attempt when they meet it again unchanged, to the bit
/// (docs/mesher.md, "Retried faces"). On unless turned off here, which the tests do to check
/// that the meshes are the same without it.
void set_face_fill_memo(bool on);
/// How many faces took remembered quads so far in this process.
std::size_t face_fill_memo_hits();

/// build_quads shares the quads of small faces (6-31 nodes) that are an earlier face turned,
/// scaled and shifted, its cycle from the same node (docs/mesher.md, "Repeated faces"): the
/// quads their own fills would give, up to rounding. On unless turned off here, which the tests
/// do to check that the meshes are the same without it.
void set_small_face_sharing(bool on);

/// Smooths the interior nodes of every patch in its frame (docs/mesher.md, "Smoothing"):
/// `iterations` Laplacian sweeps, as many of angle optimisation, then untangling sweeps over
/// nodes of quads below 0.6, then strictly below 0.7. Nodes on B-Rep edges and seams never
/// move; a move is kept only when no quad around the node falls below min(its scaled Jacobian
/// before, 0.2), so no element is ever inverted. With `movable`, only the nodes it marks move,
/// among the elements that use one (a local pass after a few late flips).
void smooth_mesh(const Part& part,
                 QuadMesh& mesh,
                 int iterations,
                 const std::vector<bool>* movable = nullptr);

}  // namespace laytracks
