#pragma once

#include <string>

#include "firmware-host/run/offline_head.hpp"

namespace facectl::testing {

// The shipped default head (or another runtime config) on simulated hardware,
// in simulated time.
class SimHead : public OfflineHead {
 public:
  explicit SimHead(const std::string& config = default_config_path(), std::size_t telemetry = 0,
                   bool noiseless = false)
      : OfflineHead(load_config(config), telemetry, noiseless) {}
};

}  // namespace facectl::testing
