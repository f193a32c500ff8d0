#include "facectl/face/yaml_file.hpp"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ios>
#include <sstream>
#include <string>
#include <system_error>

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

// Notes where each document starts; the events themselves are dropped, so a
// pass costs no memory however large the document.
class DocumentStarts : public YAML::EventHandler {
 public:
  YAML::Mark last;
  void OnDocumentStart(const YAML::Mark& at) override { last = at; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

// Refuses more YAML after the first document (after `---`, or a second
// node such as `[a] b`), which YAML::Load would silently ignore. At most
// three documents are asked for: on a token it cannot place (a `,` outside
// brackets) yaml-cpp 0.7 returns empty documents forever, each starting at
// that token, which is how YAML::LoadAll ran out of memory on `,"x`.
void check_one_document(const std::string& path, const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts starts;
  if (!parser.HandleNextDocument(starts)) return;
  if (!parser.HandleNextDocument(starts)) return;
  const YAML::Mark second = starts.last;
  // Marks only, never an index into `text`: after a byte-order mark or in
  // UTF-16, yaml-cpp's positions count the UTF-8 it converted to.
  if (parser.HandleNextDocument(starts) && starts.last.pos == second.pos) {
    throw error_at(path, second, "YAML syntax error: unexpected ',' outside [ ] or { }");
  }
  throw error_at(path, second, "expected one YAML document, found a second one here");
}

}  // namespace

YAML::Node load_yaml_file(const std::string& path) {
  // yaml-cpp keeps about 64 bytes per byte of a list in memory: the bound
  // keeps a hostile file to about a gigabyte before anything parses it.
  const std::string text = read_bounded_file(path, kMaxYamlFileBytes, "YAML file");
  YAML::Node root;
  try {
    root = YAML::Load(text);
    check_one_document(path, text);
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
