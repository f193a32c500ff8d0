#pragma once

#include <cstdint>
#include <ctime>

namespace facectl {

// CLOCK_MONOTONIC in nanoseconds: the clock of TickTime::now_ns and of every
// thread that timestamps for the tick (the one definition). A vDSO call,
// no system call, so the tick may use it.
inline std::int64_t monotonic_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace facectl
