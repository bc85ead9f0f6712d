// laytracks: all-quadrilateral meshing of shells made of planar patches (LayTracks, 2004).
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "laytracks/brep/error.hpp"

namespace {

const char* const kHelp =
    "usage: laytracks COMMAND [ARGS]\n"
    "\n"
    "commands:\n"
    "  mesh PART.json -o OUT  mesh the part with quads, check it, write .msh .vtu .bdf .inp ...\n"
    "                         (uniform tracks, or --adaptive: sized by the medial radius)\n"
    "  batch INPUTS -o DIR    mesh many parts (files, folders, list files) in parallel, with a\n"
    "                         table of the results and DIR/batch-report.json\n"
    "  medial PART.json       the medial axis of every patch, as JSON and as a picture\n"
    "  check-loops PART.json  lay the rails and report how every rail chain ends\n"
    "  draw PART.json         picture of a stage: medial, corridors, tracks or mesh\n"
    "  quality PART MESH.msh  rate any MSH 4.1 mesh of the part by quality.md\n"
    "  help [COMMAND]         this text, or a command's own\n"
    "\n"

    "exit status: 0 done; 1 the part was refused (it breaks the format's rules, or an outline\n"
    "folds back within 1e-7 x its size of itself and cannot be meshed) or could not be read\n"
    "(the message says what and where); 2 wrong command line; 3 internal error (a stage failed\n"
    "its own check: please report it with the part); 4 an output file could not be written;\n"
    "5 (quality) the mesh is not valid. On any error nothing is written, and an existing output\n"
    "file is left as it was.\n"
    "batch meshes every part it can; its status says what became of the others (laytracks help\n"
    "batch).\n";

int dispatch(const std::vector<std::string>& args) {
  using namespace laytracks::cli;
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    if (args.size() > 1 && args[1] == "mesh") {
      std::cout << kMeshHelp;
    } else if (args.size() > 1 && args[1] == "batch") {
      std::cout << kBatchHelp;
    } else if (args.size() > 1 && args[1] == "medial") {
      std::cout << kMedialHelp;
    } else if (args.size() > 1 && args[1] == "check-loops") {
      std::cout << kCheckLoopsHelp;
    } else if (args.size() > 1 && args[1] == "draw") {
      std::cout << kDrawHelp;
    } else if (args.size() > 1 && args[1] == "quality") {
      std::cout << kQualityHelp;
    } else {
      std::cout << kHelp;
    }
    return args.empty() ? kUsage : kOk;
  }
  if (args[0] == "--version") {
    std::cout << "laytracks 0.1.0\n";
    return kOk;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  for (const auto& a : rest) {
    if (a == "--help" || a == "-h") return dispatch({"help", args[0]});
  }
  if (args[0] == "mesh") return run_mesh(rest);
  if (args[0] == "batch") return run_batch(rest);
  if (args[0] == "medial") return run_medial(rest);
  if (args[0] == "check-loops") return run_check_loops(rest);
  if (args[0] == "draw") return run_draw(rest);
  if (args[0] == "quality") return run_quality(rest);
  throw UsageError("unknown command \"" + args[0] + "\" (see laytracks --help)");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace laytracks::cli;
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    return dispatch(args);
  } catch (const UsageError& e) {
    std::cerr << "laytracks: " << e.what() << '\n';
    return kUsage;
  } catch (const laytracks::InputError& e) {
    std::cerr << "laytracks: error: " << e.what() << '\n';
    return kInputRefused;
  } catch (const laytracks::InternalError& e) {
    std::cerr << "laytracks: internal error: " << e.what() << '\n';
    return kInternal;
  } catch (const laytracks::Error& e) {
    std::cerr << "laytracks: error: " << e.what() << '\n';
    return kIo;
  } catch (const std::exception& e) {
    std::cerr << "laytracks: internal error: " << e.what() << '\n';
    return kInternal;
  }
}
