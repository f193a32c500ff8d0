#pragma once

#include <string>

#include "control/controller.hpp"
#include "control/safety/safety_state.hpp"
#include "firmware-host/run/realtime_loop.hpp"

namespace facectl {

// One line for a terminal: rate, latency percentiles, overruns, state, faults.
std::string format_status(const LoopStats& stats, SafetyState state, double elapsed_s,
                          const char* fault);

// "[   2.034 s, tick 2034] RUNNING -> FAULT: reason — detail" on stderr.
void print_transition(const TransitionEvent& ev);

}  // namespace facectl
