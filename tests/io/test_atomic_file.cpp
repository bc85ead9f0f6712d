// Output files are written atomically: all or nothing, and an old file survives a failure.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "laytracks/brep/error.hpp"
#include "laytracks/io/atomic_file.hpp"

namespace fs = std::filesystem;
using laytracks::write_file_atomically;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("laytracks-test-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::size_t entries(const fs::path& d) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}

}  // namespace

TEST_CASE("a successful write replaces the file and leaves nothing else", "[io][atomic]") {
  const fs::path d = fresh_dir("atomic-ok");
  const fs::path f = d / "out.txt";
  write_file_atomically(f.string(), [](std::ostream& o) { o << "first"; });
  write_file_atomically(f.string(), [](std::ostream& o) { o << "second"; });
  CHECK(slurp(f) == "second");
  CHECK(entries(d) == 1);
}

TEST_CASE("a failing writer leaves the old file as it was and no temporary", "[io][atomic]") {
  const fs::path d = fresh_dir("atomic-fail");
  const fs::path f = d / "out.txt";
  write_file_atomically(f.string(), [](std::ostream& o) { o << "kept"; });
  CHECK_THROWS_WITH(write_file_atomically(f.string(),
                                          [](std::ostream& o) {
                                            o << "partial";
                                            throw laytracks::Error("mesh check failed");
                                          }),
                    "mesh check failed");
  CHECK(slurp(f) == "kept");
  CHECK(entries(d) == 1);
}

TEST_CASE("a failing writer creates no file where there was none", "[io][atomic]") {
  const fs::path d = fresh_dir("atomic-none");
  const fs::path f = d / "out.txt";
  CHECK_THROWS(
      write_file_atomically(f.string(), [](std::ostream&) { throw laytracks::Error("refused"); }));
  CHECK_FALSE(fs::exists(f));
  CHECK(entries(d) == 0);
}

TEST_CASE("an unwritable folder gives an error naming the path", "[io][atomic]") {
  CHECK_THROWS_WITH(write_file_atomically("/nonexistent-folder-laytracks/out.txt",
                                          [](std::ostream& o) { o << 1; }),
                    Catch::Contains("/nonexistent-folder-laytracks/out.txt"));
}
