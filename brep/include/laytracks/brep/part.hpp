// The validated part: vertices, edges shared by k >= 1 patches, loops, planar patches with their
// 2D frames, and shells. Built only by build_part(), which enforces every rule of
// ../shared/spec/brep-json.md; every Part in memory is therefore valid.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "laytracks/brep/geometry.hpp"
#include "laytracks/brep/polygon.hpp"
#include "laytracks/brep/raw_part.hpp"

namespace laytracks {

struct BrepVertex {
  Vec3 position;
  /// Index in the input file's "vertices", or -1 for a point made by discretising an arc.
  std::int64_t source_index = -1;
  /// True for points made by arc discretisation: the boundary is tangent-continuous there.
  bool from_arc = false;
};

/// A straight B-Rep edge between two vertices (arcs are already replaced by chains of these).
struct BrepEdge {
  VertexId a;  ///< a < b: the canonical orientation
  VertexId b;
  /// The patches that use this edge, ascending, each once: 1 = free edge, 2 = fold or seam,
  /// >= 3 = non-manifold junction.
  std::vector<PatchId> patches;
  /// Index into the input's "arcs" when this edge is a piece of a discretised arc, else -1.
  std::int64_t arc = -1;
};

/// A circular arc of the file, as the B-Rep keeps it: its exact circle, and the points that
/// discretise it (BrepVertex::from_arc), which the medial axis and the rails use. The mesh puts
/// its own nodes on the circle (docs/mesher.md).
struct PartArc {
  VertexId from;  ///< the file's vertices at its ends
  VertexId to;
  Vec3 center;
  double radius = 0.0;
  Vec3 e1;            ///< unit, from the centre towards `from`
  Vec3 e2;            ///< unit, axis x e1: the arc turns from e1 towards e2
  double span = 0.0;  ///< angle from `from` to `to`, in (0, 2 pi)
  std::vector<VertexId> points;  ///< interior points, from `from` to `to`, uniform in angle
  /// The point at fraction u of the angle from `from` (u in [0, 1]).
  Vec3 at(double u) const;
};

/// The largest angle a chord of a circle of this radius may span with its sagitta at most
/// chord_tol (and at most 90 degrees).
double max_chord_angle(double radius, double chord_tol);

/// An orthonormal frame on a patch's plane: n is the unit normal of the outer loop as the file
/// gives it (right-hand rule), and (u, v, n) is right-handed, so the outer loop runs
/// counter-clockwise in (u, v).
struct Frame {
  Vec3 origin;
  Vec3 u;
  Vec3 v;
  Vec3 n;

  /// Orthogonal projection onto the plane, in plane coordinates.
  Vec2 to_2d(Vec3 p) const {
    const Vec3 d = p - origin;
    return {dot(d, u), dot(d, v)};
  }
  /// The point of the plane with plane coordinates q.
  Vec3 to_3d(Vec2 q) const { return origin + q.x * u + q.y * v; }
};

struct Loop {
  /// Vertices in order, the loop closed implicitly. The outer loop keeps the file's order;
  /// a hole is reversed when needed so that it runs clockwise in the patch frame.
  std::vector<VertexId> vertices;
  /// edges[i] joins vertices[i] and vertices[i + 1] (cyclically).
  std::vector<EdgeId> edges;
  /// smooth[i]: the boundary is tangent-continuous at vertices[i] (see Polygon2::smooth).
  std::vector<bool> smooth;
  bool reversed = false;  ///< true when the order is the reverse of the file's
};

struct Patch {
  std::string name;
  Frame frame;
  std::vector<Loop> loops;  ///< loop 0 is the outer boundary, the rest are holes
  Polygon2 polygon;         ///< the loops in frame coordinates (outer CCW, holes CW)
  double area = 0.0;        ///< of the polygon, in the part's units squared
  std::size_t shell = 0;    ///< connected component of the dual graph
};

struct MeshParams {
  std::optional<double> size;  ///< element size from the file, if any
  MeshMode mode = MeshMode::Uniform;
  std::optional<double> dtheta_deg;
};

struct Part {
  std::string source;  ///< file name, for messages
  std::string units = "mm";
  std::vector<BrepVertex> vertices;  ///< the file's vertices first, in order; then arc points
  std::vector<BrepEdge> edges;
  std::vector<Patch> patches;
  MeshParams mesh;
  Box3 bbox;  ///< of the file's vertices used by patches (arcs may bulge out of it)
  /// The length every relative tolerance refers to: twice the largest distance of a used vertex
  /// from their centroid. Invariant under rotation and mirroring, unlike the bbox diagonal.
  double size = 0.0;
  double chord_tol = 0;  ///< sagitta bound used to discretise arcs
  std::vector<PartArc> arcs;  ///< the file's arcs, by index (BrepEdge::arc)
  std::size_t shell_count = 0;
  std::vector<std::string> warnings;  ///< things worth telling the user that are not errors

  std::string patch_label(PatchId p) const;  ///< `patch "wall" (index 1)`
};

}  // namespace laytracks
