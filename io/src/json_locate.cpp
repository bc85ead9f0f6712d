#include "json_locate.hpp"

#include <algorithm>
#include <cctype>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <utility>

namespace laytracks::json_locate {

namespace {

constexpr std::size_t kNone = std::string_view::npos;

bool is_continuation_byte(char c) { return (static_cast<unsigned char>(c) & 0xC0U) == 0x80U; }

bool is_json_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

bool is_digit(char c) { return c >= '0' && c <= '9'; }

/// Where the document starts: after a UTF-8 byte order mark, which nlohmann skips too.
std::size_t start_of_document(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
}

std::size_t skip_space(std::string_view text, std::size_t pos) {
  while (pos < text.size() && is_json_space(text[pos])) ++pos;
  return pos;
}

/// The length of the valid UTF-8 sequence (RFC 3629, as nlohmann checks it) starting at `pos`,
/// or 0 when the bytes there are not one.
std::size_t utf8_sequence_length(std::string_view text, std::size_t pos) {
  const auto byte = [&](std::size_t i) -> unsigned {
    return pos + i < text.size() ? static_cast<unsigned char>(text[pos + i]) : 0U;
  };
  const auto in = [](unsigned b, unsigned lo, unsigned hi) { return b >= lo && b <= hi; };
  const unsigned b0 = byte(0);
  if (b0 < 0x80U) return 1;
  if (in(b0, 0xC2U, 0xDFU)) return in(byte(1), 0x80U, 0xBFU) ? 2 : 0;
  if (in(b0, 0xE0U, 0xEFU)) {
    const unsigned lo = b0 == 0xE0U ? 0xA0U : 0x80U;
    const unsigned hi = b0 == 0xEDU ? 0x9FU : 0xBFU;
    return in(byte(1), lo, hi) && in(byte(2), 0x80U, 0xBFU) ? 3 : 0;
  }
  if (in(b0, 0xF0U, 0xF4U)) {
    const unsigned lo = b0 == 0xF0U ? 0x90U : 0x80U;
    const unsigned hi = b0 == 0xF4U ? 0x8FU : 0xBFU;
    return in(byte(1), lo, hi) && in(byte(2), 0x80U, 0xBFU) && in(byte(3), 0x80U, 0xBFU) ? 4 : 0;
  }
  return 0;
}

// ---- Helpers for text already known to be valid JSON. ----

/// `pos` is at the opening quote of a string; returns the offset just past its closing quote.
std::size_t end_of_string(std::string_view text, std::size_t pos) {
  for (++pos; pos < text.size(); ++pos) {
    if (text[pos] == '\\') {
      ++pos;
    } else if (text[pos] == '"') {
      return pos + 1;
    }
  }
  return text.size();
}

/// `pos` is at the first character of a value; returns the offset just past it.
std::size_t end_of_value(std::string_view text, std::size_t pos) {
  if (pos >= text.size()) return pos;
  const char c = text[pos];
  if (c == '"') return end_of_string(text, pos);
  if (c == '[' || c == '{') {
    int depth = 0;
    while (pos < text.size()) {
      const char d = text[pos];
      if (d == '"') {
        pos = end_of_string(text, pos);
        continue;
      }
      if (d == '[' || d == '{') ++depth;
      if ((d == ']' || d == '}') && --depth == 0) return pos + 1;
      ++pos;
    }
    return pos;
  }
  while (pos < text.size() && !is_json_space(text[pos]) && text[pos] != ',' && text[pos] != ']' &&
         text[pos] != '}') {
    ++pos;
  }
  return pos;
}

/// The decoded text of a string token, quotes included in `token`.
std::string decode_string(std::string_view token) {
  if (token.find('\\') == std::string_view::npos) {
    return std::string(token.substr(1, token.size() - 2));
  }
  return nlohmann::json::parse(token).get<std::string>();
}

// ---- The syntax checker: strict JSON, with messages for people. ----

/// Recursive descent over possibly malformed text; stops at the first error.
class SyntaxChecker {
 public:
  explicit SyntaxChecker(std::string_view text) : text_(text) {}

