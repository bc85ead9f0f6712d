// The polygons of a mesh as OpenMesh's half-edge PolyMesh can hold them, for the .obj and .off
// writers in mesh_output.cpp. OpenMesh decides which faces fit; the text is written by
// mesh_output.cpp because OpenMesh 9.0's OBJ and OFF writers (Debian 12's) narrow every point to
// float even for a double mesh (0.1 comes out as 0.10000000149011612), which would lose the
// precision the other formats keep and tie the bytes to the OpenMesh version.

// OpenMesh's PropertyT<Vec3d>::push_back copies a default-constructed VectorT, whose components
// its constructor leaves unset; GCC 12 reports that, inlined into this file, as
// -Wmaybe-uninitialized although the code is OpenMesh's. The values are overwritten before use.
// The pragma comes before the includes: GCC applies it where the inlined code is written.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <array>
#include <cstdint>
#include <mutex>
#include <vector>

#include "laytracks/brep/error.hpp"
#include "laytracks/mesher/quad_mesh.hpp"

namespace laytracks::detail {

namespace {

using OmMesh = OpenMesh::PolyMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

/// Silences OpenMesh's error stream while faces are added (a refused face is expected and
/// handled), restoring its state afterwards. omerr() is one stream for the whole process and
/// its on/off flag is a plain bool, so concurrent writers (laytracks batch) share one silence:
/// the first to come turns the stream off, the last to leave restores it, under a lock, and
/// no writer flips the flag while another is adding faces.
class QuietOpenMesh {
 public:
  QuietOpenMesh() {
    const std::lock_guard<std::mutex> lock(state().mutex);
    if (state().users++ == 0) {
      state().was_enabled = omerr().is_enabled();
      omerr().disable();
    }
  }
  ~QuietOpenMesh() {
    const std::lock_guard<std::mutex> lock(state().mutex);
    if (--state().users == 0 && state().was_enabled) omerr().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  struct State {
    std::mutex mutex;
    std::size_t users = 0;
    bool was_enabled = false;
  };
  static State& state() {
    static State s;
    return s;
  }
};

}  // namespace

/// Declared in mesh_output.cpp, its only caller. points = the mesh's nodes, then copies;
/// faces[i] = element i's nodes in its order (nodes[3] = kNoNode for a triangle), or copies of
/// them when OpenMesh's PolyMesh cannot take the face as it is (an edge of three or more faces,
/// two faces running the same way along an edge, a non-manifold vertex).
void halfedge_polygons(const QuadMesh& mesh,
                       std::vector<Vec3>& points,
                       std::vector<std::array<std::uint32_t, 4>>& faces) {
  OmMesh om;
  points = mesh.nodes;
  faces.clear();
  std::vector<OmMesh::VertexHandle> vertex;
  vertex.reserve(mesh.nodes.size());
  for (const Vec3& x : mesh.nodes) vertex.push_back(om.add_vertex(OmMesh::Point(x.x, x.y, x.z)));
  const QuietOpenMesh quiet;
  for (const MeshElement& e : mesh.elements) {
    const std::size_t n = e.is_quad() ? 4 : 3;
    std::array<std::uint32_t, 4> ids = e.nodes;
    std::vector<OmMesh::VertexHandle> face;
    for (std::size_t k = 0; k < n; ++k) face.push_back(vertex[ids[k]]);
    if (!om.add_face(face).is_valid()) {
      for (std::size_t k = 0; k < n; ++k) {
        face[k] = om.add_vertex(om.point(face[k]));
        ids[k] = static_cast<std::uint32_t>(points.size());
        points.push_back(mesh.nodes[e.nodes[k]]);
      }
      if (!om.add_face(face).is_valid()) {
        throw Error("cannot write the mesh: OpenMesh refused a face even with nodes of its own");
      }
    }
    faces.push_back(ids);
  }
}

}  // namespace laytracks::detail
