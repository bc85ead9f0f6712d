// Reading the B-Rep JSON format (../shared/spec/brep-json.md, version "brep/1").
#pragma once

#include <string>

#include "laytracks/brep/raw_part.hpp"

namespace laytracks {

/// Maximum nesting depth of arrays and objects accepted in an input file. The format needs 4
/// (root, patches, a patch's loops, a loop); anything much deeper is refused before parsing.
constexpr int kMaxJsonDepth = 32;

/// Parses the text of a part file. `source` is the name used in messages (usually the path).
/// Throws InputError for an empty text, nesting deeper than kMaxJsonDepth, malformed JSON, a
/// key given twice in one object, a missing or wrong "laytracks" tag, unknown keys, wrong types,
/// non-finite or absurd (|x| > 1e12) coordinates, indices that are not integers in range,
/// patch names given twice, and mesh parameters out of their range. The message starts with
/// `source:line:column: ` (1-based; columns count UTF-8 characters) locating the offending
/// value, key or token. On success every field of RawPart is filled as given, absent optional
/// keys stay empty, units default to "mm" and `source` is set.
/// Geometry (loop lengths, planarity, crossings) is not checked here: build_part() does that.
RawPart parse_brep_json(const std::string& text, const std::string& source);

/// Reads the file in binary and parses it with `path` as the source name. Throws InputError
/// `cannot read <path>: <reason>` when the file cannot be opened or read.
RawPart read_brep_json(const std::string& path);

}  // namespace laytracks
