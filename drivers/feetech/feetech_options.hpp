#pragma once

#include "drivers/protocol/feetech_table.hpp"

namespace facectl {

// A Feetech bus's series, timing and start-up settings (the rig's `buses[]`
// keys, docs/CONFIG.md "Feetech").
struct FeetechOptions {
  ft::Series series = ft::Series::kSts;
  double response_timeout_s = 0.010;  // for the first status packet of a request
  double fault_after_s = 0.100;       // a servo silent this long is a FAULT
  double cycle_period_s = 0.010;      // one sync write + the feedback reads
  double reconnect_interval_s = 0.5;  // reopening a lost port
  int return_delay_us = 0;            // written to Return Delay (EEPROM) if it differs
  bool write_position_limits = true;  // Min/Max Angle Limit := the rig's hard limits
};

}  // namespace facectl
