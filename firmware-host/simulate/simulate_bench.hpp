#pragma once

#include <string>

namespace facectl {

struct SimulateBenchOptions {
  std::string config;         // runtime config (default: the shipped one; its rig and show)
  std::string rig;            // instead of the config's rig
  std::string show;           // instead of the config's show
  double duration_s = 600.0;  // simulated seconds per run (the show loops)
  int runs = 5;
};

// `facectl bench simulate`: how many times faster than real time the offline
// simulation runs (no rendering), median of `runs` runs, beside the same loop
// with no outputs (ticks, show evaluation and plant stepping only), so the
// cost of the outputs shows. Exit 0, or 2 on unusable input.
int simulate_bench_command(const SimulateBenchOptions& options);

}  // namespace facectl
