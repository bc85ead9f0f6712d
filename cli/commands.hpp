// The subcommands of the laytracks executable. Each returns the process exit status and lets
// laytracks::Error propagate; main() turns errors into messages and statuses.
#pragma once

#include <string>
#include <vector>

namespace laytracks::cli {

/// Exit statuses, stated in --help.
enum Status : int {
  kOk = 0,
  kInputRefused = 1,  ///< the part breaks the format's rules, or cannot be read
  kUsage = 2,         ///< the command line is wrong
  kInternal = 3,      ///< a stage failed its own check: a bug, please report it
  kIo = 4,            ///< an output file could not be written
  kInvalidMesh = 5,   ///< quality: the mesh breaks a validity rule of quality.md
};

int run_mesh(const std::vector<std::string>& args);
extern const char* const kMeshHelp;
/// Throws UsageError unless write_mesh knows the extension of `path`.
void check_mesh_extension(const std::string& path);
int run_medial(const std::vector<std::string>& args);
extern const char* const kMedialHelp;
int run_batch(const std::vector<std::string>& args);
extern const char* const kBatchHelp;
int run_check_loops(const std::vector<std::string>& args);
int run_draw(const std::vector<std::string>& args);
int run_quality(const std::vector<std::string>& args);
extern const char* const kQualityHelp;
extern const char* const kDrawHelp;
extern const char* const kCheckLoopsHelp;

}  // namespace laytracks::cli
