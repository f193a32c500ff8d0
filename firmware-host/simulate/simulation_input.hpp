#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/fap/fap_show.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {

// What `facectl simulate` plays: a show file or an MPEG-4 FAP file, both as
// face poses over time (SI, layout order). Loading throws ConfigError (a FAP
// file: FapFormatError) naming file:line:column; nothing is half loaded.
class SimulationInput {
 public:
  static SimulationInput load_show(const LoadedConfig& cfg, const std::string& path);
  static SimulationInput load_fap(const LoadedConfig& cfg, const std::string& path);
  static SimulationInput from_show(Show show);

  const std::string& name() const { return name_; }
  const char* kind() const { return show_ ? "show" : "fap"; }
  double duration() const { return show_ ? show_->duration() : fap_->duration(); }
  void evaluate(double t, std::array<double, kMaxFaceSignals>& out) const {
    if (show_) {
      show_->evaluate(t, out);
    } else {
      fap_->evaluate(t, out);
    }
  }
  // FAP clamps and ignored FAPs (FapShow::report()); empty for shows.
  std::vector<std::string> notes() const {
    return fap_ ? fap_->report() : std::vector<std::string>{};
  }

 private:
  std::string name_;
  std::optional<Show> show_;
  std::optional<FapShow> fap_;
};

}  // namespace facectl
