// Drive-level protection in the tick (docs/SAFETY.md, "Drive-level
// protection"): the health the buses read this tick against each actuator's
// limits. No allocation: the state is preallocated in the controller.
#include "control/controller.hpp"

namespace facectl {

bool Controller::step_drive_protection(double dt) {
  const std::size_t n = model_.actuators.size();
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (!protected_at(i)) continue;
    const bool powered = driving() && !relaxed(i);
    if (step_protection(model_.protection[i], model_.actuators[i].limits, health_[i], measured_[i],
                        powered, dt, protection_[i]) &&
        protection_faulted_ >= n) {
      protection_faulted_ = i;  // the first one names the FAULT
    }
    any = any || protection_[i].mode == ProtectionMode::kFault;
  }
  return any;
}

void Controller::clear_protection_faults() {
  const std::size_t n = model_.actuators.size();
  protection_faulted_ = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (!protected_at(i) || protection_[i].mode != ProtectionMode::kFault) continue;
    const DriveProtection& p = model_.protection[i];
    if (protection_condition_present(p, health_[i])) {
      if (protection_faulted_ >= n) protection_faulted_ = i;
      continue;
    }
    // Back at the floor: the factor recovers slowly from there.
    protection_[i] = ProtectionState{};
    protection_[i].factor = p.derate_floor;
  }
  if (protection_faulted_ >= n) protection_faulted_ = kMaxActuators;
}

}  // namespace facectl
