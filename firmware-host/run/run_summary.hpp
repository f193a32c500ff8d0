#pragma once

#include <string>

#include "control/controller.hpp"
#include "firmware-host/run/realtime_loop.hpp"
#include "firmware-host/run/realtime_thread.hpp"
#include "firmware-host/run/telemetry_writer.hpp"

namespace facectl {

struct RunSummaryInput {
  const ControllerModel& model;
  const Controller& controller;
  const LoopStats& stats;
  const RealtimeReport& realtime;
  const TelemetryWriter* writer;  // may be null
  std::string rig_name;
  std::string head_name;
  std::uint64_t events_dropped = 0;  // state transitions the event ring refused
  bool real_hardware = false;
};

// Prints the end-of-run summary to stdout and returns the exit code
// (run_command.hpp documents them).
int print_run_summary(const RunSummaryInput& in);

}  // namespace facectl
