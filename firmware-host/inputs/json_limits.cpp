#include "firmware-host/inputs/json_limits.hpp"

#include <algorithm>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

void check_json_shape(std::string_view text, const std::string& file) {
  std::size_t depth = 0, deepest = 0, containers = 0;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      ++containers;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  if (deepest > kMaxJsonDepth) {
    throw ConfigError(file + ": expected JSON nested at most " + std::to_string(kMaxJsonDepth) +
                      " deep, found deeper");
  }
  if (containers > kMaxJsonContainers) {
    throw ConfigError(file + ": expected JSON of at most " + std::to_string(kMaxJsonContainers) +
                      " lists and objects, found " + std::to_string(containers));
  }
}

}  // namespace facectl
