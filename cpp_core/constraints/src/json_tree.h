// A JSON document read into a small tree that keeps what the constraint-file checks need and a
// general-purpose DOM loses: members in the file's order, the literal text of every number (so an
// integer too large for 64 bits is still reported as written), and no duplicate keys. Built from
// nlohmann::json's SAX parser; syntax errors carry their line and column.
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace meshik::constraints {

// One JSON value. Objects keep their members in the file's order; lists their elements.
struct JsonValue {
  enum class Kind { Null, Bool, Number, String, List, Object };
  Kind kind = Kind::Null;
  bool boolean = false;
  double number = 0.0;        // the number's value (finite: overflowing literals are refused)
  bool is_integer = false;    // the literal has no fraction or exponent
  std::string text;           // a string's value, or a number's literal text
  std::vector<JsonValue> elements;                         // a list's elements
  std::vector<std::pair<std::string, JsonValue>> members;  // an object's members

  // The member named `key`, or nullptr (objects only).
  const JsonValue* find(std::string_view key) const;
};

// Text that is not one JSON value, a duplicate key, or nesting deeper than the reader's limit.
// what(): "not valid JSON: line 3 column 7: <reason>", or "JSON nested too deeply", or
// "<JSON path>: duplicate key" (the path names the repeated member).
class JsonSyntaxError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The deepest nesting of lists and objects accepted (the format needs 6).
constexpr std::size_t kMaxJsonDepth = 256;

// Parses `text` (UTF-8) as one JSON value; NaN and Infinity are refused (not JSON). Throws
// JsonSyntaxError.
JsonValue parse_json(std::string_view text);

// Line and column (1-based; columns count characters, not bytes) of byte `offset` of `text`.
std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t offset);

}  // namespace meshik::constraints
