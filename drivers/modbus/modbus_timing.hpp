#pragma once

namespace facectl {

// Timing of the I/O thread. Every value is explicit: libmodbus's own default
// response timeout (500 ms) would hide a dead board for half a second per
// transaction (stephane/libmodbus#776).
struct ModbusTiming {
  double response_timeout_s = 0.020;  // per transaction attempt
  double byte_timeout_s = 0.005;      // between bytes of one reply (RTU)
  int max_retries = 1;                // extra attempts per transaction per cycle
  double board_timeout_s = 0.100;     // no good reply for this long: FAULT, commands stale
  double cycle_period_s = 0.001;      // I/O cycle; 0 runs back to back (benchmarks)
  double reconnect_interval_s = 0.050;
  int board_watchdog_ms = 100;  // written to each board's watchdog register on connect
  // TCP: the one-way latency the simulated twin adds to each command (the
  // real backend has the network's own).
  double network_latency_s = 0.0005;
};

}  // namespace facectl
