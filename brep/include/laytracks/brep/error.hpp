// Errors thrown by the library. Library code never exits the process: the CLI turns these into
// messages and exit codes.
#pragma once

#include <stdexcept>
#include <string>

namespace laytracks {

/// Any failure of the library. what() is a complete sentence for the user: what and where.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The input breaks the format contract (../shared/spec/brep-json.md): syntax, types, or a
/// geometric rule. The part is refused; nothing is written.
class InputError : public Error {
 public:
  using Error::Error;
};

/// A stage produced a result that fails its own validator: a bug, reported loudly.
class InternalError : public Error {
 public:
  using Error::Error;
};

}  // namespace laytracks
