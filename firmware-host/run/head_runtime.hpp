#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "control/controller.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/model/sim_twin.hpp"
#include "firmware-host/run/real_hardware.hpp"
#include "firmware-host/run/realtime_loop.hpp"
#include "firmware-host/run/realtime_thread.hpp"
#include "firmware-host/run/telemetry_writer.hpp"

namespace facectl {

// One head under control, as `facectl run` and `facectl serve` share it: the
// loaded configuration, its hardware (simulated twins or the real buses and
// GPIO), the channels to and from the tick, the controller and the real-time
// thread. Members are declared in the order they are built and destroyed in
// reverse, so each ring, mailbox and bus outlives its user.
struct HeadRuntime {
  std::unique_ptr<LoadedConfig> cfg;
  RealtimeReport rt;
  std::unique_ptr<SimHardware> sim;
  std::unique_ptr<RealHardware> real;
  LatestValueMailbox<FaceCommand> mailbox;
  SpscRing<TransitionEvent> events{256};
  std::unique_ptr<SpscRing<TelemetryRecord>> telemetry;
  std::unique_ptr<TelemetryWriter> writer;
  std::unique_ptr<Controller> controller;
  LoopStats stats;
  std::unique_ptr<RealtimeLoop> loop;
  std::atomic<bool> stop{false};
  std::thread rt_thread;

  const ControllerModel& model() const { return cfg->built.model; }
};

// `--hardware sim|real`; throws ConfigError for anything else.
std::optional<HardwareMode> parse_hardware_option(const std::optional<std::string>& text);

// Opens the simulated twins, or the real buses and GPIO (printing their
// notes); with `record`, the telemetry CSV; with `telemetry`, a ring for
// another reader of the tick's records. Builds the controller over them.
// Throws when something cannot be opened. Call after cfg is loaded.
void open_head(HeadRuntime& head, const std::optional<std::string>& record, bool telemetry);

// Warns what the machine lacks for a hard real-time loop, starts the logger
// and the real-time thread (printing what its set-up could not obtain).
void start_head_loop(HeadRuntime& head);

// Stops the real-time thread, then releases the outputs: nothing can hold an
// actuator once the loop stopped commanding it.
void stop_head_loop(HeadRuntime& head);

}  // namespace facectl
