#include "facectl/face/yaml_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ios>
#include <system_error>
#include <vector>

#include "facectl/face/bounded_file.hpp"
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
  // yaml-cpp keeps about 64 bytes per byte of a list in memory: the bound
  // keeps a hostile file to about a gigabyte before anything parses it.
  const std::string text = read_bounded_file(path, kMaxYamlFileBytes, "YAML file");
  YAML::Node root;
  try {
    // All documents, so that a second one (after `---`) is refused rather
    // than silently ignored.
    std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (documents.size() > 1) {
      throw error_at(path, documents[1].Mark(),
                     "expected one YAML document, found " + std::to_string(documents.size()) +
                         " (a second begins here)");
    }
    if (!documents.empty()) root = documents[0];
  } catch (const YAML::ParserException& e) {
    throw error_at(path, e.mark, "YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) {
    throw error_at(path, root.Mark(),
                   "expected a YAML mapping at the top level, found " + found(root));
  }
  check_yaml_keys(path, root);
  return root;
}

}  // namespace facectl::face
