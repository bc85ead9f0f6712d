#include "mesh_builder.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace laytracks::test {
namespace {

/// The point k/n of the way from a to b, computed so that swapping the ends (and k for n - k)
/// gives the same double: neighbouring patches traverse a shared edge in opposite directions.
Vec3 along(Vec3 a, Vec3 b, int k, int n) {
  if (k == 0) return a;
  if (k == n) return b;
  const double wa = static_cast<double>(n - k);
  const double wb = static_cast<double>(k);
  const double dn = static_cast<double>(n);
  return {(a.x * wa + b.x * wb) / dn, (a.y * wa + b.y * wb) / dn, (a.z * wa + b.z * wb) / dn};
}

}  // namespace

GridMesh grid_mesh(const Part& part,
                   double h,
                   const std::map<std::size_t, std::pair<int, int>>& divisions) {
  GridMesh out;
  std::map<std::array<double, 3>, std::uint32_t> boundary_nodes;
  auto add_node = [&](Vec3 x) {
    out.mesh.nodes.push_back(x);
    return static_cast<std::uint32_t>(out.mesh.nodes.size() - 1);
  };
  for (std::size_t p = 0; p < part.patches.size(); ++p) {
    const Patch& patch = part.patches[p];
    if (patch.loops.size() != 1 || patch.loops[0].vertices.size() != 4) {
      throw std::invalid_argument("grid_mesh: " + part.patch_label(PatchId(p)) +
                                  " is not a single quadrilateral loop");
    }
    std::array<Vec3, 4> c{};
    for (std::size_t k = 0; k < 4; ++k)
      c[k] = part.vertices[patch.loops[0].vertices[k].index()].position;
    PatchGrid g;
    g.nu = std::max(1, static_cast<int>(std::lround(distance(c[0], c[1]) / h)));
    g.nv = std::max(1, static_cast<int>(std::lround(distance(c[0], c[3]) / h)));
    if (const auto it = divisions.find(p); it != divisions.end()) {
      g.nu = it->second.first;
      g.nv = it->second.second;
    }
    g.nodes.resize(static_cast<std::size_t>((g.nu + 1) * (g.nv + 1)));
    for (int i = 0; i <= g.nu; ++i) {
      for (int j = 0; j <= g.nv; ++j) {
        const bool boundary = i == 0 || j == 0 || i == g.nu || j == g.nv;
        Vec3 x;
        if (j == 0) {
          x = along(c[0], c[1], i, g.nu);
        } else if (j == g.nv) {
          x = along(c[3], c[2], i, g.nu);
        } else if (i == 0) {
          x = along(c[0], c[3], j, g.nv);
        } else if (i == g.nu) {
          x = along(c[1], c[2], j, g.nv);
        } else {
          const double s = static_cast<double>(i) / static_cast<double>(g.nu);
          const double t = static_cast<double>(j) / static_cast<double>(g.nv);
          x = (1.0 - t) * ((1.0 - s) * c[0] + s * c[1]) + t * ((1.0 - s) * c[3] + s * c[2]);
        }
        std::uint32_t id = 0;
        if (boundary) {
          const auto [it, fresh] = boundary_nodes.emplace(std::array<double, 3>{x.x, x.y, x.z}, 0);
          if (fresh) it->second = add_node(x);
          id = it->second;
        } else {
          id = add_node(x);
        }
        g.nodes[static_cast<std::size_t>(i * (g.nv + 1) + j)] = id;
      }
    }
    g.first_element = out.mesh.elements.size();
    for (int i = 0; i < g.nu; ++i) {
      for (int j = 0; j < g.nv; ++j) {
        MeshElement e;
        e.nodes = {g.node(i, j), g.node(i + 1, j), g.node(i + 1, j + 1), g.node(i, j + 1)};
        e.patch = PatchId(p);
        e.shell = static_cast<std::uint32_t>(patch.shell);
        out.mesh.elements.push_back(e);
      }
    }
    out.grids.push_back(std::move(g));
  }
  return out;
}

}  // namespace laytracks::test
