// Private: the quads of one patch in its own frame, with local node ids, for the passes that
// work on a finished mesh patch by patch (smoothing, cavity re-fill).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks::mesher_detail {

/// The nodes used by elements of several patches (seams).
std::vector<bool> shared_nodes(const QuadMesh& mesh);

/// The nodes that no pass may move or remove: nodes used by elements of several patches, and
/// nodes on a mesh edge that only one element uses (a free edge, or a patch's boundary).
std::vector<bool> pinned_nodes(const QuadMesh& mesh);

/// The elements' edges, each under its lower node: node a's list (from start[a] to
/// start[a + 1] of `uses`) holds (b, element) for every edge (a, b), b > a, of the elements
/// `counted` takes, sorted. A counting sort: every node's list is short, where one sort of all
/// the mesh's edges was a tenth of a large shell's late smoothing.
struct EdgesByNode {
  std::vector<std::uint32_t> start;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> uses;
};
EdgesByNode edges_by_lower_node(const QuadMesh& mesh,
                                const std::function<bool(std::size_t)>& counted);

/// The nodes at B-Rep vertices (within the check's kOnBrep x the part's size of one).
std::vector<bool> vertex_nodes(const Part& part, const QuadMesh& mesh);

/// Three boundary nodes lie on one line (a straight stretch of boundary, no arc or corner)
/// when the sine of the angle between their two edges is at most this: the passes that drop
/// or slide boundary nodes (thin rows, corner kites, slides) keep the boundary as it was.
constexpr double kStraightBoundarySine = 1e-9;

/// The quads at each node of the mesh, in element order.
std::vector<std::vector<std::uint32_t>> quads_at_mesh_nodes(const QuadMesh& mesh);

/// The elements of patch p, in mesh order, over local node ids.
struct PatchQuads {
  std::vector<std::uint32_t> global;  ///< local node id -> mesh node id
  std::vector<Vec2> pos;              ///< local node id -> position in the patch frame
  std::vector<bool> fixed;            ///< local node id -> pinned (pinned_nodes)
  std::vector<std::array<std::uint32_t, 4>> quads;  ///< local ids, counter-clockwise
  std::vector<std::uint32_t> elements;              ///< quad -> mesh element index
};

/// The element indices of each patch, in mesh order (one pass over the mesh, instead of one
/// per patch).
std::vector<std::vector<std::uint32_t>> elements_by_patch(const Part& part, const QuadMesh& mesh);

/// The patches that have elements in `by_patch` (elements_by_patch, or a subset of it), in
/// patch order: the work of the passes that run patch by patch.
std::vector<std::size_t> busy_patches(const std::vector<std::vector<std::uint32_t>>& by_patch);

/// Patch p's quads, given its `elements` (elements_by_patch) and `pinned` (pinned_nodes).
/// Nodes are numbered in order of first use.
PatchQuads patch_quads(const Part& part,
                       const QuadMesh& mesh,
                       std::size_t p,
                       const std::vector<std::uint32_t>& elements,
                       const std::vector<bool>& pinned);

/// The mesh element of quad q over pq's local ids, on patch p, in `shell`.
MeshElement element_of(const PatchQuads& pq, const std::array<std::uint32_t, 4>& q,
                       std::size_t p, std::uint32_t shell);

/// The mesh without the elements `drop` marks, with `added` after the rest (orders kept), and
/// without the nodes that no element uses any more (the others renumbered in their order):
/// how the passes that take quads out and put others in (re-fill, thin rows) finish.
void replace_elements(QuadMesh& mesh, const std::vector<bool>& drop,
                      const std::vector<MeshElement>& added);

/// The threads a part's passes use: the environment's LAYTRACKS_THREADS (a whole number from
/// 1) when set, else set_mesher_threads' count when set, else as many as the machine has. The
/// output does not depend on it.
std::size_t worker_threads();

/// Runs fn(i) for every i in [0, n), on worker_threads() threads (at most n; on the
/// calling thread when that is one). For work on one index that reads and writes nothing the
/// work on another index writes (a patch's nodes, a face's quads): the result is the same as
/// in order. After every thread has ended, the exception of the lowest index that threw is
/// rethrown, as running them in order on one thread would: an index after one that threw is
/// not started, and every index before it runs, so which one is deterministic. Called from
/// within the work of
/// another parallel_for, it runs on the calling thread (no more threads than cores).
void parallel_for(std::size_t n, const std::function<void(std::size_t)>& fn);

}  // namespace laytracks::mesher_detail
