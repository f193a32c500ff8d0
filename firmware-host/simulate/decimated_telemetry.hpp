#pragma once

#include <array>
#include <cstdio>
#include <span>
#include <string>

#include "control/controller_model.hpp"
#include "control/telemetry_record.hpp"
#include "firmware-host/simulate/last_value_text.hpp"

namespace facectl {

// telemetry.csv of `facectl simulate` (docs/SIMULATE.md, "telemetry.csv"):
// one row every `every` ticks with the show time, the safety state, the
// envelope and coupled-limit flags and per actuator the command, the
// simulated position and the limiter flags. Flags are those of every tick
// since the previous row (OR), so that no engagement falls between rows.
// Compact on purpose: an hour at 100 Hz must stay a manageable file.
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
  // Flags gathered since the last row.
  std::uint8_t envelope_ = 0;
  std::uint32_t coupled_ = 0, actuator_coupled_ = 0;
  std::array<LimitFlags, kMaxActuators> limits_{};
  // Per actuator, the text of the last command and position written.
  std::array<LastValueText, kMaxActuators> last_command_{}, last_position_{};
};

}  // namespace facectl
