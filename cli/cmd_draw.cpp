// laytracks draw PART.json --stage medial|corridors|tracks -o OUT.svg [--size W] [--chord-tol T]
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/cutgraph_output.hpp"
#include "laytracks/io/medial_output.hpp"
#include "laytracks/medial/part_medial.hpp"
#include "laytracks/mesher/mesh_part.hpp"

namespace laytracks::cli {

const char* const kDrawHelp =
    "usage: laytracks draw PART.json --stage medial|corridors|tracks -o OUT.svg [--size W]\n"
    "                      [--view unfolded|oblique] [--chord-tol T]\n"
    "\n"
    "Draws a stage as SVG: one panel per patch in its own plane (unfolded), or, for corridors\n"
    "and tracks, the whole part in an oblique view (the default for parts of several patches):\n"
    "  medial     the boundary and the medial axis coloured by radius, branch points in red\n"
    "  corridors  the source rails (red) and the corridors between them, shaded\n"
    "  tracks     the track rails (blue) laid at width W and the tracks, shaded\n"
    "\n"
    "  --size W       track width (default: the part's mesh.size, else 1/40 of the part's size,\n"
    "                 twice the largest distance of a vertex from their centroid)\n"
    "  --view V       unfolded or oblique\n"
    "  --chord-tol T  sagitta bound for arcs\n";

int run_draw(const std::vector<std::string>& argv) {
  const Args args(argv, {"--stage", "-o", "--size", "--chord-tol", "--view"}, {});
  if (args.positional().size() != 1) throw UsageError("draw needs exactly one PART.json");
  const auto out = args.value("-o");
  if (!out) throw UsageError("draw needs -o OUT.svg");
  const std::string stage = args.value("--stage").value_or("");
  if (stage != "medial" && stage != "corridors" && stage != "tracks") {
    throw UsageError("draw needs --stage medial, corridors or tracks");
  }
  BuildOptions build_options;
  build_options.chord_tol = args.positive_number("--chord-tol");
  const Part part = build_part(read_brep_json(args.positional()[0]), build_options);
  const std::vector<MedialAxis> axes = compute_medial_axes(part);
  if (stage == "medial") {
    write_file_atomically(*out, [&](std::ostream& o) { write_medial_svg(o, part, axes); });
    return kOk;
  }
  CutGraphOptions options;
  if (stage == "tracks") {
    options.track_width = args.positive_number("--size").value_or(
        part.mesh.size.value_or(default_element_size(part)));
  }
  const std::string view =
      args.value("--view").value_or(part.patches.size() > 1 ? "oblique" : "unfolded");
  if (view != "oblique" && view != "unfolded") throw UsageError("--view is unfolded or oblique");
  const CutGraph graph = build_cut_graph(part, axes, options);
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
