// Property tests for the actuator limits and the mandible envelope: a million
// ticks of random and adversarial input never produce a command outside an
// actuator's position range or beyond its velocity and acceleration bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "control/limits/trajectory_limiter.hpp"
#include "tests/support/sample_count.hpp"
#include "tests/support/sim_head.hpp"

namespace facectl {
namespace {

// At least one whole e-stop and shutdown cycle (100 000 ticks) when sanitized.
const long kTicks = testing::sample_count(1'000'000);
constexpr double kRel = 1e-9;  // floating-point tolerance, relative to the bound

// Random targets (in and far out of range) and random tick lengths including
// late and early ticks, as an absolute-deadline loop produces.
TEST(LimitsProperty, LimiterKeepsEveryBoundUnderRandomTargetsAndJitteredTicks) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ActuatorLimits l;
  l.position_min = -1.0;
  l.position_max = 1.2;
  l.soft_min = -0.8;
  l.soft_max = 1.0;
  l.max_velocity = 3.0;
  l.max_acceleration = 80.0;
  LimiterState s;
  double target = 0.0;
  double prev_x = 0.0;
  double prev_v = 0.0;
  for (long i = 0; i < kTicks; ++i) {
    const double r = u(rng);
    if (r < 0.01)
      target = -5.0 + 10.0 * u(rng);  // step anywhere, often out of range
    else if (r < 0.02)
      target = u(rng) < 0.5 ? -1e30 : 1e30;  // absurd
    else if (r < 0.10)
      target = -target;  // rapid sign flips
    double dt = 0.001;
    const double j = u(rng);
    if (j < 0.01)
      dt = 0.001 * (1.0 + 20.0 * u(rng));  // late tick
    else if (j < 0.02)
      dt = 0.001 * (0.05 + 0.9 * u(rng));  // early tick after a late one
    limit_step(l, s, target, dt);

    ASSERT_GE(s.position, l.soft_min - 1e-12) << "tick " << i;
    ASSERT_LE(s.position, l.soft_max + 1e-12) << "tick " << i;
    const double v = (s.position - prev_x) / dt;
    ASSERT_LE(std::fabs(v), l.max_velocity * (1 + kRel) + 1e-9) << "tick " << i;
    const double a = (v - prev_v) / dt;
    ASSERT_LE(std::fabs(a), l.max_acceleration * (1 + kRel) + 1e-6) << "tick " << i;
    prev_x = s.position;
    prev_v = v;
  }
}

// The whole controller, fed adversarial face commands: NaN, ±inf, 1e30, steps,
// sign flips, through enable, e-stop, reset and shutdown cycles. Every
// actuator's command stays in its soft range and within its velocity and
// acceleration bounds (jerk-limited ones included); the mandible never leaves
// its envelope and the coupled face and actuator limits always hold.
TEST(LimitsProperty, ControllerKeepsActuatorsAndMandibleInsideTheirLimits) {
  testing::SimHead head;
  const ControllerModel& m = head.model();
  const std::size_t n_act = m.actuators.size();
  const std::size_t n_sig = m.layout.size();
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  head.controller().request_enable();
  std::array<double, kMaxFaceSignals> cmd = m.neutral;
  std::array<double, kMaxActuators> prev_x{};
  std::array<double, kMaxActuators> prev_v{};
  bool prev_enabled = false;
  long checked = 0;
  for (long i = 0; i < kTicks; ++i) {
    // Mutate the command.
    const double r = u(rng);
    if (r < 0.05) {
      const std::size_t k = static_cast<std::size_t>(u(rng) * static_cast<double>(n_sig));
      const double p = u(rng);
      if (p < 0.15)
        cmd[k] = nan;
      else if (p < 0.25)
        cmd[k] = u(rng) < 0.5 ? inf : -inf;
      else if (p < 0.35)
        cmd[k] = u(rng) < 0.5 ? 1e30 : -1e30;
      else if (p < 0.6)
        cmd[k] = -cmd[k];  // sign flip
      else
        cmd[k] = -2.0 + 4.0 * u(rng);  // step, often outside the envelope
    } else if (r < 0.06) {
      for (std::size_t k = 0; k < n_sig; ++k)
        cmd[k] = u(rng) < 0.5 ? 0.0 : 1.0;  // all-extreme step
    }
    if (u(rng) < 0.5) head.send(cmd);
    // Safety cycles: an e-stop and a shutdown every so often, then re-enable.
    if (i % 100000 == 30000) head.hardware().io.press_estop();
    if (i % 100000 == 30500) {
      head.hardware().io.release_estop();
      head.controller().request_reset();
    }
    if (i % 100000 == 31000 || i % 100000 == 61000) head.controller().request_enable();
    if (i % 100000 == 60000) head.controller().request_shutdown();
    const double dt = u(rng) < 0.01 ? 0.001 * (1 + 5 * u(rng)) : 0.001;
    head.step(dt);

    const Controller& c = head.controller();
    const auto& face = c.face();
    ASSERT_GE(face[m.layout.jaw_pitch()], m.envelope.pitch.min) << i;
    ASSERT_LE(face[m.layout.jaw_pitch()], m.envelope.pitch.max) << i;
    ASSERT_GE(face[m.layout.jaw_yaw()], m.envelope.yaw.min) << i;
    ASSERT_LE(face[m.layout.jaw_yaw()], m.envelope.yaw.max) << i;
    ASSERT_GE(face[m.layout.jaw_protrusion()], m.envelope.protrusion.min) << i;
    ASSERT_LE(face[m.layout.jaw_protrusion()], m.envelope.protrusion.max) << i;

    for (std::size_t k = 0; k < m.face_constraints.size(); ++k) {
      ASSERT_LE(m.face_constraints.constraint(k).value(face.data()),
                m.face_constraints.constraint(k).bound + 1e-9)
          << m.face_constraints.constraint(k).name << " tick " << i;
    }

    const bool enabled = c.state() == SafetyState::kEnabling ||
                         c.state() == SafetyState::kRunning || c.state() == SafetyState::kStopping;
    for (std::size_t k = 0; k < m.actuator_constraints.size() && enabled; ++k) {
      ASSERT_LE(m.actuator_constraints.constraint(k).value(c.commands().data()),
                m.actuator_constraints.constraint(k).bound + 1e-9)
          << m.actuator_constraints.constraint(k).name << " tick " << i;
    }
    for (std::size_t a = 0; a < n_act && enabled; ++a) {
      const ActuatorLimits& l = m.actuators[a].limits;
      const double x = c.commands()[a];
      ASSERT_GE(x, l.position_min) << m.actuators[a].name << " tick " << i;
      ASSERT_LE(x, l.position_max) << m.actuators[a].name << " tick " << i;
      if (!prev_enabled) continue;
      // After the first tick of an enable (which starts where the actuator
      // measured), the command stays in the soft range it converges into.
      const bool converged = prev_x[a] >= l.soft_min && prev_x[a] <= l.soft_max;
      if (converged) {
        ASSERT_GE(x, l.soft_min - 1e-12) << m.actuators[a].name << " tick " << i;
        ASSERT_LE(x, l.soft_max + 1e-12) << m.actuators[a].name << " tick " << i;
      }
      const double v = (x - prev_x[a]) / dt;
      const double acc = (v - prev_v[a]) / dt;
      ASSERT_LE(std::fabs(v), l.max_velocity * (1 + kRel) + 1e-9)
          << m.actuators[a].name << " tick " << i;
      ASSERT_LE(std::fabs(acc), l.max_acceleration * (1 + kRel) + 1e-6)
          << m.actuators[a].name << " tick " << i;
      ++checked;
    }
    for (std::size_t a = 0; a < n_act; ++a) {
      prev_v[a] = prev_enabled && enabled ? (c.commands()[a] - prev_x[a]) / dt : 0.0;
      prev_x[a] = c.commands()[a];
    }
    prev_enabled = enabled;
  }
  EXPECT_EQ(head.controller().counters().limit_breaches, 0u);
  EXPECT_GT(head.controller().sanitizer().rejected_total(), 1000u);  // the bad values were seen
  // Outputs are live for most of the run despite the safety cycles.
  EXPECT_GT(checked, static_cast<long>(n_act) * kTicks * 7 / 10);
}

}  // namespace
}  // namespace facectl
