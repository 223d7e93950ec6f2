// Type checks for a JSON tree with messages that name the JSON path the way a user points at an
// element: `frames[3].targets.head` or `handles["left foot"][2]`. A check that fails records a
// Violation in a ViolationList and returns nothing, so that a reader of the document can go on
// and report every problem, not only the first.
#pragma once

#include "json_tree.h"
#include "meshik/constraints/constraint_file.h"

#include <array>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace meshik::constraints {

// The problems found so far, in the order they were found.
class ViolationList {
 public:
  void add(std::string path, std::string problem) { list_.push_back({std::move(path), std::move(problem)}); }
  const std::vector<Violation>& list() const { return list_; }
  bool empty() const { return list_.empty(); }
  std::size_t size() const { return list_.size(); }

 private:
  std::vector<Violation> list_;
};

// The JSON path of object member `key` under `path` (`path.key`, or `path["odd key"]`).
std::string child_path(const std::string& path, const std::string& key);
// The JSON path of list element `index` under `path` (`path[index]`).
std::string child_path(const std::string& path, std::size_t index);

// `text` in double quotes for a one-line message: backslash, quote and control characters escaped
// (a NUL as \u0000), cut to its first `max_characters` characters followed by "...".
std::string quoted_text(const std::string& text, std::size_t max_characters = 40);

// A short description of a JSON value for messages: "a list of 2", "the number 2.5", "null", ...
std::string describe(const JsonValue& value);

// `value` formatted like printf's "%g" with `digits` significant digits ("0", "0.1", "1e-07").
std::string format_general(double value, int digits = 6);

// Number of characters (Unicode code points) of UTF-8 `text`.
std::size_t character_count(const std::string& text);

// Whether `text` is empty or only white space.
bool is_blank(const std::string& text);

// `value` as an object / a list (optionally non-empty) / a non-empty string; nullopt (and a
// violation recorded at `path`) otherwise.
const JsonValue* expect_object(const JsonValue& value, const std::string& path, ViolationList& problems);
const JsonValue* expect_list(const JsonValue& value, const std::string& path, ViolationList& problems,
                             bool non_empty = false);
std::optional<std::string> expect_string(const JsonValue& value, const std::string& path, ViolationList& problems);

// `value` as a finite number >= minimum (> minimum when exclusive_minimum).
std::optional<double> expect_number(const JsonValue& value, const std::string& path, ViolationList& problems,
                                    double minimum = -std::numeric_limits<double>::infinity(),
                                    bool exclusive_minimum = false);

// `value` as an integer >= minimum (no fraction, no exponent); `what` names it ("a vertex index").
std::optional<std::int64_t> expect_int(const JsonValue& value, const std::string& path, ViolationList& problems,
                                       std::int64_t minimum, const std::string& what = "an integer");

// `value` as exactly N finite numbers, e.g. a position [x, y, z].
template <std::size_t N>
std::optional<std::array<double, N>> expect_numbers(const JsonValue& value, const std::string& path,
                                                    ViolationList& problems) {
  if (value.kind != JsonValue::Kind::List || value.elements.size() != N) {
    problems.add(path, "expected " + std::to_string(N) + " numbers, got " + describe(value));
    return std::nullopt;
  }
  std::array<double, N> numbers{};
  bool complete = true;
  for (std::size_t i = 0; i < N; ++i) {
    const auto number = expect_number(value.elements[i], child_path(path, i), problems);
    if (number) numbers[i] = *number;
    complete = complete && number.has_value();
  }
  if (!complete) return std::nullopt;
  return numbers;
}

// Records a violation for each required member `object` lacks and each member that is neither
// required nor optional (names starting with '_' are the user's notes and always allowed).
// Returns whether there was none.
bool check_members(const JsonValue& object, const std::string& path, std::initializer_list<const char*> required,
                   std::initializer_list<const char*> optional, ViolationList& problems);

}  // namespace meshik::constraints
