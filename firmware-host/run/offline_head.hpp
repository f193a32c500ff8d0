#pragma once

#include <memory>
#include <string>

#include "control/controller.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/model/sim_twin.hpp"

namespace facectl {

// A head on simulated hardware, stepped in simulated time: the same
// Controller the real-time loop runs, driven tick by tick. Used by
// `facectl verify` and by the tests.
class OfflineHead {
 public:
  // `noiseless` zeroes the simulated measurement noise.
  explicit OfflineHead(LoadedConfig config, std::size_t telemetry = 0, bool noiseless = false);

  // Advances simulated time by dt and runs one tick.
  void step(double dt, int consecutive_overruns = 0);
  // Runs ticks of the configured period for `seconds`.
  void run_for(double seconds);
  // Publishes a face command (values in SI, layout order).
  void send(const std::array<double, kMaxFaceSignals>& values);

  LoadedConfig& config() { return *config_; }
  const ControllerModel& model() const { return config_->built.model; }
  Controller& controller() { return *controller_; }
  SimHardware& hardware() { return *hardware_; }
  SpscRing<TelemetryRecord>* telemetry() { return telemetry_.get(); }
  SpscRing<TransitionEvent>& events() { return events_; }
  double time() const { return static_cast<double>(now_ns_) * 1e-9; }
  double period() const { return 1.0 / model().rate_hz; }

 private:
  std::unique_ptr<LoadedConfig> config_;
  std::unique_ptr<SimHardware> hardware_;
  LatestValueMailbox<FaceCommand> mailbox_;
  std::unique_ptr<SpscRing<TelemetryRecord>> telemetry_;
  SpscRing<TransitionEvent> events_{1024};
  std::unique_ptr<Controller> controller_;
  std::int64_t now_ns_ = 1'000'000'000;
  std::uint64_t tick_ = 0;
  std::uint64_t sequence_ = 0;
};

}  // namespace facectl
