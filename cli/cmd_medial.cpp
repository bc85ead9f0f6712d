// laytracks medial PART.json [--json OUT.json] [--svg OUT.svg] [--chord-tol T] [--quiet]
#include <chrono>
#include <cstdio>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/medial_output.hpp"
#include "laytracks/medial/part_medial.hpp"

namespace laytracks::cli {

const char* const kMedialHelp =
    "usage: laytracks medial PART.json [--json OUT.json] [--svg OUT.svg] [--chord-tol T] "
    "[--quiet]\n"
    "\n"
    "Computes the medial axis of every patch of the part and prints, per patch, its vertices,\n"
    "edges, branch points and largest radius.\n"
    "\n"
    "  --json OUT.json  write "
    "{\"patches\":[{\"name\",\"vertices\":[{\"xyz\",\"radius\",\"degree\"}],\n"
    "                   \"edges\":[[i,j]]}]}, coordinates in the part's 3D frame\n"
    "  --svg OUT.svg    draw each patch in its plane: boundary, axis coloured by radius,\n"
    "                   branch points in red\n"
    "  --chord-tol T    sagitta bound for arcs, in the part's units (default 1e-3 x the part's\n"
    "                   size: twice the largest distance of a vertex from their centroid)\n"
    "  --quiet          print nothing but errors\n";

int run_medial(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json", "--svg", "--chord-tol"}, {"--quiet"});
  if (args.positional().size() != 1) throw UsageError("medial needs exactly one PART.json");
  const bool quiet = args.flag("--quiet");
  const auto t0 = std::chrono::steady_clock::now();

  BuildOptions build_options;
  build_options.chord_tol = args.positive_number("--chord-tol");
  const Part part = build_part(read_brep_json(args.positional()[0]), build_options);
  for (const auto& w : part.warnings) std::cerr << "laytracks: warning: " << w << '\n';

  const auto progress = [&](std::size_t done, std::size_t total) {
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!quiet && total > 1 && s > 1.0)
      std::cerr << "medial: patch " << done << "/" << total << "\r";
  };
  const std::vector<MedialAxis> axes = compute_medial_axes(part, progress);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (const auto path = args.value("--json")) {
    write_file_atomically(*path, [&](std::ostream& o) { write_medial_json(o, part, axes); });
  }
  if (const auto path = args.value("--svg")) {
    write_file_atomically(*path, [&](std::ostream& o) { write_medial_svg(o, part, axes); });
  }
  if (!quiet) {
    std::printf("%-24s %9s %9s %9s %12s\n", "patch", "vertices", "edges", "branches", "max radius");
    std::size_t branches = 0;
    for (std::size_t p = 0; p < axes.size(); ++p) {
      double rmax = 0.0;
      for (const auto& v : axes[p].vertices()) rmax = std::max(rmax, v.radius);
      branches += axes[p].branch_points().size();
      std::printf("%-24s %9zu %9zu %9zu %12.6g\n", part.patches[p].name.c_str(),
                  axes[p].vertices().size(), axes[p].edges().size(), axes[p].branch_points().size(),
                  rmax);
    }
    std::printf("%zu patches, %zu shells, %zu branch points, %.3f s\n", part.patches.size(),
                part.shell_count, branches, seconds);
  }
  return kOk;
}

}  // namespace laytracks::cli
