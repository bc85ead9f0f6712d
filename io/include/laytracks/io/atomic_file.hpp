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

/// Throws laytracks::Error, naming `path`, when write_file_atomically could not write it: its
/// folder does not exist, is not a folder or is not writable, or `path` is a folder. Called
/// before long work, so that a run does not fail at its end for a mistyped folder.
void check_can_write(const std::string& path);

}  // namespace laytracks
