#include "firmware-host/run/offline_head.hpp"

#include <cmath>

namespace facectl {

OfflineHead::OfflineHead(LoadedConfig config, std::size_t telemetry, bool noiseless)
    : config_(std::make_unique<LoadedConfig>(std::move(config))) {
  if (noiseless) {
    for (auto& a : config_->rig.actuators) a.plant.noise_stddev = 0.0;
  }
  hardware_ = make_sim_hardware(model(), config_->rig);
  if (telemetry > 0) telemetry_ = std::make_unique<SpscRing<TelemetryRecord>>(telemetry);
  controller_ =
      std::make_unique<Controller>(model(), hardware_->seams, hardware_->io,
                                   ControllerChannels{&mailbox_, telemetry_.get(), &events_});
}

void OfflineHead::step(double dt, int consecutive_overruns) {
  now_ns_ += static_cast<std::int64_t>(std::llround(dt * 1e9));
  TickTiming t;
  t.tick = tick_++;
  t.now_ns = now_ns_;
  t.time_s = time();
  t.dt_s = dt;
  t.consecutive_overruns = consecutive_overruns;
  controller_->tick(t);
}

void OfflineHead::run_for(double seconds) {
  const auto n = static_cast<long>(std::llround(seconds / period()));
  for (long i = 0; i < n; ++i) step(period());
}

void OfflineHead::send(const std::array<double, kMaxFaceSignals>& values) {
  FaceCommand cmd;
  cmd.values = values;
  cmd.sequence = ++sequence_;
  cmd.stamp_ns = now_ns_;
  mailbox_.publish(cmd);
}

}  // namespace facectl
