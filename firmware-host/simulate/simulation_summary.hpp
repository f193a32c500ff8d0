#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/simulate/simulation_input.hpp"
#include "firmware-host/simulate/simulation_run.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"
#include "sim/devices/sim_hardware.hpp"

namespace facectl {

using SummaryJson = nlohmann::ordered_json;

// summary.json of `facectl simulate` (docs/SIMULATE.md, "Summary"): the run,
// per actuator tracking error, limiter engagements and plant figures, the
// coupled constraints' and envelope's engagements, per bus load, the safety
// states and the list of problems. Numbers are rounded to 6 significant
// digits so that the file is stable and readable.
SummaryJson make_summary(const LoadedConfig& cfg, const SimulationInput& input,
                         const SimulationRun& run, const SimulationStats& stats,
                         const SimHardware& hardware);

// summary.txt: the same, as aligned text for a terminal.
std::string summary_text(const SummaryJson& summary);

// The name of LimitFlag bit `bit` in the summary ("position", "velocity", ...).
const char* limit_name(int bit);

}  // namespace facectl
