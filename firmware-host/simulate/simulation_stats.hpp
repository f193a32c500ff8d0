#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "control/controller_model.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

// How often and how long one limiter or constraint acted: `count` engagements
// (runs of consecutive ticks), `ticks` ticks in all.
struct Tally {
  std::uint64_t count = 0;
  std::uint64_t ticks = 0;
  bool active = false;
  void see(bool on) {
    if (on && !active) ++count;
    if (on) ++ticks;
    active = on;
  }
};

struct StateSpan {
  SafetyState state = SafetyState::kIdle;
  double start_s = 0.0, end_s = 0.0;
};

// Statistics of a simulation, gathered tick by tick without allocating
// (except when the safety state changes): per actuator the tracking error
// (command − simulated position) and each limiter's engagements; per face and
// actuator coupled constraint and for the face envelope, their engagements;
// the spans of each safety state.
class SimulationStats {
 public:
  struct Actuator {
    double sum_sq = 0.0;  // of the tracking error, SI²
    double max_abs = 0.0;
    double max_at_s = 0.0;
    std::array<Tally, kLimitFlagCount> limits{};  // by LimitFlag bit
  };

  explicit SimulationStats(const ControllerModel& model);

  // One tick at show time t: the controller's record and the simulated positions.
  void add(double t, const TelemetryRecord& r, std::span<const double> positions);
  void finish(double t);

  std::uint64_t ticks() const { return ticks_; }
  double rms(std::size_t actuator) const;
  const std::vector<Actuator>& actuators() const { return actuators_; }
  const std::vector<Tally>& face_constraints() const { return face_; }
  const std::vector<Tally>& actuator_constraints() const { return actuator_; }
  const Tally& envelope() const { return envelope_; }
  const std::vector<StateSpan>& states() const { return states_; }
  bool faulted() const;  // the head was in FAULT or ESTOP at some time

 private:
  std::vector<Actuator> actuators_;
  std::vector<Tally> face_, actuator_;
  Tally envelope_;
  std::vector<StateSpan> states_;
  std::uint64_t ticks_ = 0;
};

}  // namespace facectl
