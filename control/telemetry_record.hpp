#pragma once

#include <array>
#include <cstdint>

#include "control/actuator_model.hpp"
#include "control/capacity.hpp"
#include "control/safety/safety_state.hpp"

namespace facectl {

// One tick as the logger thread writes it (docs/TELEMETRY.md gives the CSV
// columns). Fixed-size plain data so that it can sit in a preallocated ring.
struct TelemetryRecord {
  std::uint64_t tick = 0;
  double time_s = 0.0;          // since the loop started
  double dt_s = 0.0;            // measured duration since the previous tick
  double wake_latency_s = 0.0;  // how late the thread woke after its deadline
  double compute_s = 0.0;       // duration of the previous tick's work
  SafetyState state = SafetyState::kIdle;
  TransitionReason transition = TransitionReason::kNone;  // set on the tick that changed state
  bool input_stale = false;
  std::uint8_t envelope_flags = 0;  // FaceEnvelope::Flag bits
  std::uint32_t coupled_flags = 0;  // bit i: face coupled limit i was violated and projected
  double coupled_violation = 0.0;   // the largest violation before projection
  std::uint32_t actuator_coupled_flags = 0;  // bit i: actuator coupled limit i fired
  double actuator_coupled_violation = 0.0;   // its largest violation of the mapped targets
  std::uint32_t rejected_values = 0;         // sanitiser rejections on this tick
  std::uint32_t overruns = 0;                // consecutive overruns before this tick
  std::uint16_t signal_count = 0;
  std::uint16_t actuator_count = 0;
  std::array<double, kMaxFaceSignals> face{};      // shaped, enveloped command (SI)
  std::array<double, kMaxActuators> command{};     // limited actuator command (SI)
  std::array<double, kMaxActuators> feedback{};    // measured position (SI)
  std::array<LimitFlags, kMaxActuators> limits{};  // LimitFlag bits
};

}  // namespace facectl
