#include "meshing.hpp"

#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/mesher/quality.hpp"

namespace laytracks::cli {

MeshingOptions meshing_options(const Args& args) {
  MeshingOptions o;
  o.build.chord_tol = args.positive_number("--chord-tol");
  o.mesh.size = args.positive_number("--size");
  if (const auto n = args.count("--smooth")) o.mesh.smooth = static_cast<int>(*n);
  return o;
}

Part read_part(const std::string& path, const BuildOptions& options) {
  return build_part(read_brep_json(path), options);
}

std::vector<double> element_scaled_jacobians(const Part& part, const QuadMesh& mesh) {
  std::vector<double> jac;
  jac.reserve(mesh.elements.size());
  for (const MeshElement& el : mesh.elements) {
    const Vec3 n = part.patches[el.patch.index()].frame.n;
    jac.push_back(measure_quad({mesh.nodes[el.nodes[0]], mesh.nodes[el.nodes[1]],
                                mesh.nodes[el.nodes[2]], mesh.nodes[el.nodes[3]]},
                               n)
                      .scaled_jacobian);
  }
  return jac;
}

void write_part_mesh(const std::string& path, const Part& part, const QuadMesh& mesh) {
  const std::vector<double> jac = element_scaled_jacobians(part, mesh);
  write_mesh(path, part, mesh, &jac);
}

}  // namespace laytracks::cli
