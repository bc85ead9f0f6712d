// Reading the B-Rep JSON format (../shared/spec/brep-json.md, version "brep/1").
#pragma once

#include <string>

#include "laytracks/brep/raw_part.hpp"

namespace laytracks {

/// Maximum nesting depth of arrays and objects accepted in an input file. The format needs 4
/// (root, patches, a patch's loops, a loop); anything much deeper is refused before parsing.
constexpr int kMaxJsonDepth = 32;

/// Parses the text of a part file. `source` is the name used in messages (usually the path).
/// Throws InputError for malformed JSON, too-deep nesting, a missing or wrong "laytracks" tag,
/// wrong types, non-finite or absurd numbers, negative or out-of-range indices and non-positive
/// mesh parameters; the message starts with `source:line:column: `.
/// Geometry is not checked here: build_part() does that.
RawPart parse_brep_json(const std::string& text, const std::string& source);

/// Reads and parses a part file. Throws InputError when the file cannot be read.
RawPart read_brep_json(const std::string& path);

}  // namespace laytracks
