#pragma once

#include <optional>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/inputs/input_format.hpp"
#include "firmware-host/inputs/pose_track.hpp"

namespace facectl {

// A recorded performance from another tool (capture, lip sync, FAP) as face
// poses over time, with what was read leniently or not shown (docs/INPUTS.md).
struct RecordedInput {
  std::string name;  // the FAP header's name, else the file's name
  InputFormat format = InputFormat::kFap;
  PoseTrack track;
  std::vector<std::string> notes;
};

// Reads `path` as `format`, or as the format its content shows. Throws
// ConfigError naming file:line for a file that is unusable, or whose format
// is neither given nor recognised. Shows are not read here (Show::load).
RecordedInput load_recorded_input(const LoadedConfig& cfg, const std::string& path,
                                  std::optional<InputFormat> format);

// The format `--format` names, or else the one `path`'s content shows.
InputFormat resolve_input_format(const std::string& path, const std::string& text,
                                 std::optional<InputFormat> format);

}  // namespace facectl
