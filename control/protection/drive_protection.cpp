#include "control/protection/drive_protection.hpp"

#include <algorithm>
#include <cmath>

namespace facectl {
namespace {

// Time spent past a threshold, continuously; NaN is never past.
double past(double value, double threshold, double timer, double dt) {
  return value >= threshold ? timer + dt : 0.0;
}

// 1 at the derate threshold, falling linearly to `floor` at the fault one.
double derate_factor(const ProtectionLimit& lim, double value, double floor) {
  if (!(value > lim.derate)) return 1.0;
  const double u = std::min((value - lim.derate) / (lim.fault - lim.derate), 1.0);
  return 1.0 - u * (1.0 - floor);
}

}  // namespace

bool step_protection(const DriveProtection& p, const ActuatorLimits& l, const ActuatorHealth& h,
                     double measured, bool powered, double dt, ProtectionState& s) {
  if (!p.configured || s.mode == ProtectionMode::kFault || !(dt > 0.0)) return false;
  const ProtectionLimit* limits[3] = {&p.temperature_c, &p.load, &p.current_a};
  const double values[3] = {h.temperature_c, std::fabs(h.load), std::fabs(h.current_a)};
  constexpr ProtectionCause causes[3] = {ProtectionCause::kTemperature, ProtectionCause::kLoad,
                                         ProtectionCause::kCurrent};
  auto fault = [&](ProtectionCause c, double v) {
    s.mode = ProtectionMode::kFault;
    s.cause = c;
    s.value_at_fault = v;
    return true;
  };
  if (p.faults && (h.hardware_error & p.hardware_error_mask) != 0) {
    return fault(ProtectionCause::kHardwareError, static_cast<double>(h.hardware_error));
  }
  double target = 1.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const ProtectionLimit& lim = *limits[k];
    if (!lim.configured()) continue;
    s.over_derate_s[k] = past(values[k], lim.derate, s.over_derate_s[k], dt);
    s.over_fault_s[k] = past(values[k], lim.fault, s.over_fault_s[k], dt);
    if (p.faults && s.over_fault_s[k] >= p.hold_s) return fault(causes[k], values[k]);
    if (s.over_derate_s[k] >= p.hold_s) {
      target = std::min(target, derate_factor(lim, values[k], p.derate_floor));
    }
  }
  const double v = h.voltage_v;
  s.voltage_bad_s = v < p.voltage_min_v || v > p.voltage_max_v ? s.voltage_bad_s + dt : 0.0;
  if (p.faults && s.voltage_bad_s >= p.hold_s) return fault(ProtectionCause::kVoltage, v);
  // Down at once (the limiter makes it bumpless), up slowly.
  s.factor = target < s.factor ? target : std::min(target, s.factor + dt / p.recover_s);

  if (p.extreme_band > 0.0 && p.extreme_budget_s > 0.0) {
    const bool in_band = powered && (measured <= l.position_min + p.extreme_band ||
                                     measured >= l.position_max - p.extreme_band);
    s.in_band_s = in_band ? s.in_band_s + dt : 0.0;
    if (s.cooldown_left_s > 0.0) {
      s.cooldown_left_s = std::max(0.0, s.cooldown_left_s - dt);
      // The command left the band a whole budget ago and the actuator is
      // still in it: it is stuck or pushed there.
      if (p.faults && s.in_band_s > 2.0 * p.extreme_budget_s)
        return fault(ProtectionCause::kExtreme, measured);
    } else if (s.in_band_s > p.extreme_budget_s) {
      s.cooldown_left_s = p.extreme_cooldown_s;
    }
  }
  s.mode = s.cooldown_left_s > 0.0 ? ProtectionMode::kCooldown
           : s.factor < 1.0        ? ProtectionMode::kDerating
                                   : ProtectionMode::kOk;
  return false;
}

bool protection_condition_present(const DriveProtection& p, const ActuatorHealth& h) {
  return (h.hardware_error & p.hardware_error_mask) != 0 ||
         h.temperature_c >= p.temperature_c.fault || std::fabs(h.load) >= p.load.fault ||
         std::fabs(h.current_a) >= p.current_a.fault || h.voltage_v < p.voltage_min_v ||
         h.voltage_v > p.voltage_max_v;
}

double protected_target(const DriveProtection& p, const ActuatorLimits& l, double rest,
                        const ProtectionState& s, double target) {
  if (!p.configured) return target;
  // Between the target and rest: inside the actuator's soft range. Other
  // actuators derate by their own factors, so coupled limits are the coupled
  // bounds' work, downstream (docs/SAFETY.md, "Drive-level protection").
  double t = rest + s.factor * (target - rest);
  if (s.cooldown_left_s > 0.0) {
    t = std::clamp(t, l.position_min + p.extreme_band, l.position_max - p.extreme_band);
  }
  return t;
}

const char* to_string(ProtectionCause cause) {
  switch (cause) {
    case ProtectionCause::kNone:
      return "none";
    case ProtectionCause::kTemperature:
      return "temperature";
    case ProtectionCause::kLoad:
      return "load";
    case ProtectionCause::kCurrent:
      return "current";
    case ProtectionCause::kVoltage:
      return "voltage";
    case ProtectionCause::kHardwareError:
      return "hardware_error";
    case ProtectionCause::kExtreme:
      return "time_at_extreme";
  }
  return "?";
}

const char* to_string(ProtectionMode mode) {
  switch (mode) {
    case ProtectionMode::kOk:
      return "ok";
    case ProtectionMode::kDerating:
      return "derating";
    case ProtectionMode::kCooldown:
      return "cooldown";
    case ProtectionMode::kFault:
      return "fault";
  }
  return "?";
}

}  // namespace facectl
