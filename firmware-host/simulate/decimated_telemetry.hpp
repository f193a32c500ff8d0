#pragma once

#include <cstdio>
#include <span>
#include <string>

#include "control/controller_model.hpp"
#include "control/telemetry_record.hpp"

namespace facectl {

// telemetry.csv of `facectl simulate` (docs/SIMULATE.md): the columns of
// `facectl run --record` (docs/TELEMETRY.md) plus pos.<actuator>, the
// simulated (true) position, one row every `every` ticks. The limiter and
// constraint flags of a row are those of every tick since the previous row
// (OR), so that no engagement falls between rows.
class DecimatedTelemetry {
 public:
  DecimatedTelemetry(const ControllerModel& model, const std::string& path, std::uint64_t every);
  ~DecimatedTelemetry();
  DecimatedTelemetry(const DecimatedTelemetry&) = delete;
  DecimatedTelemetry& operator=(const DecimatedTelemetry&) = delete;

  // One tick at show time t.
  void add(double t, const TelemetryRecord& r, std::span<const double> positions);
  // Flushes and closes; throws std::runtime_error naming the file if writing failed.
  void close();

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::uint64_t every_;
  std::uint64_t seen_ = 0;
  TelemetryRecord row_{};  // the flags gathered since the last row
};

}  // namespace facectl
