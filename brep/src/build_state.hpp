// Private to brep: the state shared by the steps of build_part(), and the steps themselves.
// Each step checks one group of rules of ../shared/spec/brep-json.md, throws InputError on the
// first violation, and fills its part of BuildState::part.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "laytracks/brep/build.hpp"
#include "laytracks/brep/part.hpp"
#include "laytracks/brep/raw_part.hpp"

namespace laytracks::detail {

/// The most segments one arc may be cut into.
constexpr std::size_t kMaxArcSegments = 100000;

/// One input arc after validation: its circle and the points that discretise it.
struct ArcInfo {
  VertexId from;  ///< as in the file
  VertexId to;
  Vec3 center;
  Vec3 axis;  ///< unit normal; from -> via -> to runs counter-clockwise about it
  double radius = 0.0;
  double span = 0.0;               ///< angle from `from` to `to` through via, in (0, 2 pi)
  std::vector<VertexId> points;    ///< interior points, in order from `from` to `to`
  std::vector<std::size_t> users;  ///< patches that use the edge, ascending, each once
};

/// A loop with its arcs replaced by their points. Segment i joins vertices[i] and vertices[i+1]
/// (cyclically); seg_arc[i] is the input arc it discretises (-1: a straight file edge) and
/// seg_forward[i] says whether it runs from the arc's `from` towards its `to`.
struct Chain {
  std::vector<VertexId> vertices;
  std::vector<std::int64_t> seg_arc;
  std::vector<char> seg_forward;
};

struct BuildState {
  const RawPart& raw;
  Part part;
  std::vector<char> used;                  ///< per file vertex: used by some patch
  std::vector<ArcInfo> arcs;               ///< one per raw arc, same order
  std::vector<std::vector<Chain>> chains;  ///< [patch][loop], final order once planes are fit
  std::vector<std::vector<std::vector<Vec2>>> loops2d;  ///< [patch][loop] in the patch frame
  std::vector<std::vector<std::size_t>> patch_arcs;     ///< arcs each patch uses, ascending
  /// For part vertex file_vertex_count() + i, an arc point: (arc index, point number from 1).
  std::vector<std::pair<std::size_t, std::size_t>> arc_point_of;

  explicit BuildState(const RawPart& r) : raw(r) {}
  std::size_t file_vertex_count() const { return raw.vertices.size(); }
};

// ---- the steps, in the order build_part() runs them ----

/// Copies vertices, units and mesh parameters and names the patches ("patch<i>" by default).
void init_part(BuildState& s);
/// Rule 1: indices in range and non-negative, finite and sane numbers, mesh parameters > 0.
void check_input(const BuildState& s, const BuildOptions& options);
/// Rule 10 (names): two patches with the same name, given or default, are refused.
void check_patch_names(const BuildState& s);
/// Rule 2: bbox and size of the used vertices; warns about unused vertices.
void measure_part(BuildState& s);
/// Rule 3: loop lengths, repeated vertices, loops touching, vertices too close together.
void check_loops(BuildState& s);
/// Rule 4: validates the arcs, discretises each once, and builds every loop's Chain.
void build_arcs(BuildState& s, const BuildOptions& options);
/// Rules 5-6: planarity, degenerate patches, the frame of every patch, 2D loops.
void fit_planes(BuildState& s);
/// Rule 8's message for patch p's loops projected into its frame (set), when two of their
/// segments cross, touch or fold back; empty when none do. For fit_planes: an outer loop of
/// zero net area is most often a bowtie, and a crossing says more than "zero area".
std::string loop_conflict(const BuildState& s, std::size_t p);
/// Rule 8, exact, in each patch's frame: no zero-area loop, every loop simple, loops neither
/// touching nor crossing, every hole inside the outer loop and outside the other holes.
void check_polygons(const BuildState& s);
/// Rules 6-7 after check_polygons(): holes turned clockwise, smooth flags; fills Patch::loops
/// (vertices, smooth, reversed), Patch::polygon and Patch::area.
void shape_polygons(BuildState& s);
/// Rule 9: one BrepEdge per unordered vertex pair; fills Loop::edges.
void build_edges(BuildState& s);
/// Rule 10: no vertex lies inside an edge without splitting it.
void check_vertices_on_edges(const BuildState& s);
/// Patches meet only along shared edges: no edge of one passes through, lies inside or ends
/// inside another (exact segment tests in the patch's frame, kOnEdge and kPlanarity margins).
void check_patch_contacts(const BuildState& s);
/// Rules 11-12: the file's dual_graph agrees with the shared edges; shells.
void check_dual_graph_and_shells(BuildState& s);

/// Rule 3 (and after arcs, for arc points): the first pair of the given vertices closer than
/// Tolerances::kMinVertexDistance x size is refused.
void check_vertex_spacing(const BuildState& s, const std::vector<VertexId>& ids);

}  // namespace laytracks::detail
