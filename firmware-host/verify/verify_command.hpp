#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facectl {

struct VerifyOptions {
  std::string rig;                  // rig YAML to verify
  std::string config;               // runtime config naming the head (default: shipped)
  std::vector<std::string> shows;   // shows to check
  std::string json;                 // write the JSON report here
  std::string plots;                // folder for the show check's telemetry and plots
  std::uint64_t ticks = 1'000'000;  // adversarial search length
  std::uint64_t seed = 1;
};

// `facectl verify RIG`: static proof, adversarial search, show check.
// Exit 0 when everything holds, 1 when something fails, 2 on unusable input.
int verify_command(const VerifyOptions& options);

}  // namespace facectl