  std::optional<SyntaxError> run() {
    try {
      std::size_t pos = skip_space(text_, start_of_document(text_));
      value(pos);
      pos = skip_space(text_, pos);
      if (pos < text_.size()) {
        fail(pos, "unexpected " + describe(pos) + " after the end of the JSON document");
      }
    } catch (const Failure&) {
      return error_;
    }
    return std::nullopt;
  }

 private:
  struct Failure {};

  /// Stops the check with "malformed JSON: <message>" at `offset`.
  [[noreturn]] void fail(std::size_t offset, const std::string& message) {
    fail_plain(offset, "malformed JSON: " + message);
  }

  [[noreturn]] void fail_plain(std::size_t offset, std::string message) {
    error_ = SyntaxError{offset, std::move(message)};
    throw Failure{};
  }

  /// What is at `pos`, for "unexpected ...": a quoted character, or "end of input".
  std::string describe(std::size_t pos) const {
    if (pos >= text_.size()) return "end of input";
    const unsigned char c = static_cast<unsigned char>(text_[pos]);
    if (c < 0x20U || c == 0x7FU) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "control character U+%04X", c);
      return buf;
    }
    const std::size_t n = utf8_sequence_length(text_, pos);
    if (n == 0) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "byte 0x%02X, not UTF-8", c);
      return buf;
    }
    return "'" + std::string(text_.substr(pos, n)) + "'";
  }

  /// A hint for common mistakes at `pos`, to append to an "unexpected" message.
  std::string hint(std::size_t pos) const {
    const std::string_view rest = text_.substr(std::min(pos, text_.size()));
    if (rest.substr(0, 1) == "/") return " (comments are not allowed in JSON)";
    if (rest.substr(0, 1) == "'") return " (strings need double quotes)";
    if (rest.substr(0, 3) == "\xE2\x80\x9C" || rest.substr(0, 3) == "\xE2\x80\x9D") {
      return " (use straight double quotes)";
    }
    return "";
  }

  [[noreturn]] void unexpected(std::size_t pos, const std::string& expected) {
    std::string message = "unexpected " + describe(pos) + ", expected " + expected + hint(pos);
    if (pos >= text_.size() && !open_.empty()) {
      const TextPosition at = position_of(text_, open_.back());
      message = "unexpected end of input: the " +
                std::string(text_[open_.back()] == '{' ? "object" : "array") + " opened at line " +
                std::to_string(at.line) + ", column " + std::to_string(at.column) +
                " is not closed";
    }
    fail(pos, message);
  }

  [[noreturn]] void trailing_comma(std::size_t pos) {
    fail(pos, "unexpected " + describe(pos) + " after ',' (a trailing comma is not allowed)");
  }

  void value(std::size_t& pos) {
    pos = skip_space(text_, pos);
    if (pos >= text_.size()) unexpected(pos, "a value");
    const char c = text_[pos];
    if (c == '{') return object(pos);
    if (c == '[') return array(pos);
    if (c == '"') return string(pos);
    if (c == '-' || is_digit(c)) return number(pos);
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) return literal(pos);
    unexpected(pos, "a value");
  }

  void object(std::size_t& pos) {
    open_.push_back(pos);
    pos = skip_space(text_, pos + 1);
    if (pos < text_.size() && text_[pos] == '}') {
      ++pos;
      open_.pop_back();
      return;
    }
    for (;;) {
      pos = skip_space(text_, pos);
      if (pos >= text_.size() || text_[pos] != '"') {
        if (pos < text_.size() && text_[pos] == '}') trailing_comma(pos);
        unexpected(pos, "a key in double quotes");
      }
      string(pos);
      pos = skip_space(text_, pos);
      if (pos >= text_.size() || text_[pos] != ':') unexpected(pos, "':' after the key");
      ++pos;
      value(pos);
      pos = skip_space(text_, pos);
      if (pos < text_.size() && text_[pos] == ',') {
        ++pos;
        continue;
      }
      if (pos < text_.size() && text_[pos] == '}') break;
      unexpected(pos, "',' or '}'");
    }
    ++pos;
    open_.pop_back();
  }

  void array(std::size_t& pos) {
    open_.push_back(pos);
    pos = skip_space(text_, pos + 1);
    if (pos < text_.size() && text_[pos] == ']') {
      ++pos;
      open_.pop_back();
      return;
    }
    for (bool first = true;; first = false) {
      pos = skip_space(text_, pos);
      if (!first && pos < text_.size() && text_[pos] == ']') trailing_comma(pos);
      value(pos);
      pos = skip_space(text_, pos);
      if (pos < text_.size() && text_[pos] == ',') {
        ++pos;
        continue;
      }
      if (pos < text_.size() && text_[pos] == ']') break;
      unexpected(pos, "',' or ']'");
    }
    ++pos;
    open_.pop_back();
  }

  void string(std::size_t& pos) {
    const std::size_t open = pos;
    for (++pos; pos < text_.size();) {
      const unsigned char c = static_cast<unsigned char>(text_[pos]);
      if (c == '"') {
        ++pos;
        return;
      }
      if (c == '\n' || c == '\r') fail(open, "string not closed before the end of the line");
      if (c < 0x20U) fail(pos, "unescaped " + describe(pos) + " in a string");
      if (c == '\\') {
        pos = escape(pos);
      } else {
        const std::size_t n = utf8_sequence_length(text_, pos);
        if (n == 0) fail(pos, "invalid UTF-8 in a string (" + describe(pos) + ")");
        pos += n;
      }
    }
    fail(open, "unterminated string: missing closing quote");
  }

  /// `pos` is at a backslash; returns the offset past the escape sequence.
  std::size_t escape(std::size_t pos) {
    if (pos + 1 >= text_.size()) fail(pos, "unterminated string: missing closing quote");
    const char e = text_[pos + 1];
    if (std::string_view("\"\\/bfnrt").find(e) != std::string_view::npos) return pos + 2;
    if (e != 'u') {
      fail(pos, "invalid escape '\\" + std::string(text_.substr(pos + 1, 1)) + "' in a string");
    }
    const long unit = hex4(pos);
    if (unit >= 0xDC00 && unit <= 0xDFFF) fail(pos, "invalid \\u escape: unpaired surrogate");
    if (unit < 0xD800 || unit > 0xDBFF) return pos + 6;
    if (text_.substr(pos + 6, 2) != "\\u") fail(pos, "invalid \\u escape: unpaired surrogate");
    const long low = hex4(pos + 6);
    if (low < 0xDC00 || low > 0xDFFF) fail(pos, "invalid \\u escape: unpaired surrogate");
    return pos + 12;
  }

  /// The code unit of the \uXXXX escape at `pos`.
  long hex4(std::size_t pos) {
    const std::string digits(text_.substr(pos + 2, 4));
    if (digits.size() != 4 || digits.find_first_not_of("0123456789abcdefABCDEF") != kNone) {
      fail(pos, "invalid \\u escape: expected 4 hexadecimal digits");
    }
    return std::strtol(digits.c_str(), nullptr, 16);
  }

  void number(std::size_t& pos) {
    const std::size_t begin = pos;
    while (pos < text_.size() && std::string_view("0123456789+-.eE").find(text_[pos]) != kNone) {
      ++pos;
    }
    const std::string token(text_.substr(begin, pos - begin));
    if (!is_json_number(token)) fail(begin, "invalid number '" + token + "'");
    if (!std::isfinite(to_double(token))) {
      fail_plain(begin, "non-finite number " + token + ": it overflows a double");
    }
  }

  /// RFC 8259: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
  static bool is_json_number(const std::string& s) {
    std::size_t i = 0;
    const auto digits = [&] {
      const std::size_t from = i;
      while (i < s.size() && is_digit(s[i])) ++i;
      return i > from;
    };
    if (i < s.size() && s[i] == '-') ++i;
    if (i < s.size() && s[i] == '0') {
      ++i;
    } else if (!digits()) {
      return false;
    }
    if (i < s.size() && s[i] == '.') {
      ++i;
      if (!digits()) return false;
    }
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
      ++i;
      if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
      if (!digits()) return false;
    }
    return i == s.size();
  }

  /// strtod in any locale: the JSON '.' becomes the locale's decimal point, as nlohmann does.
  static double to_double(std::string token) {
    const char point = *std::localeconv()->decimal_point;
    for (char& c : token) {
      if (c == '.') c = point;
    }
    return std::strtod(token.c_str(), nullptr);
  }

  void literal(std::size_t& pos) {
    const std::size_t begin = pos;
    while (pos < text_.size() &&
           (std::isalnum(static_cast<unsigned char>(text_[pos])) != 0 || text_[pos] == '_')) {
      ++pos;
    }
    const std::string_view word = text_.substr(begin, pos - begin);
    if (word == "true" || word == "false" || word == "null") return;
    fail(begin, "invalid literal '" + std::string(word) +
                    "' (a value is a number, a \"string\", true, false, null, an array or an "
                    "object)");
  }

  std::string_view text_;
  std::vector<std::size_t> open_;  ///< offsets of the containers being read
  std::optional<SyntaxError> error_;
};

