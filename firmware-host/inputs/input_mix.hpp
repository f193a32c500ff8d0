#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "control/capacity.hpp"
#include "control/command/face_command.hpp"
#include "control/command/face_layout.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "firmware-host/config/mix_config.hpp"
#include "firmware-host/inputs/show_recorder.hpp"

namespace facectl {

// The inputs `facectl run` can mix, as the runtime file's `mix:` names them.
enum class MixSource : std::uint8_t { kShow, kInput, kGamepad, kFapStream, kLiveLinkFace, kMidi };
constexpr std::size_t kMixSources = 6;
const char* to_string(MixSource s);

// The `mix:` block resolved against the head's signals and the sources this
// run has: each signal's group, and each group's present sources in priority
// order. The last group is "others", the signals no group names.
struct InputMixPlan {
  std::vector<std::string> group_names;
  std::array<std::uint8_t, kMaxFaceSignals> group_of{};
  std::vector<std::vector<MixSource>> sources;
  std::size_t signals = 0;
  std::int64_t stale_ns = 0;
  std::int64_t fade_ns = 0;
  double rate_hz = 0.0;
};

// Throws ConfigError naming the pattern's line: a pattern that matches no
// signal, a signal two groups claim, a source present that no group plays.
InputMixPlan resolve_input_mix(const MixConfig& config, const FaceLayout& layout,
                               const std::vector<MixSource>& present, double default_rate_hz);

// Several sources at once: each publishes into its own mailbox here, and
// each step takes, for every group, the first source of its list that sent a
// pose within stale_ms, crossfading over fade_ms when that changes; a group
// with none live eases to neutral. A mix is published only when a playing
// source sent something new (or a group fades), and never when no source is
// live, so the tick's input watchdog sees a lost source as it would without
// a mix and eases the face to neutral. The result goes into the tick's mailbox (and the
// recorder), where the sanitiser, envelope and limits apply as to any input.
// step() allocates nothing; the recorder, when given, does.
class InputMixer {
 public:
  InputMixer(InputMixPlan plan, const std::array<double, kMaxFaceSignals>& neutral,
             LatestValueMailbox<FaceCommand>& out, ShowRecorder* recorder = nullptr);
  ~InputMixer();
  InputMixer(const InputMixer&) = delete;
  InputMixer& operator=(const InputMixer&) = delete;

  // Where `s` publishes (its single producer).
  LatestValueMailbox<FaceCommand>& input(MixSource s) { return inputs_[index(s)]; }

  void start();  // steps at the plan's rate on its own thread
  void stop();
  // Publishes nothing more (fault rehearsal: --inject input_loss).
  void go_silent() { silent_.store(true, std::memory_order_relaxed); }
  // One mix at `now_ns` (CLOCK_MONOTONIC); true when it published.
  bool step(std::int64_t now_ns);

  // The source each group plays now (-1: none live, neutral), and how often
  // it changed; read after stop() or from step()'s thread.
  int playing(std::size_t group) const { return groups_[group].current; }
  std::uint64_t changes(std::size_t group) const { return groups_[group].changes; }
  const InputMixPlan& plan() const { return plan_; }
  // "mouth: input (changed source 2 times), brows: live_link_face, others: show".
  std::string describe() const;

 private:
  static std::size_t index(MixSource s) { return static_cast<std::size_t>(s); }
  void run();

  struct Latest {
    std::array<double, kMaxFaceSignals> values{};
    std::int64_t received_ns = 0;  // when step() took it
    std::int64_t stamp_ns = 0;     // when its producer made it
    bool seen = false;
    bool fresh = false;  // not yet in a published mix
  };
  struct Group {
    int current = -1;
    std::int64_t fade_start_ns = 0;
    std::array<double, kMaxFaceSignals> fade_from{};
    std::uint64_t changes = 0;
  };

  const InputMixPlan plan_;
  const std::array<double, kMaxFaceSignals> neutral_;
  LatestValueMailbox<FaceCommand>& out_;
  ShowRecorder* recorder_;
  std::array<LatestValueMailbox<FaceCommand>, kMixSources> inputs_;
  std::array<Latest, kMixSources> latest_;
  std::vector<Group> groups_;  // sized once, by the plan
  FaceCommand cmd_;            // the last published
  FaceCommand scratch_;
  std::int64_t first_publish_ns_ = -1;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> silent_{false};
};

}  // namespace facectl
