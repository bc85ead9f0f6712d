// Private: how B-Rep edges and vertices appear on each patch's boundary, and the registry of
// G-CUT-VERTs, which identifies a point landing within a tolerance of an existing one.
#pragma once

#include <functional>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "laytracks/brep/part.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"

namespace laytracks::cutgraph_detail {

/// A B-Rep edge as segment `seg` of loop `loop` of patch `patch`; `forward` when the segment runs
/// from the edge's vertex a to its vertex b.
struct SegmentRef {
  PatchId patch;
  std::uint32_t loop = 0;
  std::uint32_t seg = 0;
  bool forward = true;
};

/// A B-Rep vertex as corner `index` of loop `loop` of patch `patch`.
struct CornerRef {
  PatchId patch;
  std::uint32_t loop = 0;
  std::uint32_t index = 0;
};

class BoundaryIndex {
 public:
  explicit BoundaryIndex(const Part& part);

  const std::vector<SegmentRef>& segments_of(EdgeId e) const { return edge_refs_[e.index()]; }
  const std::vector<CornerRef>& corners_of(VertexId v) const { return vertex_refs_[v.index()]; }
  /// The B-Rep edge under segment `seg` of a loop, and the edge parameter of s along it.
  EdgeId edge_at(PatchId p, std::uint32_t loop, std::uint32_t seg) const;
  double edge_param(PatchId p, std::uint32_t loop, std::uint32_t seg, double s) const;

 private:
  const Part& part_;
  std::vector<std::vector<SegmentRef>> edge_refs_;
  std::vector<std::vector<CornerRef>> vertex_refs_;
};

/// A place on a patch's loop, as a map key: patch, loop, and the loop parameter u (wrapped
/// into [0, segment count)) on a grid of 1e-9, so that a break point found from a CUT-VERT and
/// from a CUT-SEG end is the same key.
using LoopKey = std::tuple<std::uint32_t, std::uint32_t, long long>;
LoopKey loop_key(const Part& part, PatchId p, std::uint32_t loop, double u);

/// Turn at a corner of a patch: +1 convex, -1 reflex, 0 straight or smooth.
int corner_turn(const Part& part, PatchId p, std::uint32_t loop, std::uint32_t index);

/// The G-CUT-VERTs of a part, found again by position.
class GCutRegistry {
 public:
  /// `tolerance`: two points closer than this (part units) are the same G-CUT-VERT.
  GCutRegistry(const Part& part, double tolerance);

  /// The G-CUT-VERT at parameter t of edge e (snapped to the edge's vertices within the
  /// tolerance), creating it if needed. `gap` receives the distance to an existing one that was
  /// reused (0 for a new one); `created` whether it is new.
  GCutId find_or_add(EdgeId e, double t, std::vector<GCutVert>& gverts, double* gap, bool* created);
  GCutId find_or_add_vertex(VertexId v, std::vector<GCutVert>& gverts, bool* created);
  /// The existing G-CUT-VERT of edge e (its inside points, or its ends where they are ones)
  /// nearest to parameter t; invalid when the edge has none. `gap`: the distance to it.
  GCutId nearest(EdgeId e, double t, double* gap) const;
  /// Distances to t within this x the edge's length of each other tie in nearest and
  /// nearest_if: the point nearer the edge's first vertex wins.
  static constexpr double kNearestTieRel = 1e-9;
  /// As nearest, among the G-CUT-VERTs `accept` takes.
  GCutId nearest_if(EdgeId e, double t, const std::function<bool(GCutId)>& accept,
                    double* gap) const;

 private:
  const Part& part_;
  double tol_;
  std::vector<std::vector<std::pair<double, GCutId>>> on_edge_;  // sorted by t, per edge
  std::map<std::uint32_t, GCutId> at_vertex_;
  std::vector<EdgeId> first_edge_;  ///< per vertex: the first edge that uses it
};

}  // namespace laytracks::cutgraph_detail
