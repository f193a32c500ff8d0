#pragma once

namespace facectl {

// A Dynamixel bus's timing and start-up settings (the rig's `buses[]` keys,
// docs/CONFIG.md "Dynamixel").
struct DynamixelOptions {
  double response_timeout_s = 0.010;  // for the first status packet of a request
  double fault_after_s = 0.100;       // a servo silent this long is a FAULT
  double cycle_period_s = 0.005;      // one sync write + one sync read
  double reconnect_interval_s = 0.5;  // reopening a lost port
  int return_delay_us = 0;            // written to Return Delay Time (EEPROM) if it differs
  int bus_watchdog_ms = 100;          // the servo's own Bus Watchdog; 0 = off
  bool write_position_limits = true;  // Min/Max Position Limit := the rig's hard limits
};

}  // namespace facectl
