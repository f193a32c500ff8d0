#pragma once

#include <string>

namespace facectl {

struct SimulateOptions {
  std::string rig;          // rig YAML
  std::string show;         // a show file, or
  std::string fap;          // an MPEG-4 FAP file, or
  std::string input;        // any input file (docs/INPUTS.md)
  std::string format;       // --format: the input's format, else detected
  std::string out;          // output folder (replaced as a whole)
  std::string config;       // runtime config (default: the shipped one)
  bool render = false;      // face render frames
  double duration_s = 0.0;  // 0: the input's length
  double telemetry_rate_hz = 100.0;
  bool quiet = false;             // no progress bar even on a terminal
  double max_output_mb = 1024.0;  // refuse a run whose outputs could be larger
};

// `facectl simulate` (docs/SIMULATE.md). Exit 0 when the head ran the input
// without a fault, 1 if it faulted (outputs written all the same), 2 on
// unusable input (nothing written, DIR untouched).
int simulate_command(const SimulateOptions& options);

}  // namespace facectl
