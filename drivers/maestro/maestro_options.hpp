#pragma once

#include "drivers/protocol/maestro_serial.hpp"

namespace facectl {

// A Maestro bus's settings (the rig's `buses[]` keys, docs/CONFIG.md
// "Maestro"). An actuator's `address` is its channel, 0..23.
struct MaestroOptions {
  maestro::Protocol protocol = maestro::Protocol::kCompact;
  int device_number = maestro::kDefaultDeviceNumber;  // Pololu protocol only
  bool multiple_targets = false;      // one Set Multiple Targets (Mini Maestro 12/18/24)
  double cycle_period_s = 0.020;      // one servo pulse period at the Maestro's 50 Hz
  double response_timeout_s = 0.020;  // beyond the wire time of a cycle's replies
  double fault_after_s = 0.100;       // a Maestro silent this long is a FAULT
  double reconnect_interval_s = 0.5;  // reopening a lost port
};

}  // namespace facectl
