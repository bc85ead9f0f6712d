// laytracks draw PART.json --stage medial|corridors|tracks|mesh -o OUT.svg [meshing options]
//                [--view unfolded|oblique] [--measure jacobian|taper|skew|aspect|edge-ratio]
#include <algorithm>
#include <iostream>
#include <memory>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/cutgraph_output.hpp"
#include "laytracks/io/medial_output.hpp"
#include "laytracks/io/mesh_svg.hpp"
#include "laytracks/medial/part_medial.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "meshing.hpp"

namespace laytracks::cli {

const char* const kDrawHelp =
    "usage: laytracks draw PART.json --stage medial|corridors|tracks|mesh -o OUT.svg\n"
    "                      [--size W | --adaptive ...] [--smooth N] [--view unfolded|oblique]\n"
    "                      [--measure M] [--chord-tol T]\n"
    "\n"
    "Draws a stage as SVG: one panel per patch in its own plane (unfolded), or, for corridors,\n"
    "tracks and mesh, the whole part in an oblique view (the default for parts of several\n"
    "patches):\n"
    "  medial     the boundary and the medial axis coloured by radius, branch points in red\n"
    "  corridors  the source rails (red) and the corridors between them, shaded\n"
    "  tracks     the track rails (blue) laid at width W (or adaptively) and the tracks,\n"
    "             shaded\n"
    "  mesh       the quads of `laytracks mesh` (checked by quality.md first), outlined and\n"
    "             filled by their scaled Jacobian (colour bar below: dark blue 0, yellow 1,\n"
    "             the 'bad' threshold 0.2 and the smallest value marked), patch boundaries bold.\n"
    "             A part the mesher refuses gets its message and exit status 3, as with\n"
    "             mesh, and nothing is written.\n"
    "\n"
    "  --view V         unfolded or oblique\n"
    "  --measure M      mesh: colour the quads by another measure of quality.md instead:\n"
    "                   taper (0 to 1, bad <= 0.8), skew (90 to 0 degrees, bad >= 30),\n"
    "                   aspect (10 to 1, bad >= 5) or edge-ratio (10 to 1, bad >= 5); the\n"
    "                   default, jacobian, is the scaled Jacobian (0 to 1, bad <= 0.2).\n"
    "                   Dark blue is the bad end, yellow the ideal; the bar marks the threshold\n"
    "                   and the element farthest from ideal\n"
    "The meshing options, as in `laytracks mesh` (tracks and mesh):\n"
    LAYTRACKS_MESHING_OPTIONS_HELP;

int run_draw(const std::vector<std::string>& argv) {
  const Args args = meshing_args(argv, {"--stage", "-o", "--view", "--measure"}, {});
  if (args.positional().size() != 1) throw UsageError("draw needs exactly one PART.json");
  const auto out = args.value("-o");
  if (!out) throw UsageError("draw needs -o OUT.svg");
  const std::string stage = args.value("--stage").value_or("");
  if (stage != "medial" && stage != "corridors" && stage != "tracks" && stage != "mesh") {
    throw UsageError("draw needs --stage medial, corridors, tracks or mesh");
  }
  if (stage != "mesh" && args.value("--smooth")) {
    throw UsageError("--smooth is for --stage mesh only");
  }
  const std::string measure = args.value("--measure").value_or("jacobian");
  if (stage != "mesh" && args.value("--measure")) {
    throw UsageError("--measure is for --stage mesh only");
  }
  const std::vector<std::string>& measures = colour_measures();
  if (std::find(measures.begin(), measures.end(), measure) == measures.end()) {
    throw UsageError("--measure is jacobian, taper, skew, aspect or edge-ratio");
  }
  const std::optional<std::string> view_arg = args.value("--view");
  if (view_arg && *view_arg != "oblique" && *view_arg != "unfolded") {
    throw UsageError("--view is unfolded or oblique");
  }
  check_can_write(*out);
  const MeshingOptions options = meshing_options(args);
  const Part part = read_part(args.positional()[0], options.build);
  const std::string view = view_arg.value_or(part.patches.size() > 1 ? "oblique" : "unfolded");
  if (stage == "mesh") {
    const MeshPartResult r = mesh_part(part, options.mesh);
    const MeshColouring colouring = colour_by(measure, part, r.mesh);
    write_file_atomically(*out, [&](std::ostream& o) {
      write_mesh_svg(o, part, r.mesh, colouring,
                     view == "oblique" ? MeshView::kOblique : MeshView::kUnfolded);
    });
    return kOk;
  }
  std::vector<MedialAxis> axes = compute_medial_axes(part);
  if (stage == "medial") {
    write_file_atomically(*out, [&](std::ostream& o) { write_medial_svg(o, part, axes); });
    return kOk;
  }
  std::unique_ptr<TrackWidthLaw> law;
  // The corridors as the tracks and the mesh at this size see them (the round holes chosen),
  // with only the source rails laid.
  CutGraphOptions cg = cut_graph_options(part, axes, options.mesh, law);
  if (stage == "corridors") cg = CutGraphOptions{};
  const CutGraph graph = build_cut_graph(part, axes, cg);
  write_file_atomically(*out, [&](std::ostream& o) {
    if (view == "oblique") {
      write_rails_oblique_svg(o, part, axes, graph, stage);
    } else {
      write_rails_svg(o, part, axes, graph, stage);
    }
  });
  return kOk;
}

}  // namespace laytracks::cli
