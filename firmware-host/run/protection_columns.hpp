// The drive-level protection columns of the telemetry CSVs (docs/TELEMETRY.md):
// for each actuator with a `protection` block, its health readings, derate
// factor, time in the extreme band and protection state.
#pragma once

#include <cstdio>

#include "control/controller_model.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

inline constexpr std::size_t kProtectionColumnsBytesAtMost = 8 * 24;

void write_protection_header(std::FILE* out, const ControllerModel& model);
// Appends the protected actuators' columns of `r` at `p` (at most
// kProtectionColumnsBytesAtMost per protected actuator); returns the new end.
char* write_protection_columns(char* p, const TelemetryRecord& r);

}  // namespace facectl
