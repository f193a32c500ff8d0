#include "drivers/hid/gamepad_mapping.hpp"

#include <cmath>

namespace facectl {

void GamepadMapping::apply(const GamepadState& state, std::span<double> pose) const {
  // First the offsets, so that terms on one signal add onto a clean base.
  for (const auto& t : terms_) {
    if (t.signal < pose.size()) pose[t.signal] = 0.0;
  }
  for (const auto& t : terms_) {
    if (t.signal >= pose.size()) continue;
    double v = 0.0;
    if (t.source == GamepadTerm::Source::kButton) {
      v = (state.buttons >> t.input) & 1u ? 1.0 : 0.0;
    } else if (t.input < kMaxGamepadAxes) {
      const double a = state.axes[t.input];
      const double mag = std::fabs(a);
      v = mag <= t.dead_zone ? 0.0 : std::copysign((mag - t.dead_zone) / (1.0 - t.dead_zone), a);
    }
    pose[t.signal] += t.offset + t.gain * v;
  }
}

}  // namespace facectl
