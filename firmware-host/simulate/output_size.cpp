#include "firmware-host/simulate/output_size.hpp"

#include <algorithm>
#include <cmath>

#include "firmware-host/run/protection_columns.hpp"
#include "firmware-host/simulate/simulation_run.hpp"

namespace facectl {
namespace {

// telemetry.csv (decimated_telemetry.cpp): tick (20 digits), time (%.6f of at
// most 1e15 s: 23), state (8), three flag words (20 each), per actuator two
// %.6g numbers (13 each) and a flag word, each after a comma, and at most
// the drive-level protection columns (protection_columns.hpp); a newline.
std::uint64_t telemetry_row_bytes_at_most(const ControllerModel& model) {
  const auto protected_count = static_cast<std::uint64_t>(
      std::count_if(model.protection.begin(), model.protection.end(),
                    [](const DriveProtection& p) { return p.configured; }));
  return 20 + 1 + 23 + 1 + 8 + 3 * 21 + model.actuators.size() * (2 * 14 + 21) +
         protected_count * kProtectionColumnsBytesAtMost + 1;
}

constexpr std::uint64_t kFixedOutputs = 1u << 20;  // plots, summary, index.html

}  // namespace

std::uint64_t simulate_output_bytes_at_most(const ControllerModel& model, double duration_s,
                                            std::uint64_t telemetry_every) {
  const double ticks = std::ceil((kSimulateEnableTimeoutS + duration_s) * model.rate_hz);
  const double rows =
      std::ceil(ticks / static_cast<double>(std::max<std::uint64_t>(1, telemetry_every))) + 2;
  const double bytes = rows * static_cast<double>(telemetry_row_bytes_at_most(model)) +
                       static_cast<double>(kFixedOutputs);
  return bytes >= 1.8e19 ? UINT64_MAX : static_cast<std::uint64_t>(bytes);
}

}  // namespace facectl
