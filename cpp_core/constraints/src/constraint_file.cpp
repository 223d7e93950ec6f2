// Reading, checking and validating constraint files (the entry points of constraint_file.h).
#include "meshik/constraints/constraint_file.h"

#include "document_reader.h"
#include "mesh_files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

namespace meshik::constraints {
namespace {

// The offset of the first byte of `text` that is not part of well-formed UTF-8 (no overlong
// forms, no surrogates, nothing above U+10FFFF), or npos.
std::size_t first_non_utf8_byte(std::string_view text) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char lead = bytes[i];
    std::size_t length = 0;
    unsigned char low = 0x80, high = 0xBF;  // the allowed range of the second byte
    if (lead < 0x80) length = 1;
    else if (lead >= 0xC2 && lead <= 0xDF) length = 2;
    else if (lead >= 0xE0 && lead <= 0xEF) length = 3, low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
    else if (lead >= 0xF0 && lead <= 0xF4) length = 4, low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
    else return i;
    for (std::size_t k = 1; k < length; ++k) {
      if (i + k >= text.size()) return i;
      const unsigned char byte = bytes[i + k];
      if (k == 1 ? (byte < low || byte > high) : (byte < 0x80 || byte > 0xBF)) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

// Constraint files larger than this are refused (a bound on memory, and on /dev/zero).
constexpr std::uintmax_t kMaxConstraintFileBytes = std::uintmax_t{1} << 30;

// The bytes of the file at `path`; ConstraintError when it is missing, not a regular file (a
// folder, device or FIFO, which could block or never end), larger than kMaxConstraintFileBytes,
// or unreadable.
std::string read_bytes(const std::string& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) throw ConstraintError(path + ": constraint file not found");
  if (std::filesystem::is_directory(status))
    throw ConstraintError(path + ": cannot read the constraint file: " + std::strerror(EISDIR));
  if (!std::filesystem::is_regular_file(status))
    throw ConstraintError(path + ": is not a regular file (a device, FIFO or socket), not a constraint file");
  if (std::filesystem::file_size(path, error) > kMaxConstraintFileBytes)
    throw ConstraintError(path + ": is larger than the 1 GiB accepted for a constraint file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!file) throw ConstraintError(path + ": cannot read the constraint file: " + std::strerror(errno));
  std::string bytes;
  char buffer[65536];
  std::size_t count = 0;
  while ((count = std::fread(buffer, 1, sizeof buffer, file.get())) > 0) {
    bytes.append(buffer, count);
    if (bytes.size() > kMaxConstraintFileBytes)
      throw ConstraintError(path + ": is larger than the 1 GiB accepted for a constraint file");
  }
  if (std::ferror(file.get())) throw ConstraintError(path + ": cannot read the constraint file: " + std::strerror(errno));
  return bytes;
}

// The result of checking constraint-file text: the document read (complete only when there is no
// problem), the problems as full messages, and whether the file's mesh names could be read.
struct CheckedText {
  ConstraintDocument document;
  std::vector<std::string> messages;
  bool mesh_names_read = false;  // "rest" and "examples" were read without a problem
};

// Checks constraint-file text. A syntax error (or a text that is not UTF-8) is the only problem
// reported; otherwise every rule the document breaks is.
CheckedText check_text(std::string_view text, const std::string& source) {
  CheckedText checked;
  const std::size_t bad_byte = first_non_utf8_byte(text);
  if (bad_byte != std::string_view::npos) {
    checked.messages.push_back(source + ": not UTF-8 text (byte " + std::to_string(bad_byte) + ")");
    return checked;
  }
  JsonValue top;
  try {
    top = parse_json(text);
  } catch (const JsonSyntaxError& error) {
    checked.messages.push_back(source + ": " + error.what());
    return checked;
  }
  ViolationList problems;
  checked.document = read_document(top, source, problems);
  checked.mesh_names_read = top.find("rest") && top.find("examples");
  for (const Violation& violation : problems.list()) {
    checked.messages.push_back(violation_message(source, violation));
    const std::string& path = violation.path;
    if (path == "" || path == "rest" || path.rfind("examples", 0) == 0) checked.mesh_names_read = false;
  }
  return checked;
}

}  // namespace

ConstraintDocument parse_constraints(std::string_view text, const std::string& source) {
  CheckedText checked = check_text(text, source);
  if (!checked.messages.empty()) throw ConstraintError(checked.messages.front());
  return std::move(checked.document);
}

ConstraintDocument read_constraint_file(const std::string& path) {
  return parse_constraints(read_bytes(path), path);
}

std::vector<std::string> validate_constraint_file(const std::string& path, bool check_mesh_files) {
  CheckedText checked;
  try {
    checked = check_text(read_bytes(path), path);
    if (check_mesh_files && checked.mesh_names_read)
      for (std::string& problem : mesh_file_problems(checked.document)) checked.messages.push_back(std::move(problem));
  } catch (const ConstraintError& error) {  // an unreadable file
    checked.messages.push_back(error.what());
  }
  return checked.messages;
}

std::int64_t find_frame(const ConstraintDocument& document, const std::string& frame) {
  const auto& frames = document.frames;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (frames[i].name == frame) return static_cast<std::int64_t>(i);
  std::size_t start = frame.find_first_not_of(" \t\r\n"), end = frame.find_last_not_of(" \t\r\n");
  const std::string number = start == std::string::npos ? "" : frame.substr(start, end - start + 1);
  if (!number.empty() && number.size() <= 9 && number.find_first_not_of("0123456789") == std::string::npos &&
      std::stoll(number) < static_cast<long long>(frames.size()))
    return std::stoll(number);
  throw ConstraintError(document.source + ": frames: no frame named or numbered \"" + frame + "\" (the file has " +
                        std::to_string(frames.size()) + " frames, numbered from 0, named " +
                        (frames.empty() ? std::string() : frames.front().name + " ... " + frames.back().name) + ")");
}

}  // namespace meshik::constraints
