#include "json_checks.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <set>

namespace meshik::constraints {
namespace {

// Whether `key` can follow a dot in a path: a letter or '_', then letters, digits, '_' or '-'.
bool is_identifier(const std::string& key) {
  if (key.empty() || !(std::isalpha(static_cast<unsigned char>(key[0])) || key[0] == '_')) return false;
  return std::all_of(key.begin(), key.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
}

// The shortest decimal digits that read back as `value` and its decimal exponent: 2.5 -> ("25", 0).
std::pair<std::string, int> shortest_digits(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::scientific);
  const std::string text(buffer, result.ptr);  // "-2.5e+00"
  const std::size_t e = text.find('e');
  std::string digits;
  for (std::size_t i = 0; i < e; ++i)
    if (std::isdigit(static_cast<unsigned char>(text[i]))) digits += text[i];
  return {digits, std::stoi(text.substr(e + 1))};
}

// A finite float written the way Python's repr() writes it: "2.5", "3.0", "1e-05", "1.5e+16".
std::string python_float_text(double value) {
  auto [digits, exponent] = shortest_digits(std::fabs(value));
  std::string text = std::signbit(value) ? "-" : "";
  if (exponent < -4 || exponent >= 16) {
    text += digits.substr(0, 1);
    if (digits.size() > 1) text += "." + digits.substr(1);
    char exp[16];
    std::snprintf(exp, sizeof exp, "e%c%02d", exponent < 0 ? '-' : '+', std::abs(exponent));
    return text + exp;
  }
  if (exponent < 0) return text + "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + digits;
  const std::size_t point = static_cast<std::size_t>(exponent) + 1;
  if (digits.size() <= point) return text + digits + std::string(point - digits.size(), '0') + ".0";
  return text + digits.substr(0, point) + "." + digits.substr(point);
}

// An integer literal's text without a sign on zero ("-0" -> "0").
std::string integer_text(const JsonValue& value) {
  return value.text == "-0" ? "0" : value.text;
}

}  // namespace

std::string child_path(const std::string& path, const std::string& key) {
  if (is_identifier(key)) return path.empty() ? key : path + "." + key;
  return path + "[" + quoted_text(key, key.size()) + "]";
}

std::string quoted_text(const std::string& text, std::size_t max_characters) {
  std::string quoted = "\"";
  std::size_t characters = 0;
  for (char c : text) {
    const bool starts_character = (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    if (starts_character && characters++ == max_characters) return quoted + "...\"";
    if (c == '\\' || c == '"') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      quoted += escaped;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

std::string child_path(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

std::size_t character_count(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

bool is_blank(const std::string& text) {
  return std::all_of(text.begin(), text.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

std::string format_general(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string describe(const JsonValue& value) {
  switch (value.kind) {
    case JsonValue::Kind::Null: return "null";
    case JsonValue::Kind::Bool: return value.boolean ? "true" : "false";
    case JsonValue::Kind::Number:
      return "the number " + (value.is_integer ? integer_text(value) : python_float_text(value.number));
    case JsonValue::Kind::String:
      return character_count(value.text) <= 40 ? quoted_text(value.text) : "a long string";
    case JsonValue::Kind::List: return "a list of " + std::to_string(value.elements.size());
    case JsonValue::Kind::Object: return "an object";
  }
  return "nothing";
}

const JsonValue* expect_object(const JsonValue& value, const std::string& path, ViolationList& problems) {
  if (value.kind == JsonValue::Kind::Object) return &value;
  problems.add(path, "expected an object, got " + describe(value));
  return nullptr;
}

const JsonValue* expect_list(const JsonValue& value, const std::string& path, ViolationList& problems,
                             bool non_empty) {
  if (value.kind != JsonValue::Kind::List) {
    problems.add(path, "expected a list, got " + describe(value));
    return nullptr;
  }
  if (non_empty && value.elements.empty()) {
    problems.add(path, "expected a non-empty list");
    return nullptr;
  }
  return &value;
}

std::optional<std::string> expect_string(const JsonValue& value, const std::string& path, ViolationList& problems) {
  if (value.kind != JsonValue::Kind::String) {
    problems.add(path, "expected a string, got " + describe(value));
    return std::nullopt;
  }
  if (is_blank(value.text)) {
    problems.add(path, "expected a non-empty string");
    return std::nullopt;
  }
  return value.text;
}

std::optional<double> expect_number(const JsonValue& value, const std::string& path, ViolationList& problems,
                                    double minimum, bool exclusive_minimum) {
  if (value.kind != JsonValue::Kind::Number) {
    problems.add(path, "expected a number, got " + describe(value));
    return std::nullopt;
  }
  if (!std::isfinite(value.number)) {  // an integer literal beyond the range of doubles
    problems.add(path, "number is too large");
    return std::nullopt;
  }
  if (value.number < minimum || (exclusive_minimum && value.number == minimum)) {
    problems.add(path, std::string("expected a number ") + (exclusive_minimum ? ">" : ">=") + " " +
                           format_general(minimum) + ", got " + format_general(value.number));
    return std::nullopt;
  }
  return value.number;
}

std::optional<std::int64_t> expect_int(const JsonValue& value, const std::string& path, ViolationList& problems,
                                       std::int64_t minimum, const std::string& what) {
  if (value.kind != JsonValue::Kind::Number || !value.is_integer) {
    problems.add(path, "expected " + what + ", got " + describe(value));
    return std::nullopt;
  }
  std::int64_t number = 0;
  const char* end = value.text.data() + value.text.size();
  const auto parsed = std::from_chars(value.text.data(), end, number);
  if (parsed.ec != std::errc() || parsed.ptr != end) {
    problems.add(path, "expected " + what + ", got " + integer_text(value) + ", which is too large");
    return std::nullopt;
  }
  if (number < minimum) {
    problems.add(path, "expected " + what + " >= " + std::to_string(minimum) + ", got " + std::to_string(number));
    return std::nullopt;
  }
  return number;
}

bool check_members(const JsonValue& object, const std::string& path, std::initializer_list<const char*> required,
                   std::initializer_list<const char*> optional, ViolationList& problems) {
  const std::size_t before = problems.size();
  for (const char* name : required)
    if (!object.find(name)) problems.add(path, std::string("missing member \"") + name + "\"");
  std::set<std::string> allowed(required.begin(), required.end());
  allowed.insert(optional.begin(), optional.end());
  for (const auto& member : object.members) {
    if (allowed.count(member.first) || member.first.rfind('_', 0) == 0) continue;
    std::string listed;
    for (const std::string& name : allowed) listed += (listed.empty() ? "" : ", ") + name;
    problems.add(child_path(path, member.first), "unknown member (expected one of: " + listed + ")");
  }
  return problems.size() == before;
}

}  // namespace meshik::constraints
