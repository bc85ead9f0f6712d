// Running the laytracks executable from a test as a user runs it: through the shell, capturing
// stdout, stderr and the exit status. Shared by the CLI tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace laytracks::test {

struct Run {
  int status = -1;
  std::string out;
  std::string err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The path quoted for the shell.
inline std::string q(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

/// Runs `laytracks ARGS` through the shell (in the test's working folder), capturing stdout,
/// stderr and the exit status. The captures are per process, so CTest may run tests in
/// parallel.
inline Run run(const std::string& args) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("laytracks-cli-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path out = dir / "stdout.txt";
  const fs::path err = dir / "stderr.txt";
  const std::string cmd =
      std::string("'") + LAYTRACKS_EXE + "' " + args + " >" + q(out) + " 2>" + q(err);
  const int raw = std::system(cmd.c_str());
  Run r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// An empty folder of the given name in the temporary folder (emptied if it exists).
inline std::filesystem::path fresh_dir(const std::string& name) {
  namespace fs = std::filesystem;
  const fs::path d = fs::temp_directory_path() / ("laytracks-cli-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace laytracks::test
