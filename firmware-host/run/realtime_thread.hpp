#pragma once

#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "firmware-host/config/runtime_config.hpp"

namespace facectl {

// What the real-time set-up obtained; anything refused is a warning, not an error.
struct RealtimeReport {
  bool fifo = false;
  bool memory_locked = false;
  bool pinned = false;
  bool idle_latency_held = false;  // /dev/cpu_dma_latency request in force
  std::vector<std::string> warnings;
};

// Moves the calling thread (and so every thread it starts later) off the CPU
// the real-time thread will be pinned to, so that their system calls cannot
// delay its wake-up on a kernel without full preemption. No-op without `cpu`.
void keep_off_realtime_cpu(const RealtimeSettings& settings, RealtimeReport& report);

// Locks memory (process-wide), holds the /dev/cpu_dma_latency request for the
// rest of the process, then starts `body` on a thread with SCHED_FIFO
// and CPU affinity where permitted, its stack prefaulted. Waits until the
// thread has applied its settings, so the report is complete on return.
std::thread start_realtime_thread(const RealtimeSettings& settings, std::function<void()> body,
                                  RealtimeReport& report);

}  // namespace facectl
