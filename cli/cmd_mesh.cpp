// laytracks mesh PART.json -o OUT.ext [--size W | --adaptive [--dtheta DEG] [--min-size S]
//                [--max-size S]] [--smooth N] [--report R.json] [--chord-tol T] [--quiet]
//                [--debug-dump DIR]
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/mesh_output.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "meshing.hpp"

namespace laytracks::cli {

const char* const kMeshHelp =
    "usage: laytracks mesh PART.json -o OUT.ext [--size W | --uniform | --adaptive\n"
    "                      [--dtheta DEG] [--min-size S] [--max-size S]] [--smooth N]\n"
    "                      [--report R.json]\n"
    "                      [--chord-tol T] [--quiet] [--debug-dump DIR]\n"
    "\n"
    "Meshes the part with quadrilaterals only (LayTracks: uniform tracks, or with --adaptive\n"
    "tracks as wide as the medial radius times dtheta), checks the mesh by\n"
    "every validity rule of quality.md, and writes it only if it passes. The format follows\n"
    "the extension of OUT: .msh (Gmsh 4.1), .vtu (VTK), .bdf (Nastran), .inp (Abaqus), .obj,\n"
    ".off. Progress per stage goes to stderr; the last line sums up the mesh.\n"
    "\n"
    "  -o OUT.ext       the mesh file (written atomically: nothing is left on failure)\n"
    LAYTRACKS_MESHING_OPTIONS_HELP
    "  --report R.json  quality figures before and after smoothing (with the element sizes\n"
    "                   and the worst ratio between neighbours), counts, time per stage\n"
    "  --debug-dump DIR if the mesh fails its check, write DIR/mesh.msh and DIR/part.json\n"
    "  --quiet          print nothing but errors\n"
    "\n"
    "The passes use all cores; LAYTRACKS_THREADS=N in the environment sets how many. The\n"
    "output is the same, byte for byte, for every N.\n";

namespace {

nlohmann::ordered_json summary_json(const QualitySummary& s) {
  std::ostringstream o;
  write_quality_json(o, s, false);
  return nlohmann::ordered_json::parse(o.str());
}

}  // namespace

void check_mesh_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string known;
  for (const std::string& e : mesh_output_extensions()) {
    if (e == ext) return;
    known += (known.empty() ? "" : " ") + e;
  }
  throw UsageError("cannot write a mesh to \"" + path + "\": the extension must be one of " +
                   known);
}

