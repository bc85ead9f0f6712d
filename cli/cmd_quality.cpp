// laytracks quality PART.json MESH.msh [--json OUT.json] [--histograms] [--quiet]
#include <cstdio>
#include <iostream>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/io/msh_reader.hpp"
#include "laytracks/mesher/check.hpp"

namespace laytracks::cli {

const char* const kQualityHelp =
    "usage: laytracks quality PART.json MESH.msh [--json OUT.json] [--histograms]\n"
    "                         [--chord-tol T] [--quiet]\n"
    "\n"
    "Rates a Gmsh MSH 4.1 mesh of the part, ours or another mesher's, by\n"
    "../shared/spec/quality.md: the six validity rules (all quads, none inverted, on its patch\n"
    "and oriented with it, areas, conformity, boundary following) and the quality figures\n"
    "(mean, worst, p5/p95 and % beyond the thresholds of every measure). Surface entity t of\n"
    "the mesh is patch t-1 of the part. Exit status 5 when the mesh is not valid.\n"
    "\n"
    "  --json OUT.json  the summary figures, then \"valid\", \"failure_counts\" (per rule) and\n"
    "                   \"failures\": [{rule, message}], at most 20 sentences per rule\n"
    "  --histograms     add the per-measure histograms to the JSON\n"
    "  --chord-tol T    sagitta bound for arcs: use the one the mesh was made with\n"
    "  --quiet          print nothing but errors\n";

int run_quality(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json", "--chord-tol"}, {"--histograms", "--quiet"});
  if (args.positional().size() != 2) throw UsageError("quality needs PART.json and MESH.msh");
  BuildOptions build_options;
  build_options.chord_tol = args.positive_number("--chord-tol");
  const Part part = build_part(read_brep_json(args.positional()[0]), build_options);
  const QuadMesh mesh = read_msh(args.positional()[1]);
  const MeshCheck check = check_mesh(part, mesh);
  const QualitySummary summary = summarize(part, mesh);
  if (const auto path = args.value("--json")) {
    write_file_atomically(
        *path, [&](std::ostream& o) { write_quality_json(o, summary, check, args.flag("--histograms")); });
  }
  if (!args.flag("--quiet")) {
    std::printf("%zu elements (%zu quads, %zu triangles), %zu nodes, %zu invalid\n",
                summary.elements, summary.quads, summary.triangles, summary.nodes,
                summary.invalid_elements);
    std::printf("%-16s %10s %10s %10s %10s %8s\n", "measure", "mean", "worst", "p5", "p95",
                "% bad");
    for (const MeasureSummary& m : summary.measures) {
      std::printf("%-16s %10.4g %10.4g %10.4g %10.4g %8.2f  (bad %s)\n", m.name.c_str(), m.mean,
                  m.worst, m.p5, m.p95, m.bad_percent, m.bad_when.c_str());
    }
    std::printf("valid by quality.md: %s\n", check.valid() ? "yes" : "NO");
  }
  if (!check.valid()) std::cerr << check.report();
  return check.valid() ? kOk : kInvalidMesh;
}

}  // namespace laytracks::cli
