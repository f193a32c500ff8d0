#pragma once

#include <functional>
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

struct RigConfig;
struct SimHardware;
class RealtimeLoop;

// Throws ConfigError when a bus_fault names no bus of the rig.
void check_injection_buses(const std::vector<Injection>& injections, const RigConfig& rig);

// Fires, once each, the injections due at `t` seconds on the simulated
// hardware (estop, bus_fault), the input (input_loss: `silence_input`, which
// makes whatever feeds the tick's mailbox go quiet) and the loop
// (overrun_storm); a null or empty target skips its kinds.
void fire_due_injections(std::vector<Injection>& injections, double t, SimHardware* sim,
                         const std::function<void()>& silence_input, RealtimeLoop* loop);

}  // namespace facectl
