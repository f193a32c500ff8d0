#pragma once

#include <array>
#include <bit>
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
};

// Tallies for the bits of a flag word, counted by runs: a tick with the same
// flags as the tick before costs one comparison (the usual case); a run's
// ticks are added when it ends, by see() with other flags or by close().
template <std::size_t N>
struct FlagTallies {
  std::array<Tally, N> bits{};
  std::uint32_t previous = 0;
  std::uint64_t since = 0;  // the tick the run of `previous` began
  // The flags of tick `tick` (0, 1, 2, ..., in order).
  void see(std::uint32_t flags, std::uint64_t tick) {
    if (flags == previous) return;
    close(tick);
    const std::uint32_t rising = flags & ~previous;
    for (std::uint32_t f = rising; f != 0; f &= f - 1) ++bits[std::countr_zero(f)].count;
    previous = flags;
  }
  // Adds the ticks of the current run before `tick`.
  void close(std::uint64_t tick) {
    for (std::uint32_t f = previous; f != 0; f &= f - 1) {
      bits[std::countr_zero(f)].ticks += tick - since;
    }
    since = tick;
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
// the spans of each safety state. The tallies and the tracking figures
// (actuators(), rms()) are complete after finish().
class SimulationStats {
 public:
  struct Actuator {
    double sum_sq = 0.0;  // of the tracking error, SI²
    double max_abs = 0.0;
    double max_at_s = 0.0;
    FlagTallies<kLimitFlagCount> limits;  // by LimitFlag bit
  };

  explicit SimulationStats(const ControllerModel& model);

  // One tick at show time t: the controller's record and the simulated positions.
  void add(double t, const TelemetryRecord& r, std::span<const double> positions);
  // Closes the state spans and the tallies at the end of the run, show time t.
  void finish(double t);

  std::uint64_t ticks() const { return ticks_; }
  double rms(std::size_t actuator) const;
  const std::vector<Actuator>& actuators() const { return actuators_; }
  const Tally& face_constraint(std::size_t k) const { return face_.bits[k]; }
  const Tally& actuator_constraint(std::size_t k) const { return actuator_.bits[k]; }
  const Tally& envelope() const { return envelope_.bits[0]; }
  const std::vector<StateSpan>& states() const { return states_; }
  bool faulted() const;  // the head was in FAULT or ESTOP at some time

 private:
  std::vector<Actuator> actuators_;
  FlagTallies<CoupledConstraints::kMaxConstraints> face_, actuator_;
  FlagTallies<1> envelope_;  // any clamp
  // The tracking error per actuator while the run goes on, in arrays of their
  // own (copied into actuators_ by finish()) so that a tick reads them in order.
  std::array<double, kMaxActuators> sum_sq_{}, max_abs_{}, max_at_s_{};
  // The limiter flags of the tick before, to visit the actuators' tallies
  // only on the ticks some flag changed.
  std::array<LimitFlags, kMaxActuators> limits_before_{};
  std::vector<StateSpan> states_;
  std::uint64_t ticks_ = 0;
};

}  // namespace facectl
