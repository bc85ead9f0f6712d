#include "laytracks/io/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "laytracks/brep/error.hpp"

namespace laytracks {

namespace fs = std::filesystem;

namespace {

/// A name beside `path` that no other writer uses: same folder, so the rename is atomic.
fs::path temporary_beside(const fs::path& path) {
  std::random_device rd;
  const auto tag = std::to_string(rd()) + std::to_string(rd());
  return path.parent_path() / ("." + path.filename().string() + ".tmp" + tag);
}

}  // namespace

void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  const fs::path target(path);
  if (target.filename().empty()) throw Error("cannot write \"" + path + "\": not a file name");
  const fs::path tmp = temporary_beside(target);
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) {
        throw Error("cannot write " + path + ": " + std::strerror(errno));
      }
      write(out);
      out.flush();
      if (!out) throw Error("cannot write " + path + ": the write failed (disk full?)");
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw Error("cannot write " + path + ": " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void check_can_write(const std::string& path) {
  const fs::path target(path);
  if (target.filename().empty()) throw Error("cannot write \"" + path + "\": not a file name");
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::exists(folder, ec))
    throw Error("cannot write " + path + ": the folder " + folder.string() + " does not exist");
  if (!fs::is_directory(folder, ec))
    throw Error("cannot write " + path + ": " + folder.string() + " is not a folder");
  if (fs::is_directory(target, ec)) throw Error("cannot write " + path + ": it is a folder");
  // The temporary file goes beside the target: the folder must take new files.
  if (::access(folder.c_str(), W_OK) != 0)
    throw Error("cannot write " + path + ": " + std::strerror(errno));
}

}  // namespace laytracks
