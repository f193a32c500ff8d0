#include "firmware-host/run/head_runtime.hpp"

#include <cstdio>
#include <stdexcept>
#include <vector>

#include "firmware-host/run/realtime_readiness.hpp"

namespace facectl {

std::optional<HardwareMode> parse_hardware_option(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  if (*text == "sim") return HardwareMode::kSim;
  if (*text == "real") return HardwareMode::kReal;
  throw ConfigError("--hardware: expected sim or real, found '" + *text + "'");
}

void open_head(HeadRuntime& head, const std::optional<std::string>& record, bool telemetry) {
  const ControllerModel& model = head.model();
  if (head.cfg->runtime.hardware == HardwareMode::kReal) {
    try {
      head.real = make_real_hardware(model, *head.cfg);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("real hardware: ") + e.what());
    }
    for (const auto& note : head.real->notes) std::fprintf(stderr, "%s\n", note.c_str());
  } else {
    head.sim = make_sim_hardware(model, head.cfg->rig);
  }
  const std::vector<ActuatorBus*>& seams = head.real ? head.real->seams : head.sim->seams;
  SafetyIo& io = head.real ? head.real->io() : static_cast<SafetyIo&>(head.sim->io);
  if (record || telemetry) {
    head.telemetry = std::make_unique<SpscRing<TelemetryRecord>>(head.cfg->runtime.telemetry_ring);
  }
  if (record) head.writer = std::make_unique<TelemetryWriter>(model, *head.telemetry, *record);
  head.controller = std::make_unique<Controller>(
      model, seams, io, ControllerChannels{&head.mailbox, head.telemetry.get(), &head.events});
}

namespace {

void warn_if_not_realtime_ready(const RuntimeConfig& runtime) {
  const std::vector<std::string> gaps = realtime_gaps(runtime.realtime);
  if (gaps.empty()) return;
  std::fprintf(stderr,
               "warning: this machine is not set up for a hard real-time loop "
               "(docs/REALTIME.md). Under load expect stalls of tens of ms, and a FAULT when one "
               "outlasts %d periods (runtime.overrun_fault_count):\n",
               runtime.safety.overrun_fault_count);
  for (const std::string& gap : gaps) std::fprintf(stderr, "  - %s\n", gap.c_str());
}

}  // namespace

void start_head_loop(HeadRuntime& head) {
  warn_if_not_realtime_ready(head.cfg->runtime);
  if (head.writer) head.writer->start();
  head.loop = std::make_unique<RealtimeLoop>(*head.controller, head.model().rate_hz, head.stats);
  head.rt_thread = start_realtime_thread(
      head.cfg->runtime.realtime, [&head] { head.loop->run(head.stop); }, head.rt);
  for (const auto& w : head.rt.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

void stop_head_loop(HeadRuntime& head) {
  head.stop.store(true);
  if (head.rt_thread.joinable()) head.rt_thread.join();
  head.controller->release_outputs();
}

}  // namespace facectl
