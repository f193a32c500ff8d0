#pragma once

#include <array>
#include <functional>
#include <span>

#include "firmware-host/run/offline_head.hpp"
#include "firmware-host/simulate/simulation_input.hpp"

namespace facectl {

// How long run_simulation waits for the head to reach RUNNING.
inline constexpr double kSimulateEnableTimeoutS = 30.0;

class SimulationStats;
class DecimatedTelemetry;
class ActuatorPlots;
class ProgressBar;

// Where each tick of a simulation goes; every sink is optional.
struct SimulationSinks {
  SimulationStats* stats = nullptr;
  DecimatedTelemetry* telemetry = nullptr;
  ActuatorPlots* plots = nullptr;
  ProgressBar* progress = nullptr;
  // Called every 1/frame_rate_hz of show time with the face command and the
  // simulated actuator positions (the render sequence).
  std::function<void(std::span<const double>, std::span<const double>)> frame;
  double frame_rate_hz = 25.0;
};

struct SimulationRun {
  double enable_s = 0.0;               // simulated time from enable request to RUNNING
  double clock_at_show_start_s = 0.0;  // the head's clock (OfflineHead::time()) at show time 0
  double show_s = 0.0;                 // simulated time the show played
  std::uint64_t ticks = 0;             // ticks while the show played
  bool enabled = false;                // the head reached RUNNING
};

// Enables the head on its neutral pose (as `facectl run` does, in simulated
// time), then plays `input` for `duration_s` of show time (looping it if that
// is longer than the input), publishing a pose at the runtime config's show
// rate and stepping the head's Controller at its own rate. Show time 0 is the
// tick the head was RUNNING. Allocates nothing per tick beyond what the sinks do.
SimulationRun run_simulation(OfflineHead& head, const SimulationInput& input, double duration_s,
                             const SimulationSinks& sinks);

}  // namespace facectl
