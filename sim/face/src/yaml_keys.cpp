#include "facectl/face/yaml_keys.hpp"

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include "facectl/face/input_error.hpp"

namespace facectl::face {
namespace {

using Pending = std::pair<YAML::Node, std::string>;  // a node and its key path

struct Problem {
  YAML::Mark at;
  std::string what;
};

// A walk over every mapping and sequence of a document, without recursion
// (nesting is as deep as yaml-cpp's parser allows).
class KeyWalk {
 public:
  explicit KeyWalk(const YAML::Node& root) { todo_.emplace_back(root, ""); }

  // The problem earliest in the file, if any.
  std::optional<Problem> run() {
    while (!todo_.empty()) {
      auto [node, path] = std::move(todo_.back());
      todo_.pop_back();
      if (!(node.IsMap() || node.IsSequence()) || !first_visit(node)) continue;
      std::vector<Pending> children;
      if (node.IsMap()) {
        check_map(node, path, children);
      } else {
        std::size_t i = 0;
        for (const auto& item : node)
          children.emplace_back(item, path + "[" + std::to_string(i++) + "]");
      }
      // Walked in file order, so that an alias is named by its anchor's path.
      // (Pushed, never swapped: assigning a YAML::Node writes into the node.)
      for (auto c = children.rbegin(); c != children.rend(); ++c) todo_.push_back(std::move(*c));
    }
    return first_;
  }

 private:
  void check_map(const YAML::Node& map, const std::string& path, std::vector<Pending>& children) {
    std::unordered_map<std::string, YAML::Mark> seen_keys;
    for (const auto& kv : map) {
      YAML::Mark at = kv.first.Mark();
      if (at.line < 0) at = map.Mark();  // an empty key (`? : 1`) has no place of its own
      if (!kv.first.IsScalar()) {
        const char* found = kv.first.IsSequence() ? "a sequence"
                            : kv.first.IsMap()    ? "a mapping"
                                                  : "nothing";
        report(at, (path.empty() ? "<top>" : path) +
                       ": a mapping key must be a plain name, found " + found);
        continue;
      }
      const std::string key = path.empty() ? kv.first.Scalar() : path + "." + kv.first.Scalar();
      const auto [first, fresh] = seen_keys.emplace(kv.first.Scalar(), at);
      if (!fresh) {
        report(at, "duplicate key '" + key + "' (first at line " +
                       std::to_string(first->second.line + 1) + ")");
      }
      children.emplace_back(kv.second, key);
    }
  }

  // An alias is the very node it names: walk it once, not once per use.
  bool first_visit(const YAML::Node& node) {
    std::vector<YAML::Node>& here = visited_[node.Mark().pos];
    for (const YAML::Node& v : here) {
      if (v.is(node)) return false;
    }
    here.push_back(node);
    return true;
  }

  void report(const YAML::Mark& at, std::string what) {
    if (!first_ || at.pos < first_->at.pos) first_ = Problem{at, std::move(what)};
  }

  std::vector<Pending> todo_;
  std::unordered_map<int, std::vector<YAML::Node>> visited_;  // by position in the file
  std::optional<Problem> first_;
};

}  // namespace

void check_yaml_keys(const std::string& file, const YAML::Node& root) {
  if (const std::optional<Problem> p = KeyWalk(root).run()) {
    throw InputError(file, p->at.line + 1, p->at.column + 1, p->what);
  }
}

}  // namespace facectl::face