// ---- Duplicate keys, on valid text. ----

/// Walks valid JSON and stops at the first key repeated in its object. Keeps only a stack of
/// path steps (views into the text) and the keys of the open objects, reused across objects.
class DuplicateFinder {
 public:
  explicit DuplicateFinder(std::string_view text) : text_(text) {}

  std::optional<DuplicateKey> run() {
    value(skip_space(text_, start_of_document(text_)), 0);
    return found_;
  }

 private:
  struct Step {
    std::string_view key;  ///< raw key token, quotes included; empty for an array element
    std::size_t index = 0;
  };
  struct Key {
    std::string name;
    std::size_t offset;
  };

  /// Returns the offset past the value at `pos` (or anywhere once a duplicate is found).
  std::size_t value(std::size_t pos, std::size_t depth) {
    if (text_[pos] == '{') return object(pos, depth);
    if (text_[pos] == '[') return array(pos, depth);
    return end_of_value(text_, pos);
  }

  std::size_t object(std::size_t pos, std::size_t depth) {
    if (keys_.size() <= depth) keys_.resize(depth + 1);
    keys_[depth].clear();
    pos = skip_space(text_, pos + 1);
    while (text_[pos] != '}') {
      const std::size_t key_end = end_of_string(text_, pos);
      const std::string_view token = text_.substr(pos, key_end - pos);
      std::string name = decode_string(token);
      for (const Key& seen : keys_[depth]) {
        if (seen.name == name) {
          found_ = DuplicateKey{std::move(name), path(), seen.offset, pos};
          return text_.size();
        }
      }
      keys_[depth].push_back(Key{std::move(name), pos});
      pos = skip_space(text_, skip_space(text_, key_end) + 1);  // past ':'
      path_.push_back(Step{token, 0});
      pos = value(pos, depth + 1);
      path_.pop_back();
      if (found_) return text_.size();
      pos = skip_space(text_, pos);
      if (text_[pos] == ',') pos = skip_space(text_, pos + 1);
    }
    return pos + 1;
  }

