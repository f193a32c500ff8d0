#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/inputs/input_format.hpp"
#include "firmware-host/inputs/pose_track.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {

// What `facectl simulate` plays: a show, or a recorded input (an MPEG-4 FAP
// file, a capture, lip sync; docs/INPUTS.md), both as face poses over time
// (SI, layout order). Loading throws ConfigError naming file:line:column;
// nothing is half loaded.
class SimulationInput {
 public:
  static SimulationInput load_show(const LoadedConfig& cfg, const std::string& path);
  static SimulationInput load_fap(const LoadedConfig& cfg, const std::string& path);
  // Any input file, in `format` or the one its content shows.
  static SimulationInput load_input(const LoadedConfig& cfg, const std::string& path,
                                    std::optional<InputFormat> format);
  static SimulationInput from_show(Show show);

  const std::string& name() const { return name_; }
  // "show", "fap", "live_link_face", ... (input_format_name).
  const char* kind() const { return input_format_name(format_); }
  double duration() const { return show_ ? show_->duration() : track_.duration(); }
  void evaluate(double t, std::array<double, kMaxFaceSignals>& out) const {
    if (show_) {
      show_->evaluate(t, out);
    } else {
      track_.evaluate(t, out);
    }
  }
  // What was read leniently, clamped or not shown; empty for shows.
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  std::string name_;
  InputFormat format_ = InputFormat::kShow;
  std::optional<Show> show_;
  PoseTrack track_;
  std::vector<std::string> notes_;
};

}  // namespace facectl
