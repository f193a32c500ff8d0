#pragma once

#include <string>
#include <vector>

namespace facectl {

// A fault to rehearse on simulated hardware (`facectl run --inject KIND@SECONDS`).
struct Injection {
  enum class Kind { kEstop, kBusFault, kInputLoss, kOverrunStorm };
  Kind kind = Kind::kEstop;
  double at_s = 0.0;
  std::string bus;        // kBusFault
  double stall_ms = 0.0;  // kOverrunStorm: how long the tick is stalled
  bool done = false;
};

// Parses "estop@3", "bus_fault:can0@2.5", "input_loss@4", "overrun_storm:50@5".
// Throws std::invalid_argument with a message naming the text and what was expected.
Injection parse_injection(const std::string& text);

}  // namespace facectl
