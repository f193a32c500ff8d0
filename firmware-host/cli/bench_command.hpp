#pragma once

#include <optional>
#include <string>
#include <vector>

namespace facectl {

struct BenchLoopOptions {
  std::string config;
  double duration_s = 10.0;  // per variant
  double chunk_s = 1.0;      // variants alternate in chunks of this length
  std::optional<double> rate_hz;
  // Faults to rehearse, as `run --inject`, timed in pipeline seconds.
  std::vector<std::string> inject;
};

// `facectl bench loop`: the full default pipeline on simulated hardware beside
// a bare clock_nanosleep loop, interleaved in one run; prints both wake-up
// latency distributions, the ratio of their p99s and the tick compute time.
// A pipeline that leaves RUNNING (FAULT, ESTOP) ends the measurement there:
// the figures cover the ticks before it, and the command exits 1.
int bench_loop_command(const BenchLoopOptions& options);

}  // namespace facectl
