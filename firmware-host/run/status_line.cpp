#include "firmware-host/run/status_line.hpp"

#include <cstdio>

namespace facectl {

std::string format_status(const LoopStats& stats, SafetyState state, double elapsed_s,
                          const char* fault) {
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "t=%6.1fs  %8.2f Hz  wake p50 %4.0f us p99 %5.0f us max %6.0f us  overruns %llu  "
                "%-8s %s",
                elapsed_s, stats.measured_rate_hz(), stats.wake_latency.percentile(50) * 1e6,
                stats.wake_latency.percentile(99) * 1e6, stats.wake_latency.max() * 1e6,
                static_cast<unsigned long long>(stats.overruns.load()),
                std::string(to_string(state)).c_str(), fault);
  return buf;
}

}  // namespace facectl

namespace facectl {

void print_transition(const TransitionEvent& ev) {
  std::fprintf(stderr, "[%9.3f s, tick %llu] %s -> %s: %s%s%s\n", ev.time_s,
               static_cast<unsigned long long>(ev.tick), std::string(to_string(ev.from)).c_str(),
               std::string(to_string(ev.to)).c_str(), std::string(to_string(ev.reason)).c_str(),
               ev.detail[0] != '\0' ? " — " : "", ev.detail);
}

}  // namespace facectl
