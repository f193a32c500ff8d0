#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace facectl {

// Bounds checked on a JSON input's text before it is parsed: nlohmann's
// dump() and copies recurse, so a file of 100 000 ['s would overflow the
// stack; and a parsed value costs some 20 times its text, so a 64 MiB file of
// empty objects would cost over a gigabyte. Real inputs nest 4 deep and hold
// a few containers per frame or cue.
inline constexpr std::size_t kMaxJsonDepth = 16;
inline constexpr std::size_t kMaxJsonContainers = 2'000'000;

// Throws ConfigError "file: expected JSON nested at most 16 deep, ..." (or
// with at most 2 000 000 lists and objects). Brackets inside strings do not count.
void check_json_shape(std::string_view text, const std::string& file);

// The input's text, shape-checked then parsed. Every failure is a
// ConfigError naming the file, and the line where the parser gives a place:
// "file:3: expected <what>, found text that is not JSON", or "file:3:
// expected numbers a double can hold, found '1e999'" (nlohmann throws
// out_of_range, not parse_error, for those).
nlohmann::json parse_json_input(std::string_view text, const std::string& file,
                                const std::string& what);

}  // namespace facectl
