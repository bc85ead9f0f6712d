#include "meshing.hpp"

#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/mesher/quality.hpp"

namespace laytracks::cli {

Args meshing_args(const std::vector<std::string>& argv,
                  std::set<std::string> with_value,
                  std::set<std::string> flags) {
  with_value.insert({"--size", "--smooth", "--chord-tol", "--dtheta", "--min-size", "--max-size"});
  flags.insert({"--adaptive", "--uniform"});
  return Args(argv, with_value, flags);
}

MeshingOptions meshing_options(const Args& args) {
  MeshingOptions o;
  o.build.chord_tol = args.positive_number("--chord-tol");
  o.mesh.size = args.positive_number("--size");
  if (const auto n = args.count("--smooth")) o.mesh.smooth = static_cast<int>(*n);
  if (args.flag("--adaptive") && args.flag("--uniform"))
    throw UsageError("--adaptive and --uniform: choose one mode");
  if (args.flag("--adaptive")) o.mesh.adaptive = true;
  // --size is uniform mode's parameter: it overrides a part's mesh.mode "adaptive".
  if (args.flag("--uniform") || (o.mesh.size && !args.flag("--adaptive"))) o.mesh.adaptive = false;
  o.mesh.dtheta_deg = args.positive_number("--dtheta");
  o.mesh.min_size = args.positive_number("--min-size");
  o.mesh.max_size = args.positive_number("--max-size");
  if (o.mesh.dtheta_deg && !(*o.mesh.dtheta_deg <= 90.0))
    throw UsageError("--dtheta is an angle in degrees in (0, 90], got " + *args.value("--dtheta"));
  if (o.mesh.min_size && o.mesh.max_size && *o.mesh.min_size > *o.mesh.max_size)
    throw UsageError("--min-size " + *args.value("--min-size") + " is larger than --max-size " +
                     *args.value("--max-size"));
  if (args.flag("--uniform") && (o.mesh.dtheta_deg || o.mesh.min_size || o.mesh.max_size))
    throw UsageError("--dtheta, --min-size and --max-size are for adaptive mode, not --uniform");
  if (o.mesh.adaptive.value_or(false) && o.mesh.size)
    throw UsageError("--size is the element size of uniform mode; with --adaptive, bound the "
                     "sizes with --min-size and --max-size");
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
