#pragma once

#include <string>
#include <vector>

namespace facectl {

// A telemetry CSV as `facectl run --record` writes it (docs/TELEMETRY.md),
// read back for plots and reports. Numeric columns only; text columns
// (state, transition) are kept as strings.
struct TelemetryTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  // Column index, or -1.
  int find(const std::string& name) const;
  // A numeric column; throws ConfigError naming file:line if a cell is not a number.
  std::vector<double> numbers(const std::string& name) const;
  std::string file;
};

// Throws ConfigError (file:line: what was expected, what was found) on a
// malformed file.
TelemetryTable read_telemetry_csv(const std::string& path);

}  // namespace facectl
