#pragma once

#include <cstdint>

#include "drivers/protocol/custom_can_frames.hpp"

namespace facectl {

// Settings shared by the CAN actuator buses (docs/PROTOCOLS.md).
struct CanBusOptions {
  bool fd = false;                   // CAN FD frames (custom layout only)
  long data_bitrate = 0;             // CAN FD data phase (bit rate switch); 0 = the nominal rate
  int cycle_divider = 1;             // transmit on every Nth tick: the bus rate is tick rate / N
  double heartbeat_timeout_s = 0.1;  // a node not heard for this long: FAULT

  // Custom boards.
  custom_can::Width width = custom_can::Width::kInt16;

  // CiA 402 drives.
  double rotary_counts_per_rad = 131072.0 / 6.283185307179586;  // 17-bit encoder
  double linear_counts_per_m = 1.0e6;                           // 1 µm per count
  bool map_pdos = true;           // map RPDO1/TPDO1 by SDO at each enable (CiA 301 procedure)
  int host_node = 127;            // our heartbeat's node id (0x700 + host_node)
  int host_heartbeat_ms = 10;     // how often we produce it
  int drive_heartbeat_ms = 20;    // 0x1017 on each drive
  int drive_watchdog_ms = 100;    // 0x1016:01 on each drive: our heartbeat's timeout
  double sdo_timeout_s = 0.05;    // per SDO request while enabling
  double enable_timeout_s = 0.5;  // to reach "operation enabled" after the SDOs
  // No TPDO1 from an operational drive for this long, and for more than ten
  // of our SYNCs, while its heartbeat goes on: FAULT. 0: ten bus cycles
  // (tick period x cycle_divider), at least 20 ms.
  double feedback_timeout_s = 0.0;
  // On disable, quick stop (controlword 0x0002) is held this long, or until
  // the drive reports switch on disabled, before disable voltage (0x0000).
  double quick_stop_s = 0.1;
};

}  // namespace facectl
