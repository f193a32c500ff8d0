#pragma once

#include <span>
#include <vector>

#include "drivers/bus_spec.hpp"

namespace facectl {

// How long a bus keeps its wire busy, for the simulation summary.
struct BusTiming {
  double cycle_time_s = 0;  // wire time of one bus cycle (one network latency over TCP)
  double load = 0;          /* fraction of the tick period the wire is busy */
};

// A bus's timing and, per actuator, when its command lands after the bus
// cycle starts (docs/CONFIG.md, "Simulated bus timing"):
// - CAN custom: the board's command frame's end, frames sent in node order;
//   CiA 402: the SYNC after every drive's RPDO (the drives latch on SYNC);
// - Modbus RTU: the end of the board's write request and its 3.5-character
//   silence, boards served in unit order, each a write and a read;
// - Modbus TCP: the configured network latency;
// - PCA9685: the end of the board's last LEDn block write at the bus's
//   i2c_khz, boards served in list order (pca9685_cycle_bits).
struct SimBusTiming {
  BusTiming timing;
  std::vector<double> arrival_s;  // per actuator, in the order of `addresses`
};

SimBusTiming sim_bus_timing(const BusSpec& bus, std::span<const int> addresses, double tick_hz);

}  // namespace facectl