  std::size_t array(std::size_t pos, std::size_t depth) {
    pos = skip_space(text_, pos + 1);
    path_.push_back(Step{{}, 0});
    while (text_[pos] != ']') {
      pos = value(pos, depth + 1);
      if (found_) return text_.size();
      ++path_.back().index;
      pos = skip_space(text_, pos);
      if (text_[pos] == ',') pos = skip_space(text_, pos + 1);
    }
    path_.pop_back();
    return pos + 1;
  }

  JsonPath path() const {
    JsonPath result;
    for (const Step& step : path_) {
      if (step.key.empty()) {
        result.emplace_back(step.index);
      } else {
        result.emplace_back(decode_string(step.key));
      }
    }
    return result;
  }

  std::string_view text_;
  std::vector<Step> path_;
  std::vector<std::vector<Key>> keys_;  ///< keys seen so far in the open object at each depth
  std::optional<DuplicateKey> found_;
};

// ---- Following a path, on valid text. ----

struct Child {
  std::size_t key = kNone;  ///< offset of the key's opening quote; kNone for an array element
  std::size_t value = kNone;
};

/// The child named by `step` of the container whose first character is at `pos`.
std::optional<Child> find_child(std::string_view text, std::size_t pos, const PathStep& step) {
  if (pos >= text.size()) return std::nullopt;
  const char open = text[pos];
  if (open != (step.is_key ? '{' : '[')) return std::nullopt;
  const char close = step.is_key ? '}' : ']';
  pos = skip_space(text, pos + 1);
  for (std::size_t index = 0; pos < text.size() && text[pos] != close; ++index) {
    Child child;
    if (step.is_key) {
      child.key = pos;
      const std::size_t key_end = end_of_string(text, pos);
      const bool match = decode_string(text.substr(pos, key_end - pos)) == step.key;
      pos = skip_space(text, skip_space(text, key_end) + 1);  // past ':'
      child.value = pos;
      if (match) return child;
    } else {
      child.value = pos;
      if (index == step.index) return child;
    }
    pos = skip_space(text, end_of_value(text, pos));
    if (pos < text.size() && text[pos] == ',') pos = skip_space(text, pos + 1);
  }
  return std::nullopt;
}

