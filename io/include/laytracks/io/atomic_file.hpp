// Writing output files atomically: a temporary file in the same folder, then a rename.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace laytracks {

/// Calls `write` with a stream onto a temporary file beside `path`, then renames it over `path`.
/// If `write` throws or the stream fails, the temporary file is removed, `path` is untouched,
/// and the error propagates (as laytracks::Error for I/O failures).
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace laytracks
