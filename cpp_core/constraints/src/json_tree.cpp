#include "json_tree.h"

#include "json_checks.h"

#include <nlohmann/json.hpp>

#include <unordered_set>

namespace meshik::constraints {
namespace {

using Json = nlohmann::json;

// Builds a JsonValue tree from nlohmann's SAX events. Open lists and objects wait on a stack;
// each object remembers its JSON path (for the duplicate-key message).
class TreeBuilder : public nlohmann::json_sax<Json> {
 public:
  explicit TreeBuilder(std::string_view text) : text_(text) {}

  JsonValue take_root() { return std::move(root_); }
  const std::string& failure() const { return failure_; }

  bool null() override { return add(JsonValue{}); }
  bool boolean(bool value) override {
    JsonValue v;
    v.kind = JsonValue::Kind::Bool;
    v.boolean = value;
    return add(std::move(v));
  }
  bool number_integer(number_integer_t value) override {
    return add(number(static_cast<double>(value), std::to_string(value), true));
  }
  bool number_unsigned(number_unsigned_t value) override {
    return add(number(static_cast<double>(value), std::to_string(value), true));
  }
  bool number_float(number_float_t value, const string_t& literal) override {
    const bool integer = literal.find_first_of(".eE") == std::string::npos;
    return add(number(value, literal, integer));
  }
  bool string(string_t& value) override {
    JsonValue v;
    v.kind = JsonValue::Kind::String;
    v.text = std::move(value);
    return add(std::move(v));
  }
  bool binary(binary_t&) override { return false; }  // not produced by the JSON text parser
  bool start_object(std::size_t) override { return open(JsonValue::Kind::Object); }
  bool key(string_t& name) override {
    Open& object = open_.back();
    if (!object.keys.insert(name).second) {  // a hash set: 100,000 members are checked in linear time
      failure_ = child_path(object.path, name) + ": duplicate key";
      return false;
    }
    object.key = std::move(name);
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(JsonValue::Kind::List); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t position, const std::string& last_token,
                   const nlohmann::detail::exception& error) override {
    // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 1, column 2:
    // syntax error while ...; last read: '<token>'; expected ..."; keep the reason without the
    // token (the line and column point at it), and count the column in characters.
    std::string reason = error.what();
    const std::size_t colon = reason.find(": ", reason.find("parse error at line"));
    if (reason.rfind("[json.exception.", 0) == 0) {
      const std::size_t start = colon != std::string::npos ? colon + 2 : reason.find(']') + 2;
      reason = reason.substr(std::min(start, reason.size()));
    }
    const std::string token = "; last read: '" + last_token + "'";
    const std::size_t at = reason.find(token);
    if (at != std::string::npos) reason.erase(at, token.size());
    const auto [line, column] = line_and_column(text_, position > 0 ? position - 1 : 0);
    failure_ = "not valid JSON: line " + std::to_string(line) + " column " + std::to_string(column) + ": " + reason;
    return false;
  }

 private:
  struct Open {
    JsonValue value;
    std::string path;  // JSON path of this list or object
    std::string key;   // the pending member name (objects)
    std::unordered_set<std::string> keys;  // every member name so far (objects)
  };

  static JsonValue number(double value, std::string literal, bool integer) {
    JsonValue v;
    v.kind = JsonValue::Kind::Number;
    v.number = value;
    v.is_integer = integer;
    v.text = std::move(literal);
    return v;
  }

  // The JSON path of the next value added to the innermost open list or object.
  std::string next_path() const {
    if (open_.empty()) return "";
    const Open& parent = open_.back();
    if (parent.value.kind == JsonValue::Kind::Object) return child_path(parent.path, parent.key);
    return child_path(parent.path, parent.value.elements.size());
  }

  bool add(JsonValue value) {
    if (open_.empty()) {
      root_ = std::move(value);
      return true;
    }
    Open& parent = open_.back();
    if (parent.value.kind == JsonValue::Kind::Object)
      parent.value.members.emplace_back(std::move(parent.key), std::move(value));
    else
      parent.value.elements.push_back(std::move(value));
    return true;
  }

  bool open(JsonValue::Kind kind) {
    if (open_.size() >= kMaxJsonDepth) {
      failure_ = "JSON nested too deeply";
      return false;
    }
    std::string path = next_path();
    open_.push_back(Open{JsonValue{}, std::move(path), {}});
    open_.back().value.kind = kind;
    return true;
  }

  bool close() {
    JsonValue done = std::move(open_.back().value);
    open_.pop_back();
    return add(std::move(done));
  }

  std::string_view text_;
  std::vector<Open> open_;
  JsonValue root_;
  std::string failure_;
};

}  // namespace

const JsonValue* JsonValue::find(std::string_view key) const {
  for (const auto& member : members)
    if (member.first == key) return &member.second;
  return nullptr;
}

std::pair<std::size_t, std::size_t> line_and_column(std::string_view text, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {  // not a UTF-8 continuation byte
      ++column;
    }
  }
  return {line, column};
}

JsonValue parse_json(std::string_view text) {
  TreeBuilder builder(text);
  const bool parsed = Json::sax_parse(text.begin(), text.end(), &builder, nlohmann::detail::input_format_t::json,
                                      /*strict=*/true, /*ignore_comments=*/false);
  if (!parsed) throw JsonSyntaxError(builder.failure().empty() ? "not valid JSON" : builder.failure());
  return builder.take_root();
}

}  // namespace meshik::constraints
