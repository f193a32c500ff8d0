// Actuator coupled limits hold exactly (docs/SAFETY.md, "Actuator coupled
// limits"): a million ticks (a tenth when sanitized) of random, extreme and
// bang-bang face input, with late and early ticks, e-stops, shutdowns and
// FAULTs whose hold and rest reactions keep the mouth commanded, on a rig
// with four limits over five mouth actuators (three jerk-limited, shared
// actuators, both signs). No command may break a coupled limit, nor any
// actuator's own position, velocity or acceleration limits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/run/offline_head.hpp"
#include "tests/support/sample_count.hpp"

namespace facectl {
namespace {

// Two whole safety cycles (50 000 ticks each) when sanitized.
const long kTicks = testing::sample_count(1'000'000);
constexpr double kRel = 1e-9;  // floating-point tolerance, relative to the bound

LoadedConfig coupled_rig() {
  ConfigOverrides o;
  o.rig_path =
      std::string(FACECTL_SOURCE_DIR) + "/tests/firmware-host/verify/rigs/actuator_coupled.yaml";
  LoadedConfig cfg = load_config(default_config_path(), o);
  // A million ticks of bang-bang input would trip any servo's thermal model:
  // this test is about the control law (as verify's adversarial search).
  for (ActuatorConfig& a : cfg.rig.actuators) a.plant.thermal.trips = false;
  return cfg;
}

class Adversary {
 public:
  explicit Adversary(const ControllerModel& m) : m_(m), values_(m.neutral) {}

  // Segments of 1..300 ticks: uniform over each signal's whole domain,
  // extremes, bang-bang between extremes every tick, neutral, NaN bursts.
  const std::array<double, kMaxFaceSignals>& next() {
    if (left_ == 0) {
      left_ = 1 + rng_() % 300;
      mode_ = static_cast<int>(rng_() % 100);
      late_ = rng_() % 4 == 0;
      if (mode_ >= 30) draw();
    }
    --left_;
    if (mode_ < 30) draw();  // bang-bang
    return values_;
  }
  double dt(double period) {
    return late_ ? period * (0.2 + 3.0 * unit()) : period;  // late and early ticks
  }
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }

 private:
  void draw() {
    for (std::size_t i = 0; i < m_.layout.size(); ++i) {
      const SignalInfo& s = m_.layout.signal(i);
      if (mode_ < 70) {
        values_[i] = rng_() % 2 ? s.domain_max : s.domain_min;
      } else if (mode_ < 92) {
        values_[i] = s.domain_min + (s.domain_max - s.domain_min) * unit();
      } else if (mode_ < 97) {
        values_[i] = m_.neutral[i];
      } else {
        values_[i] = rng_() % 3 == 0 ? std::numeric_limits<double>::quiet_NaN() : m_.neutral[i];
      }
    }
  }

