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
  // Drive-level protection (docs/SAFETY.md), per actuator; the writers list
  // the actuators whose bit is set here (those with a `protection` block).
  // float: a reading's precision, and half the bytes in the ring.
  std::uint64_t protected_mask = 0;
  std::array<float, kMaxActuators> temperature_c{};  // NaN: not reported
  std::array<float, kMaxActuators> load{};           // fraction of max torque
  std::array<float, kMaxActuators> current_a{};
  std::array<float, kMaxActuators> voltage_v{};
  std::array<std::uint32_t, kMaxActuators> hardware_error{};
  std::array<float, kMaxActuators> derate{};             // factor on the command, 1 = none
  std::array<float, kMaxActuators> extreme_s{};          // continuous time in the extreme band
  std::array<std::uint8_t, kMaxActuators> protection{};  // ProtectionMode
};

}  // namespace facectl
