#pragma once

#include <string>
#include <vector>

#include "drivers/protocol/can_bus_budget.hpp"
#include "firmware-host/config/rig_config.hpp"

namespace facectl {

// The load one configured bus puts on its wire at the loop rate.
struct BusBudgetResult {
  enum class Verdict { kOk, kWarning, kRefused };
  std::string bus;
  std::string where;  // file:line:col of the bus entry
  Verdict verdict = Verdict::kOk;
  double load = 0.0;  // fraction of the wire's capacity
  // The line to print, e.g. "can0: 8 frames per cycle at 250 Hz = 270000 bit/s,
  // 27.0% of 1000000 bit/s".
  std::string text;
  CanBusBudget can;  // CAN buses: the figures behind the text
};

// Budgets every bus of the rig at `tick_hz` (docs/PROTOCOLS.md, "Bus budget"):
// - CAN: frames per bus cycle and load at the configured bitrate, 135 bits per
//   classic frame, FD frames at their own worst case; above 50% is a warning,
//   above 70% refused.
// - Modbus RTU: the bytes of one I/O cycle on the wire against the cycle
//   period; a cycle that does not fit is a warning (the I/O thread then runs
//   slower than configured; the tick is not affected). Modbus TCP: not budgeted.
// Throws ConfigError, at the actuator, for an address the bus's protocol cannot
// carry (custom CAN nodes 1..63, CiA 402 nodes 1..127, Modbus units 1..247).
std::vector<BusBudgetResult> check_bus_budgets(const RigConfig& rig, double tick_hz);

// Throws ConfigError naming the first refused bus with its numbers; appends a
// line per warned bus to `warnings`.
void enforce_bus_budgets(const std::vector<BusBudgetResult>& results,
                         std::vector<std::string>& warnings);

}  // namespace facectl
