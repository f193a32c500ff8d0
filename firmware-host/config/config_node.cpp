#include "firmware-host/config/config_node.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "facectl/face/input_error.hpp"
#include "facectl/face/yaml_file.hpp"

namespace facectl {
namespace {

std::string position(const std::string& file, const YAML::Mark& mark) {
  std::ostringstream out;
  out << file;
  if (mark.line >= 0) out << ':' << mark.line + 1 << ':' << mark.column + 1;
  return out.str();
}

}  // namespace

ConfigNode::ConfigNode(const YAML::Node& node, std::shared_ptr<const std::string> file,
                       std::string path, YAML::Mark mark)
    : node_(node), file_(std::move(file)), path_(std::move(path)), mark_(mark) {}

ConfigNode ConfigNode::load_file(const std::string& path, std::string root_name) {
  YAML::Node root;
  try {
    root = face::load_yaml_file(path);
  } catch (const face::InputError& e) {
    throw ConfigError(e.what());
  }
  return ConfigNode(root, std::make_shared<const std::string>(path), std::move(root_name),
                    root.Mark());
}

std::string ConfigNode::where() const {
  return position(*file_, mark_);
}

ConfigNode ConfigNode::child(const YAML::Node& node, std::string path) const {
  YAML::Mark mark = node.Mark();
  if (mark.line < 0) mark = mark_;
  return ConfigNode(node, file_, std::move(path), mark);
}

bool ConfigNode::has(std::string_view key) const {
  return node_.IsMap() && node_[std::string(key)].IsDefined() && !node_[std::string(key)].IsNull();
}

std::optional<ConfigNode> ConfigNode::get(std::string_view key) const {
  if (!node_.IsMap()) fail("a mapping");
  const YAML::Node value = node_[std::string(key)];
  if (!value.IsDefined() || value.IsNull()) return std::nullopt;
  return child(value, path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

ConfigNode ConfigNode::operator[](std::string_view key) const {
  std::optional<ConfigNode> value = get(key);
  if (!value) fail("key '" + std::string(key) + "'", "no such key");
  return *value;
}

void ConfigNode::expect_keys(std::initializer_list<std::string_view> allowed) const {
  expect_keys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void ConfigNode::expect_keys(const std::vector<std::string>& allowed) const {
  if (!node_.IsMap()) fail("a mapping");
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();  // plain: load_file checked every key
    bool known = false;
    for (const auto& a : allowed) known = known || key == a;
    if (known) continue;
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    ConfigNode at = child(kv.first, path_.empty() ? key : path_ + "." + key);
    at.fail("one of: " + list, "unknown key '" + key + "'");
  }
}

std::vector<ConfigNode> ConfigNode::items() const {
  if (!node_.IsSequence()) fail("a sequence");
  std::vector<ConfigNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.push_back(child(node_[i], path_ + "[" + std::to_string(i) + "]"));
  }
  return out;
}

std::vector<std::pair<std::string, ConfigNode>> ConfigNode::entries() const {
  if (!node_.IsMap()) fail("a mapping");
  std::vector<std::pair<std::string, ConfigNode>> out;
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();  // plain: load_file checked every key
    ConfigNode value = child(kv.second, path_.empty() ? key : path_ + "." + key);
    if (kv.second.IsNull()) value.mark_ = kv.first.Mark();
    out.emplace_back(key, value);
  }
  return out;
}

std::string ConfigNode::found() const {
  if (!node_.IsDefined() || node_.IsNull()) return "nothing";
  if (node_.IsMap()) return "a mapping";
  if (node_.IsSequence()) return "a sequence";
  return "'" + node_.Scalar() + "'";
}

void ConfigNode::fail(std::string_view expected) const {
  fail(expected, found());
}

void ConfigNode::fail(std::string_view expected, std::string_view found_text) const {
  std::string message = where() + ": " + (path_.empty() ? std::string("<top>") : path_) +
                        ": expected " + std::string(expected) + ", found " +
                        std::string(found_text);
  throw ConfigError(message);
}

double ConfigNode::number() const {
  if (!node_.IsScalar()) fail("a number");
  double value = 0.0;
  if (!YAML::convert<double>::decode(node_, value) || !std::isfinite(value)) {
    fail("a finite number");
  }
  return value;
}

double ConfigNode::number_in(double lo, double hi) const {
  const double v = number();
  if (v < lo || v > hi) {
    std::ostringstream e;
    e << "a number in [" << lo << ", " << hi << "]";
    fail(e.str());
  }
  return v;
}

double ConfigNode::positive() const {
  const double v = number();
  if (!(v > 0.0)) fail("a number > 0");
  return v;
}

double ConfigNode::non_negative() const {
  const double v = number();
  if (v < 0.0) fail("a number >= 0");
  return v;
}

long ConfigNode::integer() const {
  if (!node_.IsScalar()) fail("an integer");
  long value = 0;
  if (!YAML::convert<long>::decode(node_, value)) fail("an integer");
  return value;
}

long ConfigNode::integer_in(long lo, long hi) const {
  const long v = integer();
  if (v < lo || v > hi) {
    fail("an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return v;
}

std::string ConfigNode::string() const {
  if (!node_.IsScalar()) fail("a string");
  return node_.Scalar();
}

bool ConfigNode::boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) fail("true or false");
  return value;
}

std::vector<std::string> ConfigNode::string_list() const {
  std::vector<std::string> out;
  for (const auto& item : items()) out.push_back(item.string());
  return out;
}

std::string resolve_path(const std::string& base_file, const std::string& relative) {
  const std::filesystem::path rel(relative);
  if (rel.is_absolute()) return rel.string();
  return (std::filesystem::path(base_file).parent_path() / rel).lexically_normal().string();
}

}  // namespace facectl
