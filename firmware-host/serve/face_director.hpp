#pragma once

#include <array>
#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "control/capacity.hpp"
#include "control/command/face_command.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/inputs/show.hpp"

namespace facectl {

// The face command source of `facectl serve`: a non-real-time thread that
// publishes, at a fixed rate, whatever the operator chose: the neutral face, a
// show (then the next one queued), a held expression or a held pose. A change
// of source crossfades from the last command sent, so the command never jumps;
// the tick's shaper, envelope and limits apply as to any input.
class FaceDirector {
 public:
  using Pose = std::array<double, kMaxFaceSignals>;
  enum class Source { kNeutral, kShow, kExpression, kPose };

  struct Status {
    Source source = Source::kNeutral;
    std::string name;  // the show or expression
    double position_s = 0.0;
    double duration_s = 0.0;
    std::vector<std::string> queue;
  };

  static constexpr double kCrossfadeSeconds = 0.5;

  FaceDirector(const Pose& neutral, LatestValueMailbox<FaceCommand>& mailbox, double rate_hz);
  ~FaceDirector();
  FaceDirector(const FaceDirector&) = delete;
  FaceDirector& operator=(const FaceDirector&) = delete;

  void start();
  void stop();

  // Shows by the name the operator knows them by (the catalog's).
  void play(std::shared_ptr<const Show> show, std::string name);  // now, keeping the queue
  void enqueue(std::shared_ptr<const Show> show, std::string name);
  void stop_show();  // back to neutral; clears the queue
  void hold(Source source, std::string name, const Pose& pose);

  Status status() const;

 private:
  void run();
  void switch_to(Source source, std::string name, std::shared_ptr<const Show> show,
                 const Pose& pose, std::int64_t now);  // caller holds mutex_
  void compose(std::int64_t now, Pose& out);           // caller holds mutex_

  const Pose neutral_;
  LatestValueMailbox<FaceCommand>& mailbox_;
  double rate_hz_;

  mutable std::mutex mutex_;  // between the director thread and the API's threads only
  Source source_ = Source::kNeutral;
  std::string name_;
  std::shared_ptr<const Show> show_;
  struct Queued {
    std::shared_ptr<const Show> show;
    std::string name;
  };
  std::deque<Queued> queue_;
  Pose held_{};
  std::int64_t source_start_ns_ = 0;
  Pose fade_from_{};
  Pose last_{};

  std::thread thread_;
  std::atomic<bool> stop_{false};
};

std::string_view to_string(FaceDirector::Source source);

}  // namespace facectl
