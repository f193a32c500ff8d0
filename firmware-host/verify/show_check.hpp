#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"

namespace facectl::verify {

// A run of consecutive ticks on which one mechanism acted on one subject.
struct Engagement {
  std::string kind;     // envelope, position, velocity, acceleration, jerk, approach,
                        // coupled (face), actuator coupled, mapping
  std::string subject;  // actuator, coupled limit, or "face"
  double start_s = 0.0, end_s = 0.0;
  double size = 0.0;  // largest |target − command| (actuator unit) or violation
  std::string unit;
};

// The ticks the controller spent outside IDLE, ENABLING, RUNNING and STOPPING
// (in FAULT or ESTOP): any one fails the show.
struct ShowFault {
  std::string state;        // of the first such tick: FAULT or ESTOP
  double at_s = 0.0;        // its show time (0 if the head faulted before the show began)
  std::string reason;       // the transition's reason and detail
  std::uint64_t ticks = 0;  // such ticks in all
};

struct ShowCheck {
  std::string show;
  double duration_s = 0.0;
  std::vector<Engagement> engagements;
  std::optional<ShowFault> fault;
  bool clean() const;         // nothing clamped or projected (limiter rate limits are listed too)
  bool passed() const;        // clean, and the head never left the live states
  std::string telemetry_csv;  // written when an output folder is given
  int plots = 0;
};

// Plays the show offline, in simulated time, through the whole pipeline of
// the rig's simulated twin, and lists every clamp, limiter engagement and
// coupled-limit activation with its time and size. With `out_dir`, writes the
// telemetry CSV and one SVG plot per actuator there.
ShowCheck check_show(const LoadedConfig& cfg, const std::string& show_path,
                     const std::string& out_dir);

}  // namespace facectl::verify
