#include "firmware-host/inputs/show_player.hpp"

#include <cmath>
#include <ctime>

#include "control/realtime/loop_timer.hpp"

namespace facectl {

ShowPlayer::ShowPlayer(const Show& show, LatestValueMailbox<FaceCommand>& mailbox, double rate_hz,
                       bool loop)
    : ShowPlayer(
          [&show](double t, std::array<double, kMaxFaceSignals>& out) { show.evaluate(t, out); },
          show.duration(), mailbox, rate_hz, loop) {}

ShowPlayer::ShowPlayer(PoseSource source, double duration_s,
                       LatestValueMailbox<FaceCommand>& mailbox, double rate_hz, bool loop,
                       ShowRecorder* recorder)
    : source_(std::move(source)),
      duration_s_(duration_s),
      mailbox_(mailbox),
      recorder_(recorder),
      rate_hz_(rate_hz),
      loop_(loop) {}

ShowPlayer::~ShowPlayer() {
  stop();
}

void ShowPlayer::start() {
  thread_ = std::thread([this] { run(); });
}

void ShowPlayer::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

void ShowPlayer::run() {
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz_));
  const std::int64_t t0 = monotonic_ns();
  std::int64_t deadline = t0;
  FaceCommand cmd;
  while (!stop_.load(std::memory_order_relaxed)) {
    const std::int64_t now = monotonic_ns();
    double t = clock_ ? clock_(now) : static_cast<double>(now - t0) * 1e-9;
    const double duration = duration_s_;
    if (t >= duration) {
      if (loop_ && duration > 0.0) {
        t = std::fmod(t, duration);
      } else {
        finished_.store(true, std::memory_order_relaxed);
      }
    }
    const bool gave_way = give_way_ && finished_.load(std::memory_order_relaxed);
    if (!silent_.load(std::memory_order_relaxed) && !gave_way) {
      source_(t, cmd.values);
      if (recorder_) recorder_->add(static_cast<double>(now - t0) * 1e-9, cmd.values);
      ++cmd.sequence;
      cmd.stamp_ns = now;
      mailbox_.publish(cmd);
    }
    deadline += period_ns;
    timespec ts{static_cast<time_t>(deadline / 1'000'000'000),
                static_cast<long>(deadline % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
  }
}

}  // namespace facectl
