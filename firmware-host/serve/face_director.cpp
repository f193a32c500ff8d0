#include "firmware-host/serve/face_director.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "control/realtime/loop_timer.hpp"

namespace facectl {

std::string_view to_string(FaceDirector::Source source) {
  switch (source) {
    case FaceDirector::Source::kNeutral:
      return "neutral";
    case FaceDirector::Source::kShow:
      return "show";
    case FaceDirector::Source::kExpression:
      return "expression";
    case FaceDirector::Source::kPose:
      return "pose";
  }
  return "?";
}

FaceDirector::FaceDirector(const Pose& neutral, LatestValueMailbox<FaceCommand>& mailbox,
                           double rate_hz)
    : neutral_(neutral), mailbox_(mailbox), rate_hz_(rate_hz), last_(neutral) {
  fade_from_ = neutral;
}

FaceDirector::~FaceDirector() {
  stop();
}

void FaceDirector::start() {
  source_start_ns_ = monotonic_ns();
  thread_ = std::thread([this] { run(); });
}

void FaceDirector::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

void FaceDirector::switch_to(Source source, std::string name, std::shared_ptr<const Show> show,
                             const Pose& pose, std::int64_t now) {
  fade_from_ = last_;
  source_ = source;
  name_ = std::move(name);
  show_ = std::move(show);
  held_ = pose;
  source_start_ns_ = now;
}

void FaceDirector::play(std::shared_ptr<const Show> show, std::string name) {
  const std::lock_guard lock(mutex_);
  switch_to(Source::kShow, std::move(name), std::move(show), neutral_, monotonic_ns());
}

void FaceDirector::enqueue(std::shared_ptr<const Show> show, std::string name) {
  const std::lock_guard lock(mutex_);
  if (source_ == Source::kShow) {
    queue_.push_back({std::move(show), std::move(name)});
  } else {
    switch_to(Source::kShow, std::move(name), std::move(show), neutral_, monotonic_ns());
  }
}

void FaceDirector::stop_show() {
  const std::lock_guard lock(mutex_);
  queue_.clear();
  if (source_ == Source::kShow) switch_to(Source::kNeutral, "", nullptr, neutral_, monotonic_ns());
}

void FaceDirector::hold(Source source, std::string name, const Pose& pose) {
  const std::lock_guard lock(mutex_);
  switch_to(source, std::move(name), nullptr, pose, monotonic_ns());
}

FaceDirector::Status FaceDirector::status() const {
  const std::lock_guard lock(mutex_);
  Status s;
  s.source = source_;
  s.name = name_;
  if (show_) {
    s.duration_s = show_->duration();
    s.position_s =
        std::min(s.duration_s, static_cast<double>(monotonic_ns() - source_start_ns_) * 1e-9);
  }
  for (const auto& q : queue_) s.queue.push_back(q.name);
  return s;
}

void FaceDirector::compose(std::int64_t now, Pose& out) {
  double t = static_cast<double>(now - source_start_ns_) * 1e-9;
  if (source_ == Source::kShow && t >= show_->duration()) {
    // The show is over: the next one queued, else the neutral face.
    if (!queue_.empty()) {
      Queued next = std::move(queue_.front());
      queue_.pop_front();
      switch_to(Source::kShow, std::move(next.name), std::move(next.show), neutral_, now);
    } else {
      switch_to(Source::kNeutral, "", nullptr, neutral_, now);
    }
    t = 0.0;
  }
  if (source_ == Source::kShow) {
    show_->evaluate(t, out);
  } else {
    out = held_;
  }
  if (t < kCrossfadeSeconds) {
    const double u = t / kCrossfadeSeconds;
    const double w = u * u * (3.0 - 2.0 * u);
    for (std::size_t i = 0; i < out.size(); ++i)
      out[i] = fade_from_[i] + w * (out[i] - fade_from_[i]);
  }
  last_ = out;
}

void FaceDirector::run() {
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / rate_hz_));
  std::int64_t deadline = monotonic_ns();
  FaceCommand cmd;
  while (!stop_.load(std::memory_order_relaxed)) {
    const std::int64_t now = monotonic_ns();
    {
      const std::lock_guard lock(mutex_);
      compose(now, cmd.values);
    }
    ++cmd.sequence;
    cmd.stamp_ns = now;
    mailbox_.publish(cmd);
    deadline = std::max(deadline + period_ns, now);
    timespec ts{static_cast<time_t>(deadline / 1'000'000'000),
                static_cast<long>(deadline % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
  }
}

}  // namespace facectl
