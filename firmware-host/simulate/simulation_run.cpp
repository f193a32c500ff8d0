#include "firmware-host/simulate/simulation_run.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "firmware-host/simulate/actuator_plots.hpp"
#include "firmware-host/simulate/decimated_telemetry.hpp"
#include "firmware-host/simulate/progress_bar.hpp"
#include "firmware-host/simulate/simulation_stats.hpp"

namespace facectl {
namespace {

// Reads every actuator's simulated (true) position, in actuator order.
class PositionReader {
 public:
  PositionReader(const ControllerModel& m, SimHardware& hw) {
    for (std::size_t b = 0; b < m.buses.size(); ++b) {
      for (std::size_t i = 0; i < m.buses[b].count; ++i) plants_.push_back(&hw.buses[b]->plant(i));
    }
  }
  void read(std::array<double, kMaxActuators>& out) const {
    for (std::size_t i = 0; i < plants_.size(); ++i) out[i] = plants_[i]->position();
  }

 private:
  std::vector<const sim::ServoPlant*> plants_;
};

void drain(OfflineHead& head) {
  while (head.telemetry()->front() != nullptr) head.telemetry()->pop();
}

}  // namespace

SimulationRun run_simulation(OfflineHead& head, const SimulationInput& input, double duration_s,
                             const SimulationSinks& sinks) {
  SimulationRun run;
  const ControllerModel& m = head.model();
  const double period = head.period();
  head.send(m.neutral);
  head.controller().request_enable();
  const double start = head.time();
  while (head.controller().state() != SafetyState::kRunning &&
         head.time() - start < kSimulateEnableTimeoutS) {
    head.step(period);
    drain(head);
  }
  run.enable_s = head.time() - start;
  run.enabled = head.controller().state() == SafetyState::kRunning;
  // The pose published before a step is used by the tick that step runs, one
  // period later on the head's clock: that tick is show time 0.
  run.clock_at_show_start_s = head.time() + period;
  if (!run.enabled) return run;

  const PositionReader reader(m, head.hardware());
  std::array<double, kMaxActuators> positions{};
  std::array<double, kMaxFaceSignals> pose{};
  const std::span<const double> pos(positions.data(), m.actuators.size());
  const std::span<const double> face(pose.data(), m.layout.size());
  const double show_period = 1.0 / std::max(1.0, head.config().runtime.show_rate_hz);
  const double frame_period = 1.0 / std::max(1e-3, sinks.frame_rate_hz);
  const double length = input.duration();
  const auto ticks = static_cast<std::uint64_t>(std::llround(duration_s / period));
  std::uint64_t next_pose = 0, next_frame = 0;  // in ticks, counted without drift
  std::uint64_t poses = 0, frames = 0;
  for (std::uint64_t k = 0; k <= ticks; ++k) {
    const double t = static_cast<double>(k) * period;
    if (k >= next_pose) {
      input.evaluate(length > 0.0 && t > length ? std::fmod(t, length) : t, pose);
      head.send(pose);
      next_pose = static_cast<std::uint64_t>(
          std::ceil(static_cast<double>(++poses) * show_period / period - 1e-9));
    }
    head.step(period);
    const TelemetryRecord* r = head.telemetry()->front();
    if (r == nullptr) throw std::logic_error("simulate: the controller published no telemetry");
    reader.read(positions);
    if (sinks.stats != nullptr) sinks.stats->add(t, *r, pos);
    if (sinks.telemetry != nullptr) sinks.telemetry->add(t, *r, pos);
    if (sinks.plots != nullptr) sinks.plots->add(t, *r, pos);
    if (sinks.frame && k >= next_frame) {
      sinks.frame(face, pos);
      next_frame = static_cast<std::uint64_t>(
          std::ceil(static_cast<double>(++frames) * frame_period / period - 1e-9));
    }
    if (sinks.progress != nullptr) sinks.progress->update(t);
    drain(head);
  }
  run.ticks = ticks + 1;
  run.show_s = static_cast<double>(ticks) * period;
  if (sinks.stats != nullptr) sinks.stats->finish(run.show_s);
  if (sinks.progress != nullptr) sinks.progress->finish();
  return run;
}

}  // namespace facectl
