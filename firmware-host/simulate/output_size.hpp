#pragma once

#include <cstdint>

#include "control/controller_model.hpp"

namespace facectl {

// An upper bound on the bytes `simulate` writes for `duration_s` of show
// (after the enable ramp), render frames aside: telemetry.csv, a row every
// `telemetry_every` ticks at its longest, and the plots, summary and report,
// which take under a megabyte whatever the length. (A frame's PNG size is
// known only once drawn: RenderOptions::max_bytes bounds them as they come.)
std::uint64_t simulate_output_bytes_at_most(const ControllerModel& model, double duration_s,
                                            std::uint64_t telemetry_every);

}  // namespace facectl
