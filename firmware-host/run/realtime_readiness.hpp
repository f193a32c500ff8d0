#pragma once

#include <string>
#include <vector>

#include "firmware-host/config/runtime_config.hpp"

namespace facectl {

// What this machine lacks for a hard real-time loop, read from the kernel's
// own files under `root` ("/" on a real machine; a test passes a fake tree).
// Each entry says what is missing and what to do (docs/REALTIME.md): a
// PREEMPT_RT kernel, the loop's CPU isolated (isolcpus=, nohz_full=), device
// interrupts kept off it, the CPU frequency governor.
// An empty list: nothing to warn about. Never throws; unreadable files are
// taken as "unknown" and not reported.
std::vector<std::string> realtime_gaps(const RealtimeSettings& settings,
                                       const std::string& root = "/");

}  // namespace facectl
