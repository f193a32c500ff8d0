#pragma once

#include <yaml-cpp/yaml.h>

#include <initializer_list>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace facectl {

// A configuration or input file is unusable. The message names
// file:line:column, the key, what was expected and what was found.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A YAML node that remembers where it came from, so that every error can say
// file:line:column and the key path (e.g. rig.actuators[3].max_velocity_deg_s).
class ConfigNode {
 public:
  static ConfigNode load_file(const std::string& path, std::string root_name);

  const std::string& file() const { return *file_; }
  const std::string& path() const { return path_; }
  std::string where() const;  // file:line:column

  bool has(std::string_view key) const;
  ConfigNode operator[](std::string_view key) const;  // required
  std::optional<ConfigNode> get(std::string_view key) const;
  // Rejects keys outside `allowed`, so that typos do not silently fall back to defaults.
  void expect_keys(std::initializer_list<std::string_view> allowed) const;
  void expect_keys(const std::vector<std::string>& allowed) const;

  std::vector<ConfigNode> items() const;                            // a sequence
  std::vector<std::pair<std::string, ConfigNode>> entries() const;  // a mapping, in file order
  bool is_map() const { return node_.IsMap(); }

  double number() const;  // finite
  double number_in(double lo, double hi) const;
  double positive() const;
  double non_negative() const;
  long integer() const;
  long integer_in(long lo, long hi) const;
  std::string string() const;
  bool boolean() const;
  std::vector<std::string> string_list() const;

  [[noreturn]] void fail(std::string_view expected) const;
  [[noreturn]] void fail(std::string_view expected, std::string_view found) const;
  std::string found() const;  // a short description of what is here

 private:
  ConfigNode(const YAML::Node& node, std::shared_ptr<const std::string> file, std::string path,
             YAML::Mark mark);
  ConfigNode child(const YAML::Node& node, std::string path) const;

  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;
  YAML::Mark mark_;
};

// Resolves `relative` against the folder of `base_file` (absolute paths stay).
std::string resolve_path(const std::string& base_file, const std::string& relative);

}  // namespace facectl
