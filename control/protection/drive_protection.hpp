// Drive-level protection (docs/SAFETY.md, "Drive-level protection"): what a
// smart servo reports (ActuatorHealth) against per-actuator limits. A free
// function over a const model and preallocated state, called in the tick:
// no allocation, no lock, no blocking.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"

namespace facectl {

inline constexpr double kNoLimit = std::numeric_limits<double>::infinity();

// One reported value's thresholds on its magnitude: derating starts at
// `derate`, FAULT at `fault` (derate < fault); infinite = not configured.
struct ProtectionLimit {
  double derate = kNoLimit;
  double fault = kNoLimit;
  bool configured() const { return fault < kNoLimit; }
};

// What faulted an actuator (telemetry `protection` column, fault texts).
enum class ProtectionCause : std::uint8_t {
  kNone,
  kTemperature,
  kLoad,
  kCurrent,
  kVoltage,
  kHardwareError,
  kExtreme,
};
inline constexpr std::size_t kProtectionCauseCount = 7;

struct DriveProtection {
  bool configured = false;
  ProtectionLimit temperature_c;  // °C
  ProtectionLimit load;           // |load|, fraction of max torque
  ProtectionLimit current_a;      // |current|, A
  double voltage_min_v = -kNoLimit;
  double voltage_max_v = kNoLimit;
  std::uint32_t hardware_error_mask = 0xFFFFFFFFu;  // bits that FAULT
  double derate_floor = 0.5;                        // factor at the fault threshold
  // A value must stay past a threshold this long before it derates or
  // faults: one noisy reading does neither.
  double hold_s = 0.1;
  // The factor falls at once (the limiter rate-limits the command) but rises
  // by at most 1 per recover_s: a hot servo cools slowly.
  double recover_s = 10.0;
  double extreme_band = 0.0;      // SI from either end of the hard range; 0 = none
  double extreme_budget_s = 0.0;  // continuous time measured in the band
  double extreme_cooldown_s = 0.0;
  // false: derate and cool down only, never FAULT (verify's adversarial
  // search, which lets no servo trip: it checks the control law).
  bool faults = true;
  // "protection: <actuator> <cause>", written at load: the tick copies, never formats.
  std::array<std::string, kProtectionCauseCount> fault_text{};
};

// What protection is doing to an actuator (telemetry).
enum class ProtectionMode : std::uint8_t { kOk, kDerating, kCooldown, kFault };

struct ProtectionState {
  ProtectionMode mode = ProtectionMode::kOk;
  ProtectionCause cause = ProtectionCause::kNone;  // latched FAULT cause
  double factor = 1.0;                             // derate factor applied to the command
  double value_at_fault = 0.0;                     // the reading that faulted it
  std::array<double, 3> over_derate_s{};           // temperature, load, current
  std::array<double, 3> over_fault_s{};
  double voltage_bad_s = 0.0;
  double in_band_s = 0.0;        // continuous time measured in the extreme band
  double cooldown_left_s = 0.0;  // > 0: the command is kept out of the band
};

// One tick: updates `s` from `health` and the measured position; true on the
// tick the actuator newly faults. A NaN reading counts as "not past". Time in
// the extreme band counts only while the actuator is `powered` (driven).
bool step_protection(const DriveProtection& p, const ActuatorLimits& l,
                     const ActuatorHealth& health, double measured, bool powered, double dt,
                     ProtectionState& s);

// True while a reading is past a fault threshold (or an error bit is set):
// a latched FAULT may be reset only once this is false.
bool protection_condition_present(const DriveProtection& p, const ActuatorHealth& health);

// The target this actuator may have now: pulled toward `rest` by the derate
// factor, and kept out of the extreme band during a cool-down.
double protected_target(const DriveProtection& p, const ActuatorLimits& l, double rest,
                        const ProtectionState& s, double target);

const char* to_string(ProtectionCause cause);
const char* to_string(ProtectionMode mode);

}  // namespace facectl
