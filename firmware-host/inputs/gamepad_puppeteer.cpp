#include "firmware-host/inputs/gamepad_puppeteer.hpp"

#include <cmath>
#include <ctime>

#include "control/realtime/loop_timer.hpp"

namespace facectl {

GamepadPuppeteer::GamepadPuppeteer(Source source, GamepadMapping mapping,
                                   const std::array<double, kMaxFaceSignals>& neutral,
                                   LatestValueMailbox<FaceCommand>& mailbox, double rate_hz,
                                   ShowRecorder* recorder)
    : source_(std::move(source)),
      mapping_(std::move(mapping)),
      neutral_(neutral),
      mailbox_(mailbox),
      rate_hz_(rate_hz),
      recorder_(recorder) {}

GamepadPuppeteer::~GamepadPuppeteer() {
  stop();
}

void GamepadPuppeteer::start() {
  thread_ = std::thread([this] {
    const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz_));
    std::int64_t deadline = monotonic_ns();
    while (!stop_.load(std::memory_order_relaxed)) {
      step(monotonic_ns());
      deadline += period_ns;
      timespec ts{static_cast<time_t>(deadline / 1'000'000'000),
                  static_cast<long>(deadline % 1'000'000'000)};
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    }
  });
}

void GamepadPuppeteer::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

void GamepadPuppeteer::step(std::int64_t now_ns) {
  while (source_(state_)) {
  }
  connected_.store(state_.connected, std::memory_order_relaxed);
  if (!state_.connected) return;
  if (t0_ns_ < 0) t0_ns_ = now_ns;
  command_.values = neutral_;
  mapping_.apply(state_, command_.values);
  ++command_.sequence;
  command_.stamp_ns = now_ns;
  mailbox_.publish(command_);
  published_.fetch_add(1, std::memory_order_relaxed);
  if (recorder_ != nullptr) {
    recorder_->add(static_cast<double>(now_ns - t0_ns_) * 1e-9, command_.values);
  }
}

}  // namespace facectl