/// The child found by the last step of `path`, following the steps before it.
std::optional<Child> follow(std::string_view text, const JsonPath& path) {
  Child at;
  at.value = skip_space(text, start_of_document(text));
  for (const PathStep& step : path) {
    const std::optional<Child> child = find_child(text, at.value, step);
    if (!child) return std::nullopt;
    at = *child;
  }
  return at;
}

}  // namespace

TextPosition position_of(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  TextPosition at;
  std::size_t i = start_of_document(text);
  for (; i < offset; ++i) {
    if (text[i] == '\n') {
      ++at.line;
      at.column = 1;
    } else if (!is_continuation_byte(text[i])) {
      ++at.column;
    }
  }
  return at;
}

std::string to_string(const JsonPath& path) {
  if (path.empty()) return "the root";
  std::string s;
  for (const PathStep& step : path) {
    if (step.is_key) {
      if (!s.empty()) s += '.';
      s += step.key;
    } else {
      s += '[' + std::to_string(step.index) + ']';
    }
  }
  return s;
}

std::optional<std::size_t> find_excess_nesting(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) return i;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

std::optional<SyntaxError> find_syntax_error(std::string_view text) {
  return SyntaxChecker(text).run();
}

std::optional<DuplicateKey> find_duplicate_key(std::string_view text) {
  return DuplicateFinder(text).run();
}

std::optional<Span> locate_value(std::string_view text, const JsonPath& path) {
  const std::optional<Child> at = follow(text, path);
  if (!at) return std::nullopt;
  return Span{at->value, end_of_value(text, at->value)};
}

std::optional<std::size_t> locate_key(std::string_view text, const JsonPath& path) {
  if (path.empty() || !path.back().is_key) return std::nullopt;
  const std::optional<Child> at = follow(text, path);
  if (!at) return std::nullopt;
  return at->key;
}

}  // namespace laytracks::json_locate