  const ControllerModel& m_;
  std::mt19937_64 rng_{20261122};
  std::array<double, kMaxFaceSignals> values_;
  std::uint64_t left_ = 0;
  int mode_ = 0;
  bool late_ = false;
};

TEST(ActuatorCoupledProperty, CoupledAndOwnLimitsHoldThroughAdversarialInputAndFaults) {
  OfflineHead head(coupled_rig(), 0, true);
  const ControllerModel& m = head.model();
  const CoupledConstraints& limits = m.actuator_constraints;
  ASSERT_EQ(limits.size(), 4u);
  const std::size_t n = m.actuators.size();
  // The mouth board's actuators hold or rest in FAULT; the neck board relaxes.
  const BusModel& mouth = m.buses[0];
  ASSERT_EQ(mouth.name, "mouth_board");

  Adversary adversary(m);
  Controller& c = head.controller();
  c.request_enable();
  std::array<double, kMaxActuators> prev_x{}, prev_v{};
  std::array<bool, kMaxActuators> prev_driven{};
  long coupled_violations = 0, own_violations = 0, checked = 0, fault_ticks = 0, bounded = 0;
  double worst_excess = -std::numeric_limits<double>::infinity();
  std::string first_violation;
  const auto report = [&](const std::string& what, long tick) {
    if (first_violation.empty()) first_violation = what + " at tick " + std::to_string(tick);
  };
  for (long t = 0; t < kTicks; ++t) {
    // Safety cycles every 50000 ticks: an overrun storm FAULT (everything
    // reacts), a neck-board FAULT (the mouth holds or rests), an e-stop and a
    // shutdown, each followed by a reset and a re-enable.
    const long phase = t % 50'000;
    int overruns = 0;
    if (phase == 10'000) overruns = 1000;
    if (phase == 20'000) head.hardware().find("neck_board")->inject_fault("board not answering");
    if (phase == 22'000) head.hardware().find("neck_board")->clear_fault();
    if (phase == 30'000) head.hardware().io.press_estop();
    if (phase == 30'200) head.hardware().io.release_estop();
    if (phase == 40'000) c.request_shutdown();
    if (phase == 12'000 || phase == 22'500 || phase == 30'500) c.request_reset();
    if (phase == 12'100 || phase == 22'600 || phase == 30'600 || phase == 42'000) {
      c.request_enable();
    }
    head.send(adversary.next());
    const double dt = adversary.dt(head.period());
    head.step(dt, overruns);

    const SafetyState s = c.state();
    const bool live =
        s == SafetyState::kEnabling || s == SafetyState::kRunning || s == SafetyState::kStopping;
    const bool holding = s == SafetyState::kFault && c.fault_holding();
    fault_ticks += holding ? 1 : 0;
    std::array<bool, kMaxActuators> driven{};
    for (std::size_t i = 0; i < n; ++i) {
      driven[i] = live || (holding && i >= mouth.first && i < mouth.first + mouth.count);
    }
    const auto& x = c.commands();
    if (live || holding) {
      for (std::size_t k = 0; k < limits.size(); ++k) {
        const double excess = limits.constraint(k).value(x.data()) - limits.constraint(k).bound;
        worst_excess = std::max(worst_excess, excess);
        if (excess > 1e-9) {
          ++coupled_violations;
          report(limits.constraint(k).name + " exceeded by " + std::to_string(excess), t);
        }
      }
    }
    for (std::size_t i = 0; i < n; ++i) {
      if ((c.limit_flags()[i] & kLimitCoupled) != 0) ++bounded;
      if (!driven[i] || !prev_driven[i]) continue;
      const ActuatorLimits& l = m.actuators[i].limits;
      const double v = (x[i] - prev_x[i]) / dt;
      const double a = (v - prev_v[i]) / dt;
      const bool in_range = x[i] >= l.soft_min - 1e-12 && x[i] <= l.soft_max + 1e-12;
      const bool slow = std::fabs(v) <= l.max_velocity * (1 + kRel) + 1e-9;
      const bool smooth = std::fabs(a) <= l.max_acceleration * (1 + kRel) + 1e-6;
      if (!in_range || !slow || !smooth) {
        ++own_violations;
        report(m.actuators[i].name + (in_range ? "" : " position") + (slow ? "" : " velocity") +
                   (smooth ? "" : " acceleration") + " (v " + std::to_string(v) + ", a " +
                   std::to_string(a) + ")",
               t);
      }
      ++checked;
    }
    for (std::size_t i = 0; i < n; ++i) {
      prev_v[i] = driven[i] && prev_driven[i] ? (x[i] - prev_x[i]) / dt : 0.0;
      prev_x[i] = x[i];
    }
    prev_driven = driven;
  }
  std::printf(
      "worst coupled excess %.3g (degree-units), %ld coupled violations, %ld own; "
      "%ld actuator-ticks bounded, %ld FAULT ticks holding, %ld actuator-ticks checked\n",
      worst_excess, coupled_violations, own_violations, bounded, fault_ticks, checked);
  EXPECT_EQ(coupled_violations, 0)
      << "worst excess " << worst_excess << "; first: " << first_violation;
  EXPECT_EQ(own_violations, 0) << "first: " << first_violation;
  EXPECT_EQ(c.counters().limit_breaches, 0u);
  // Not vacuous: the targets overran the limits, the bounds shaped many steps,
  // the mouth was held in FAULT, and most ticks were checked.
  EXPECT_GT(c.counters().actuator_coupled_projections, static_cast<std::uint64_t>(kTicks / 10));
  EXPECT_GT(bounded, kTicks / 20);
  EXPECT_GT(fault_ticks, kTicks / 50'000 * 2'000);
  EXPECT_GT(checked, static_cast<long>(n) * kTicks * 6 / 10);
}

}  // namespace
}  // namespace facectl
