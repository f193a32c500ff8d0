#pragma once

#include <optional>
#include <string>

namespace facectl {

struct BenchLoopOptions {
  std::string config;
  double duration_s = 10.0;  // per variant
  double chunk_s = 1.0;      // variants alternate in chunks of this length
  std::optional<double> rate_hz;
};

// `facectl bench loop`: the full default pipeline on simulated hardware beside
// a bare clock_nanosleep loop, interleaved in one run; prints both wake-up
// latency distributions, the ratio of their p99s and the tick compute time.
int bench_loop_command(const BenchLoopOptions& options);

}  // namespace facectl
