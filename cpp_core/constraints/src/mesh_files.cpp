// locate_mesh_files and mesh_file_problems: the rest and example meshes a constraint document
// names, found on disk.
#include "mesh_files.h"

#include "json_checks.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

namespace meshik::constraints {
namespace fs = std::filesystem;
namespace {

// "<source>: <path>: <problem>" as a ConstraintError.
ConstraintError error_at(const ConstraintDocument& document, const std::string& path, const std::string& problem) {
  return ConstraintError(document.source + ": " + path + ": " + problem);
}

// `name` taken from `base` (unless absolute), made absolute with symbolic links resolved.
fs::path absolute_path(const fs::path& base, const std::string& name) {
  return fs::weakly_canonical(fs::absolute(base / name));
}

// The absolute path of the existing file `name`; ConstraintError at `path` otherwise.
std::string existing_file(const ConstraintDocument& document, const fs::path& base, const std::string& name,
                          const std::string& path) {
  if (name.find('\0') != std::string::npos)
    throw error_at(document, path, "the file name " + quoted_text(name) + " contains a NUL character");
  fs::path resolved;
  fs::file_type type = fs::file_type::none;
  try {
    resolved = absolute_path(base, name);
    type = fs::status(resolved).type();
  } catch (const fs::filesystem_error& error) {
    throw error_at(document, path, std::string("unusable file name: ") + error.what());
  }
  if (type == fs::file_type::not_found) throw error_at(document, path, "mesh file not found: " + resolved.string());
  if (type == fs::file_type::directory) throw error_at(document, path, "is a folder, not a mesh file: " + resolved.string());
  if (type != fs::file_type::regular)
    throw error_at(document, path, "is not a regular file (a device, FIFO or socket), not a mesh file: " + resolved.string());
  return resolved.string();
}

// Whether `a` sorts before `b` with runs of digits compared as numbers ("pose2" before "pose10").
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool digit_a = std::isdigit(static_cast<unsigned char>(a[i])), digit_b = std::isdigit(static_cast<unsigned char>(b[j]));
    if (digit_a && digit_b) {
      std::size_t end_a = i, end_b = j;
      while (end_a < a.size() && std::isdigit(static_cast<unsigned char>(a[end_a]))) ++end_a;
      while (end_b < b.size() && std::isdigit(static_cast<unsigned char>(b[end_b]))) ++end_b;
      std::string number_a = a.substr(i, end_a - i), number_b = b.substr(j, end_b - j);
      number_a.erase(0, std::min(number_a.find_first_not_of('0'), number_a.size() - 1));
      number_b.erase(0, std::min(number_b.find_first_not_of('0'), number_b.size() - 1));
      if (number_a.size() != number_b.size()) return number_a.size() < number_b.size();
      if (number_a != number_b) return number_a < number_b;
      i = end_a, j = end_b;
    } else if (digit_a != digit_b) {
      return digit_a;  // a number sorts before text
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// The files matching `pattern` (relative to `base`), the rest mesh left out, sorted naturally.
std::vector<std::string> glob_files(const ConstraintDocument& document, const fs::path& base, const std::string& pattern,
                                    const std::string& rest) {
  std::set<std::string> matches;
  try {
    if (pattern.find('\0') != std::string::npos) throw fs::filesystem_error("embedded null byte", std::error_code());
    glob_t found{};
    const int status = ::glob((base / pattern).c_str(), 0, nullptr, &found);
    for (std::size_t i = 0; status == 0 && i < found.gl_pathc; ++i) {
      const fs::path match = fs::weakly_canonical(fs::absolute(found.gl_pathv[i]));
      if (fs::is_regular_file(match) && match.string() != rest) matches.insert(match.string());
    }
    globfree(&found);
  } catch (const fs::filesystem_error& error) {
    throw error_at(document, "examples", std::string("unusable glob pattern: ") + error.what());
  }
  if (matches.empty())
    throw error_at(document, "examples", "glob \"" + pattern + "\" matches no mesh file besides the rest mesh (in " +
                                             base.string() + ")");
  std::vector<std::string> sorted(matches.begin(), matches.end());
  std::sort(sorted.begin(), sorted.end(), natural_less);
  return sorted;
}

}  // namespace

std::vector<std::string> mesh_file_problems(const ConstraintDocument& document) {
  std::vector<std::string> problems;
  const fs::path base = fs::path(document.source).parent_path();
  std::string rest;
  try {
    rest = existing_file(document, base, document.rest, "rest");
  } catch (const ConstraintError& error) {
    problems.push_back(error.what());
  }
  try {
    if (document.examples_glob) glob_files(document, base, *document.examples_glob, rest);
  } catch (const ConstraintError& error) {
    problems.push_back(error.what());
  }
  for (std::size_t i = 0; i < document.examples.size(); ++i) try {
      existing_file(document, base, document.examples[i], "examples[" + std::to_string(i) + "]");
    } catch (const ConstraintError& error) {
      problems.push_back(error.what());
    }
  return problems;
}

MeshFiles locate_mesh_files(const ConstraintDocument& document) {
  const fs::path base = fs::path(document.source).parent_path();
  MeshFiles files;
  files.rest = existing_file(document, base, document.rest, "rest");
  if (document.examples_glob) {
    files.examples = glob_files(document, base, *document.examples_glob, files.rest);
    return files;
  }
  for (std::size_t i = 0; i < document.examples.size(); ++i)
    files.examples.push_back(
        existing_file(document, base, document.examples[i], "examples[" + std::to_string(i) + "]"));
  return files;
}

}  // namespace meshik::constraints
