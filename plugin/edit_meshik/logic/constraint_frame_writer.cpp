#include "constraint_frame_writer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace meshik::edit {
namespace {

// A JSON string literal for `text` (UTF-8 passes through; quotes, backslashes and control
// characters are escaped).
std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
      out += escaped;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

// The shortest decimal text that reads back as exactly `value` (finite).
std::string jsonNumber(double value) {
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

void check(const std::string& path, const DragFrame& frame) {
  const auto fail = [&path](const std::string& what) { throw ConstraintWriteError(path + ": " + what); };
  if (path.empty()) throw ConstraintWriteError("constraint file: no file name given");
  if (frame.rest_path.empty()) fail("the rest mesh has no file (save it first)");
  for (size_t i = 0; i < frame.example_paths.size(); ++i)
    if (frame.example_paths[i].empty()) fail("example " + std::to_string(i) + " has no file (save it first)");
  if (frame.example_paths.empty()) fail("no example mesh");
  if (frame.handles.empty()) fail("no handle");
  if (frame.targets.size() != 3 * frame.handles.size())
    fail("expected " + std::to_string(3 * frame.handles.size()) + " target coordinates, got " +
         std::to_string(frame.targets.size()));
  std::set<int> seen;
  for (size_t h = 0; h < frame.handles.size(); ++h) {
    if (frame.handles[h] < 0) fail("handle " + std::to_string(h) + " has a negative vertex index");
    if (!seen.insert(frame.handles[h]).second)
      fail("vertex " + std::to_string(frame.handles[h]) + " is a handle twice");
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(frame.targets[3 * h + k]))
        fail("the target of handle " + std::to_string(h) + " (vertex " + std::to_string(frame.handles[h]) +
             ") is not finite");
  }
  if (!(frame.weight_regularization >= 0.0 && std::isfinite(frame.weight_regularization)))
    fail("weight regularization must be a finite number >= 0");
  if (frame.max_iterations < 1) fail("max_iterations must be at least 1");
}

std::string documentText(const DragFrame& frame) {
  std::ostringstream out;
  out << "{\n \"format\": \"meshik-constraints\",\n \"version\": 1,\n";
  out << " \"rest\": " << jsonString(frame.rest_path) << ",\n \"examples\": [";
  for (size_t i = 0; i < frame.example_paths.size(); ++i)
    out << (i ? ", " : "") << jsonString(frame.example_paths[i]);
  out << "],\n \"feature_space\": \"" << (frame.linear_feature_space ? "linear" : "nonlinear") << "\",\n";
  out << " \"weight_regularization\": " << jsonNumber(frame.weight_regularization) << ",\n";
  out << " \"max_iterations\": " << frame.max_iterations << ",\n";
  out << " \"handles\": {" << jsonString(frame.group_name) << ": [";
  for (size_t h = 0; h < frame.handles.size(); ++h) out << (h ? ", " : "") << frame.handles[h];
  out << "]},\n \"frames\": [{\"name\": " << jsonString(frame.frame_name) << ", \"targets\": {"
      << jsonString(frame.group_name) << ": [";
  for (size_t h = 0; h < frame.handles.size(); ++h) {
    out << (h ? ",\n  " : "\n  ") << "[" << jsonNumber(frame.targets[3 * h]) << ", "
        << jsonNumber(frame.targets[3 * h + 1]) << ", " << jsonNumber(frame.targets[3 * h + 2]) << "]";
  }
  out << "\n ]}}]\n}\n";
  return out.str();
}

}  // namespace

void writeConstraintFrame(const std::string& path, const DragFrame& frame) {
  check(path, frame);
  const std::string text = documentText(frame);
  const std::string temporary = path + ".partial";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) {
      std::remove(temporary.c_str());
      throw ConstraintWriteError(path + ": cannot write the file");
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    std::remove(temporary.c_str());
    throw ConstraintWriteError(path + ": cannot replace the file");
  }
}

}  // namespace meshik::edit