int run_mesh(const std::vector<std::string>& argv) {
  const Args args = meshing_args(argv, {"-o", "--report", "--debug-dump"}, {"--quiet"});
  if (args.positional().size() != 1) throw UsageError("mesh needs exactly one PART.json");
  const auto out = args.value("-o");
  if (!out) throw UsageError("mesh needs -o OUT.ext (.msh .vtu .bdf .inp .obj .off)");
  check_mesh_extension(*out);
  check_can_write(*out);
  if (const auto report = args.value("--report")) check_can_write(*report);
  const bool quiet = args.flag("--quiet");
  const auto t0 = std::chrono::steady_clock::now();
  const MeshingOptions options = meshing_options(args);
  const std::string input = args.positional()[0];
  const Part part = read_part(input, options.build);
  const auto on_stage = [&](const char* stage) {
    if (!quiet) std::fprintf(stderr, "  %-7s ...\n", stage);
  };
  MeshPartResult r;
  try {
    r = mesh_part(part, options.mesh, on_stage);
  } catch (const InvalidMeshError& e) {
    if (const auto dir = args.value("--debug-dump")) {
      std::filesystem::create_directories(*dir);
      write_mesh((std::filesystem::path(*dir) / "mesh.msh").string(), part, e.mesh());
      std::filesystem::copy_file(input, std::filesystem::path(*dir) / "part.json",
                                 std::filesystem::copy_options::overwrite_existing);
      std::ofstream((std::filesystem::path(*dir) / "failures.txt").string()) << e.check().report();
      std::cerr << "laytracks: the failing mesh and the part are in " << *dir << "\n";
    }
    std::cerr << e.check().report();
    throw;
  }
  if (r.size_capped_from && !quiet) {
    const double extent = part_extent(part), cap = kMaxSizeFraction * extent;
    std::cerr << "laytracks: note: element size " << *r.size_capped_from
              << " is more than a quarter of the part's extent (" << extent << "): meshed at "
              << r.size;
    if (r.size < cap) std::cerr << " (at " << cap << " no valid mesh came)";
    std::cerr << "\n";
  } else if (r.size_failed_at && !quiet) {
    std::cerr << "laytracks: note: at element size " << *r.size_failed_at << " no valid mesh came ("
              << r.failed_because << "); meshed at " << r.size << "\n";
  }
  write_part_mesh(*out, part, r.mesh);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (const auto report = args.value("--report")) {
    nlohmann::ordered_json doc;
    doc["part"] = input;
    doc["mode"] = r.adaptive ? "adaptive" : "uniform";
    if (r.adaptive) {
      doc["dtheta_deg"] = r.dtheta_deg;
      doc["min_end_width"] = r.size;
    } else {
      doc["size"] = r.size;
      if (r.size_capped_from || r.size_failed_at)
        doc["size_asked"] = r.size_capped_from ? *r.size_capped_from : *r.size_failed_at;
      if (r.size_failed_at) doc["size_failed"] = r.failed_because;
    }
    doc["smooth"] = options.mesh.smooth;
    doc["quads"] = r.mesh.elements.size();
    doc["nodes"] = r.mesh.nodes.size();
    doc["valid"] = r.check.valid();
    doc["faces"] = r.stats.faces;
    for (std::size_t k = 0; k < kTemplateNames.size(); ++k)
      doc["faces_by_template"][kTemplateNames[k]] = r.stats.by_template[k];
    doc["faces_shared"] = r.stats.shared_faces;
    doc["narrow_fans_dropped"] = r.stats.narrow_fans;
    doc["crowded_feet_dropped"] = r.stats.crowded_feet;
    doc["twin_rails_dropped"] = r.stats.twin_rails;
    doc["unfolded_darts"] = r.stats.unfolded_darts;
    doc["graded_rails"] = r.stats.graded_rails;
    doc["outward_rails_dropped"] = r.stats.outward_rails;
    doc["slit_rails_dropped"] = r.stats.slit_rails;
    doc["sliver_cap_rails_dropped"] = r.stats.sliver_cap_rails;
    doc["needle_tip_faces"] = r.stats.needle_tip_faces;
    doc["split_pieces"] = r.stats.split_pieces;
    doc["crossing_rails_dropped"] = r.stats.crossing_rails;
    doc["fan_cluster_merges"] = r.stats.fan_clusters;
    doc["smooth_vertex_feet"] = r.stats.smooth_vertex_feet;
    doc["edge_flips"] = r.stats.edge_flips;
    doc["thin_rows_merged"] = r.stats.thin_rows;
    doc["corner_kites_folded"] = r.stats.corner_kites;
    doc["corner_reliefs_folded"] = r.stats.corner_reliefs;
    doc["thin_bends_squared"] = r.stats.thin_bends;
    doc["boundary_nodes_slid"] = r.stats.slid_nodes;
    doc["late_rounds"] = r.stats.late_rounds;
    doc["cavity_refills"] = r.stats.cavity_refills;
    doc["regrids"] = r.stats.regrids;
    doc["loop_bridges"] = r.stats.loop_bridges;
    doc["disk_patches"] = r.stats.disk_patches;
    doc["hub_patches"] = r.stats.hub_patches;
    doc["spiral_closures"] = r.spiral_closures;
    doc["loop_closures"] = r.loop_closures;
    doc["rail_merges"] = r.rail_merges;
    doc["crowded_rails_dropped"] = r.crowded_rails;
    doc["crowded_seeds_dropped"] = r.crowded_seeds;
    doc["parity_fixes"] = {{"boundary_pieces", r.stats.parity_boundary},
                           {"rail_segments", r.stats.parity_rails},
                           {"strips_matched", r.stats.parity_strips}};
    doc["seconds"] = {{"medial", r.times.medial}, {"rails", r.times.rails},
                      {"quads", r.times.quads},   {"refill", r.times.refill},
                      {"smooth", r.times.smooth},
                      {"check", r.times.check},   {"total", seconds}};
    doc["quality"] = summary_json(r.quality);
    doc["quality_before_smoothing"] = summary_json(r.before_smoothing);
    write_file_atomically(*report, [&](std::ostream& o) { o << doc.dump(2) << '\n'; });
  }
  if (!quiet) {
    const auto& m = r.quality.measures;
    std::string grading;
    if (r.adaptive) {
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "sizes %.3g to %.3g (finest/coarsest tenth %.2f), worst neighbour ratio %.2f, ",
                    r.quality.min_size, r.quality.max_size, r.quality.fine_coarse_ratio,
                    r.quality.worst_neighbour_ratio);
      grading = buf;
    }
    std::printf(
        "%s: %zu quads, %zu nodes, min scaled Jacobian %.3f, beyond thresholds: skew %.1f%%, "
        "aspect %.1f%%, taper %.1f%%, %s%.2f s\n",
        out->c_str(), r.quality.quads, r.quality.nodes, m[6].worst, m[0].bad_percent,
        m[1].bad_percent, m[2].bad_percent, grading.c_str(), seconds);
  }
  return kOk;
}

}  // namespace laytracks::cli
