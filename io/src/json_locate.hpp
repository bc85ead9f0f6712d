// Private to io/: small scanners over the raw text of a JSON document, for error messages.
//
// nlohmann::json keeps no source positions in its DOM, so the reader parses with it, validates
// the DOM, and only when something is wrong comes back here to find where in the text the
// offending value is. Every function here works on the bytes of the document; none builds a
// DOM. Offsets are 0-based byte offsets into the text.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace laytracks::json_locate {

/// A 1-based line and column. Lines are separated by '\n'; columns count characters (UTF-8
/// code points, a tab counts as one), so they match what an editor shows.
struct TextPosition {
  std::size_t line = 1;
  std::size_t column = 1;
};

/// The line and column of the byte at `offset` (an offset at or past the end of the text gives
/// the position just after the last character). A leading UTF-8 byte order mark is not counted.
TextPosition position_of(std::string_view text, std::size_t offset);

/// One step of a path from the root of a document to a value: an object key or an array index.
struct PathStep {
  PathStep(std::string k) : key(std::move(k)), is_key(true) {}  // NOLINT: implicit on purpose
  PathStep(const char* k) : key(k), is_key(true) {}             // NOLINT
  PathStep(std::size_t i) : index(i) {}                         // NOLINT
  std::string key;
  std::size_t index = 0;
  bool is_key = false;
};
using JsonPath = std::vector<PathStep>;

/// The path as a user reads it: `patches[1].loops[0][3]`, `mesh.size`; "the root" when empty.
std::string to_string(const JsonPath& path);

/// The offset of the first '[' or '{' that opens a container nested deeper than `max_depth`
/// (the root container is at depth 1), or nothing. Works on any text, well-formed or not:
/// brackets inside strings (with their escapes) are ignored.
std::optional<std::size_t> find_excess_nesting(std::string_view text, int max_depth);

/// A syntax error: where, and what in words (without the position), e.g.
/// "malformed JSON: unexpected '}', expected a value".
struct SyntaxError {
  std::size_t offset = 0;
  std::string message;
};

/// The first syntax error of the text as strict JSON (RFC 8259), or nothing when it is valid.
/// A number too large for a double (1e999) is an error too. The nesting depth is expected to
/// have been checked with find_excess_nesting() first (recursion follows the nesting).
std::optional<SyntaxError> find_syntax_error(std::string_view text);

/// A key given twice in one object.
struct DuplicateKey {
  std::string key;         ///< decoded
  JsonPath object;         ///< the object holding it
  std::size_t first = 0;   ///< offset of the first occurrence of the key (its opening quote)
  std::size_t second = 0;  ///< offset of the second occurrence
};

/// The first key, in text order, that appears twice in the same object, or nothing.
/// Precondition: the text is valid JSON. The scan is linear and builds no per-value strings.
std::optional<DuplicateKey> find_duplicate_key(std::string_view text);

/// Where a value's text starts and ends: [begin, end).
struct Span {
  std::size_t begin = 0;
  std::size_t end = 0;
};

/// The text span of the value at `path`, or nothing when there is no such value.
/// Precondition: the text is valid JSON without duplicate keys.
std::optional<Span> locate_value(std::string_view text, const JsonPath& path);

/// The offset of the key (its opening quote) named by the last step of `path`, which must be
/// a key, or nothing when there is no such key. Precondition as for locate_value().
std::optional<std::size_t> locate_key(std::string_view text, const JsonPath& path);

}  // namespace laytracks::json_locate
