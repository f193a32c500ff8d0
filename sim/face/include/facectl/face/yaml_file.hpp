// The one way facectl reads a YAML file: its own files, the face model's,
// shows, expressions and FAP tables alike.
#pragma once

#include <cstdint>
#include <string>

namespace YAML {
class Node;
}

namespace facectl::face {

// The largest YAML file facectl reads (docs/CONFIG.md, "Limits").
inline constexpr std::uintmax_t kMaxYamlFileBytes = 16u << 20;

// Loads `path` as a YAML mapping with plain, unique keys (check_yaml_keys).
// Throws InputError naming the file, and line:column where there is one, for
// a directory or other non-regular file, a file over kMaxYamlFileBytes,
// a second document, an unreadable file, a syntax error, an empty file or a top
// level that is not a mapping, so that no yaml-cpp or stream error escapes
// without the file's name.
YAML::Node load_yaml_file(const std::string& path);

}  // namespace facectl::face
