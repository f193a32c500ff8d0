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

// A mapping or sequence still to walk. Its key path is built only for a
// report, from the chain of parents: copying it into every entry would cost
// as much memory again as a large document.
struct Pending {
  YAML::Node node;
  std::size_t parent;  // index into KeyWalk::seen_, or kRoot
  YAML::Node key;      // its key, if its parent is a mapping
  std::size_t index;   // its place, if its parent is a sequence
  bool keyed;          // which of the two
};
constexpr std::size_t kRoot = static_cast<std::size_t>(-1);

struct Problem {
  YAML::Mark at;
  std::string what;
};

std::string describe(const YAML::Node& node) {
  if (node.IsSequence()) return "a sequence";
  if (node.IsMap()) return "a mapping";
  return "nothing";
}

// A walk over every mapping and sequence of a document, without recursion
// (nesting is as deep as yaml-cpp's parser allows).
class KeyWalk {
 public:
  explicit KeyWalk(const YAML::Node& root) {
    todo_.push_back({root, kRoot, YAML::Node(), 0, false});
  }

  // The problem earliest in the file, if any.
  std::optional<Problem> run() {
    std::vector<Pending> children;
    while (!todo_.empty()) {
      Pending entry = std::move(todo_.back());
      todo_.pop_back();
      if (!first_visit(entry.node)) continue;
      seen_.push_back(entry);
      const std::size_t self = seen_.size() - 1;
      children.clear();
      if (entry.node.IsMap()) {
        check_map(entry.node, self, children);
      } else {
        std::size_t i = 0;
        for (const auto& item : entry.node) {
          if (item.IsMap() || item.IsSequence())
            children.push_back({item, self, YAML::Node(), i, false});
          ++i;
        }
      }
      // Walked in file order, so that an alias is named by its anchor's path.
      // (Pushed, never swapped: assigning a YAML::Node writes into the node.)
      for (auto c = children.rbegin(); c != children.rend(); ++c) todo_.push_back(std::move(*c));
    }
    return first_;
  }

 private:
  void check_map(const YAML::Node& map, std::size_t self, std::vector<Pending>& children) {
    std::unordered_map<std::string, YAML::Mark> seen_keys;
    for (const auto& kv : map) {
      YAML::Mark at = kv.first.Mark();
      if (at.line < 0) at = map.Mark();  // an empty key (`? : 1`) has no place of its own
      if (!kv.first.IsScalar()) {
        report(at, path_of(self) + ": expected a plain name as mapping key, found " +
                       describe(kv.first));
        continue;
      }
      // yaml-cpp reads `<<` as an ordinary key, not as a merge: the keys it
      // means to bring in would be silently missing.
      if (kv.first.Scalar() == "<<" && kv.first.Tag() != "!") {
        report(at, path_of(self) + ": YAML merge keys (<<) are not supported; write the keys out");
        continue;
      }
      const auto [first, fresh] = seen_keys.emplace(kv.first.Scalar(), at);
      if (!fresh) {
        report(at, "duplicate key '" + joined(path_of(self), kv.first.Scalar()) +
                       "' (first at line " + std::to_string(first->second.line + 1) + ")");
      }
      if (kv.second.IsMap() || kv.second.IsSequence())
        children.push_back({kv.second, self, kv.first, 0, true});
    }
  }

  static std::string joined(const std::string& path, const std::string& key) {
    return path == "<top>" ? key : path + "." + key;
  }

  // The key path of seen_[at], e.g. `actuators[2].limits`; `<top>` for the root.
  std::string path_of(std::size_t at) const {
    std::vector<std::string> parts;
    for (std::size_t i = at; i != kRoot && seen_[i].parent != kRoot; i = seen_[i].parent) {
      const Pending& p = seen_[i];
      parts.push_back(p.keyed ? "." + p.key.Scalar() : "[" + std::to_string(p.index) + "]");
    }
    if (parts.empty()) return "<top>";
    std::string path;
    for (auto part = parts.rbegin(); part != parts.rend(); ++part) path += *part;
    return path[0] == '.' ? path.substr(1) : path;
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
  std::vector<Pending> seen_;  // every node walked, for the paths of reports
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
