#include "facectl/face/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ios>
#include <system_error>
#include <vector>

#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_keys.hpp"

namespace facectl::face {
namespace {

// yaml-cpp places an empty document nowhere (line -1); its errors point at 1:1.
InputError error_at(const std::string& path, const YAML::Mark& at, const std::string& what) {
  if (at.line < 0) return InputError(path, 1, 1, what);
  return InputError(path, at.line + 1, at.column + 1, what);
}

std::string found(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a sequence";
  return "'" + node.Scalar() + "'";
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  // An ifstream opens a directory, and reading it throws basic_filebuf's
  // "underflow" error, which names no file; a FIFO or device may never end.
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(st)) {
    throw InputError(path + ": is a directory, expected a YAML file");
  }
  if (std::filesystem::exists(st) && !std::filesystem::is_regular_file(st)) {
    throw InputError(path + ": is not a regular file, expected a YAML file");
  }
  // yaml-cpp keeps about 64 bytes per byte of a list in memory: the bound
  // keeps a hostile file to about a gigabyte before anything reads it.
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxYamlFileBytes) {
    throw InputError(path + ": file is " + std::to_string(size) + " bytes, expected at most " +
                     std::to_string(kMaxYamlFileBytes) + " for a YAML file");
  }
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file (expected a readable YAML file)");
  YAML::Node root;
  try {
    // All documents, so that a second one (after `---`) is refused rather
    // than silently ignored.
    std::vector<YAML::Node> documents = YAML::LoadAll(in);
    if (documents.size() > 1) {
      throw error_at(path, documents[1].Mark(),
                     "expected one YAML document, found " + std::to_string(documents.size()) +
                         " (a second begins here)");
    }
    if (!documents.empty()) root = documents[0];
  } catch (const YAML::ParserException& e) {
    throw error_at(path, e.mark, "YAML syntax error: " + e.msg);
  } catch (const std::ios_base::failure& e) {
    throw InputError(path + ": cannot read file (" + e.what() + ")");
  }
  if (!root.IsMap()) {
    throw error_at(path, root.Mark(),
                   "expected a YAML mapping at the top level, found " + found(root));
  }
  check_yaml_keys(path, root);
  return root;
}

}  // namespace facectl::face
