#include "firmware-host/inputs/json_input.hpp"

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

namespace {

int line_at(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + offset, '\n'));
}

}  // namespace

nlohmann::json parse_json_input(std::string_view text, const std::string& file,
                                const std::string& what) {
  check_json_shape(text, file);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is one past the offending character.
    const std::size_t at = e.byte == 0 ? 0 : e.byte - 1;
    throw ConfigError(file + ":" + std::to_string(line_at(text, at)) + ": expected " + what +
                      ", found text that is not JSON");
  } catch (const nlohmann::json::out_of_range& e) {
    // "number overflow parsing '1e999'": no offset, so find the number.
    const std::string message = e.what();
    const auto open = message.find('\'');
    const auto close = message.rfind('\'');
    const std::string number =
        open < close ? message.substr(open + 1, close - open - 1) : std::string("a number");
    throw ConfigError(file + ":" + std::to_string(line_at(text, text.find(number))) +
                      ": expected numbers a double can hold, found '" + number.substr(0, 60) + "'");
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError(file + ": expected " + what + ", found JSON the parser refuses (" + e.what() +
                      ")");
  }
}

}  // namespace facectl
