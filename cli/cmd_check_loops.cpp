// laytracks check-loops PART.json [--size W | --adaptive ...] [--json OUT.json] [--chord-tol T]
//                       [--quiet]
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/brep/build.hpp"
#include "laytracks/cutgraph/cut_graph.hpp"
#include "laytracks/io/atomic_file.hpp"
#include "laytracks/io/brep_json.hpp"
#include "laytracks/medial/part_medial.hpp"
#include "laytracks/mesher/mesh_part.hpp"
#include "meshing.hpp"

namespace laytracks::cli {

const char* const kCheckLoopsHelp =
    "usage: laytracks check-loops PART.json [--size W | --adaptive [--dtheta DEG]\n"
    "                             [--min-size S] [--max-size S]] [--json OUT.json]\n"
    "                             [--chord-tol T] [--quiet]\n"
    "\n"
    "Lays the rails (from the branch points' touching points, then the track rails of every\n"
    "corridor at width W, or adaptively as `laytracks mesh` would) and reports every rail\n"
    "chain and how it ends: loop, free-edge, concave-vertex, branch-point, junction (an edge\n"
    "of 3 or more patches), convex-vertex, round-corner.\n"
    "On a closed shell without concave vertices every rail that passes no branch point must\n"
    "close, within 1e-9 x the part's size. Exit status 3 when a rail ends where the geometry\n"
    "does not allow it, a loop does not close, or the cut graph fails its validator.\n"
    "\n"
    "  --size W, --uniform, --adaptive, --dtheta, --min-size, --max-size\n"
    "                  the tracks, as for `laytracks mesh` (laytracks help mesh)\n"
    "  --json OUT.json "
    "{\"rails\":[{\"id\",\"start\",\"end\",\"closure_gap\",\"source\",\"patches\",\n"
    "                  \"points\",\"from\",\"to\"}],\"deleted\":[{\"at\",\"patch\",\n"
    "                  \"corridor_width\",\"through_branch_point\"}],\"loops\",\"max_closure_gap\",\n"
    "                  \"ok\",...}: each rail's first and last boundary points and each\n"
    "                  deleted source rail's point in the part's 3D frame (the same rails\n"
    "                  in another pose of the part are at the posed points)\n"
    "  --chord-tol T   sagitta bound for arcs\n"
    "  --quiet         print nothing but errors\n";

namespace {
/// A point as [x, y, z].
nlohmann::ordered_json xyz(Vec3 p) { return nlohmann::ordered_json::array({p.x, p.y, p.z}); }
}  // namespace

/// Largest closure gap of a loop accepted, x the part's size (the paper's lemma, Fig. 4).
constexpr double kMaxClosureGapRel = 1e-9;

int run_check_loops(const std::vector<std::string>& argv) {
  const Args args = meshing_args(argv, {"--json"}, {"--quiet"});
  if (args.positional().size() != 1) throw UsageError("check-loops needs exactly one PART.json");
  const auto t0 = std::chrono::steady_clock::now();
  const MeshingOptions meshing = meshing_options(args);
  const Part part = read_part(args.positional()[0], meshing.build);
  std::vector<MedialAxis> axes = compute_medial_axes(part);
  std::unique_ptr<TrackWidthLaw> law;
  const CutGraphOptions options = cut_graph_options(part, axes, meshing.mesh, law);
  const CutGraph graph = build_cut_graph(part, axes, options);
  const std::vector<std::string> problems = validate_cut_graph(part, axes, graph);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  std::size_t loops = 0;
  double max_gap = 0.0;
  std::map<std::string, std::size_t> ends;
  nlohmann::ordered_json rails = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < graph.chains.size(); ++i) {
    const RailChain& c = graph.chains[i];
    if (c.end == RailEnd::Loop) {
      ++loops;
      max_gap = std::max(max_gap, c.closure_gap);
    }
    if (c.end != RailEnd::Loop) {
      ++ends[to_string(c.start)];
      ++ends[to_string(c.end)];
    }
    nlohmann::ordered_json patches = nlohmann::ordered_json::array();
    for (PatchId p : c.patches) patches.push_back(part.patches[p.index()].name);
    nlohmann::ordered_json rail{{"id", i},
                                {"start", to_string(c.start)},
                                {"end", to_string(c.end)},
                                {"closure_gap", c.closure_gap},
                                {"source", c.source},
                                {"patches", patches},
                                {"points", c.through.size()}};
    if (!c.through.empty()) {
      rail["from"] = xyz(graph.gverts[c.through.front().index()].position);
      rail["to"] = xyz(graph.gverts[c.through.back().index()].position);
    }
    rails.push_back(std::move(rail));
  }
  nlohmann::ordered_json deleted = nlohmann::ordered_json::array();
  for (const DeletedRail& d : graph.deleted)
    deleted.push_back({{"at", xyz(d.at)},
                       {"patch", part.patches[d.patch.index()].name},
                       {"corridor_width", d.corridor_width},
                       {"through_branch_point", d.through_branch_point}});
  const bool gaps_ok = max_gap <= kMaxClosureGapRel * part.size;
  const bool ok = problems.empty() && gaps_ok;
  nlohmann::ordered_json doc;
  doc["rails"] = rails;
  doc["deleted"] = deleted;
  doc["loops"] = loops;
  doc["max_closure_gap"] = max_gap;
  doc["ok"] = ok;
  doc["mode"] = law ? "adaptive" : "uniform";
  doc["track_width"] = law ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.track_width);
  doc["rail_points"] = graph.gverts.size();
  doc["corridors"] = graph.corridor_count;
  doc["tracks"] = graph.track_count;
  doc["deleted_rails"] = graph.deleted.size();
  doc["narrow_rounds"] = graph.narrow_rounds;
  doc["narrow_corridors_kept"] = graph.narrow_kept;
  doc["crowded_rails_dropped"] = graph.crowded_rails;
  doc["crowded_seeds_dropped"] = graph.crowded_seeds;
  doc["problems"] = problems;
  if (const auto path = args.value("--json")) {
    write_file_atomically(*path, [&](std::ostream& o) { o << doc.dump(1) << '\n'; });
  }
  if (!args.flag("--quiet")) {
    char tracks[96];
    if (law) {
      std::snprintf(tracks, sizeof tracks, "adaptive tracks (dtheta %.3g deg)",
                    law->options().dtheta * 180.0 / kPi);
    } else {
      std::snprintf(tracks, sizeof tracks, "track width %.6g", options.track_width);
    }
    std::printf("%zu rail chains (%zu loops) through %zu rail points, %s, %.3f s\n",
                graph.chains.size(), loops, graph.gverts.size(), tracks, seconds);
    std::printf(
        "%zu corridors, %zu tracks; %zu source rails deleted for narrow corridors (in %zu "
        "rounds), %zu narrow corridors kept (small features); not laid for crowding: %zu "
        "source rails, %zu track seeds\n",
        graph.corridor_count, graph.track_count, graph.deleted.size(), graph.narrow_rounds,
        graph.narrow_kept, graph.crowded_rails, graph.crowded_seeds);
    std::printf("chain ends:\n");
    for (const auto& [end, n] : ends) std::printf("  %-15s %zu\n", end.c_str(), n);
    std::printf("largest loop closure gap %.3g (limit %.3g): %s\n", max_gap,
                kMaxClosureGapRel * part.size, gaps_ok ? "ok" : "TOO LARGE");
  }
  for (std::size_t i = 0; i < problems.size() && i < 10; ++i) {
    std::cerr << "laytracks: check-loops: " << problems[i] << '\n';
  }
  return ok ? kOk : kInternal;
}

}  // namespace laytracks::cli
