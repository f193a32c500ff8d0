#include "firmware-host/inputs/input_mix.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "control/clock.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {
namespace {

constexpr std::uint8_t kUnassigned = 0xff;

MixSource source_named(const std::string& name) {
  const auto& names = mix_source_names();
  return static_cast<MixSource>(std::find(names.begin(), names.end(), name) - names.begin());
}

// The sources of `names` this run has, in their order.
std::vector<MixSource> present_of(const std::vector<std::string>& names,
                                  const std::vector<MixSource>& present) {
  std::vector<MixSource> out;
  for (const std::string& n : names) {
    const MixSource s = source_named(n);
    if (std::find(present.begin(), present.end(), s) != present.end()) out.push_back(s);
  }
  return out;
}

}  // namespace

const char* to_string(MixSource s) {
  return mix_source_names()[static_cast<std::size_t>(s)].c_str();
}

InputMixPlan resolve_input_mix(const MixConfig& config, const FaceLayout& layout,
                               const std::vector<MixSource>& present, double default_rate_hz) {
  InputMixPlan plan;
  plan.signals = layout.size();
  plan.group_of.fill(kUnassigned);
  for (std::size_t g = 0; g < config.groups.size(); ++g) {
    const MixGroupConfig& group = config.groups[g];
    for (std::size_t p = 0; p < group.signals.size(); ++p) {
      bool matched = false;
      for (std::size_t i = 0; i < layout.size(); ++i) {
        const std::string key = yaml_key(layout.signal(i));
        if (fnmatch(group.signals[p].c_str(), key.c_str(), 0) != 0) continue;
        matched = true;
        if (plan.group_of[i] != kUnassigned && plan.group_of[i] != g) {
          throw ConfigError(group.signals_where[p] + ": expected each signal in one group, found " +
                            key + " in groups " + plan.group_names[plan.group_of[i]] + " and " +
                            group.name);
        }
        plan.group_of[i] = static_cast<std::uint8_t>(g);
      }
      if (!matched) {
        throw ConfigError(group.signals_where[p] +
                          ": expected a signal key or pattern of the head (jaw_pitch_deg, "
                          "frontalis_*), found '" +
                          group.signals[p] + "', which matches none");
      }
    }
    plan.group_names.push_back(group.name);
    plan.sources.push_back(present_of(group.sources, present));
  }
  plan.group_names.emplace_back("others");
  plan.sources.push_back(present_of(config.others, present));
  const auto others = static_cast<std::uint8_t>(plan.group_names.size() - 1);
  for (std::size_t i = 0; i < layout.size(); ++i) {
    if (plan.group_of[i] == kUnassigned) plan.group_of[i] = others;
  }
  for (const MixSource s : present) {
    const bool played = std::any_of(plan.sources.begin(), plan.sources.end(), [s](const auto& l) {
      return std::find(l.begin(), l.end(), s) != l.end();
    });
    if (!played) {
      throw ConfigError(std::string("mix: expected every source of the run in a group's sources or "
                                    "in others, found ") +
                        to_string(s) + " in none");
    }
  }
  plan.stale_ns = static_cast<std::int64_t>(config.stale_ms * 1e6);
  plan.fade_ns = static_cast<std::int64_t>(config.fade_ms * 1e6);
  plan.rate_hz = config.rate_hz > 0.0 ? config.rate_hz : default_rate_hz;
  return plan;
}

InputMixer::InputMixer(InputMixPlan plan, const std::array<double, kMaxFaceSignals>& neutral,
                       LatestValueMailbox<FaceCommand>& out, ShowRecorder* recorder)
    : plan_(std::move(plan)),
      neutral_(neutral),
      out_(out),
      recorder_(recorder),
      groups_(plan_.group_names.size()) {
  cmd_.values = neutral_;
  for (Group& g : groups_) g.fade_from = neutral_;
}

InputMixer::~InputMixer() {
  stop();
}

bool InputMixer::step(std::int64_t now_ns) {
  for (std::size_t s = 0; s < kMixSources; ++s) {
    if (inputs_[s].consume(scratch_)) {
      latest_[s].values = scratch_.values;
      latest_[s].stamp_ns = scratch_.stamp_ns;
      latest_[s].received_ns = now_ns;
      latest_[s].seen = true;
      latest_[s].fresh = true;
    }
  }
  const auto live = [&](MixSource s) {
    const Latest& l = latest_[index(s)];
    return l.seen && now_ns - l.received_ns < plan_.stale_ns;
  };
  bool any_live = false;
  bool news = false;  // a group's source sent a pose since the last publish, or a group fades
  std::int64_t stamp = 0;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    int winner = -1;
    for (const MixSource s : plan_.sources[g]) {
      if (live(s)) {
        winner = static_cast<int>(index(s));
        break;
      }
    }
    Group& group = groups_[g];
    if (winner != group.current) {
      group.fade_from = cmd_.values;  // from what the tick was last given
      group.fade_start_ns = now_ns;
      group.current = winner;
      ++group.changes;
    }
    if (winner >= 0) {
      any_live = true;
      stamp = std::max(stamp, latest_[static_cast<std::size_t>(winner)].stamp_ns);
      news = news || latest_[static_cast<std::size_t>(winner)].fresh;
    }
    news = news || now_ns - group.fade_start_ns < plan_.fade_ns;
  }
  if (!any_live) {
    // The tick's input watchdog eases to neutral; a source that comes back
    // fades in from there, as at the start.
    cmd_.values = neutral_;
    return false;
  }
  // A pose repeated would look fresh to the tick's watchdog (it counts
  // sequence numbers): only what is new is published, so a source that stops
  // is noticed by the tick after input_timeout_ms, as without a mix.
  if (!news || silent_.load(std::memory_order_relaxed)) return false;
  for (Latest& l : latest_) l.fresh = false;
  for (std::size_t i = 0; i < plan_.signals; ++i) {
    const Group& group = groups_[plan_.group_of[i]];
    const double target = group.current >= 0
                              ? latest_[static_cast<std::size_t>(group.current)].values[i]
                              : neutral_[i];
    const double a = plan_.fade_ns > 0
                         ? std::clamp(static_cast<double>(now_ns - group.fade_start_ns) /
                                          static_cast<double>(plan_.fade_ns),
                                      0.0, 1.0)
                         : 1.0;
    cmd_.values[i] = group.fade_from[i] + a * (target - group.fade_from[i]);
  }
  ++cmd_.sequence;
  cmd_.stamp_ns = stamp;
  out_.publish(cmd_);
  if (first_publish_ns_ < 0) first_publish_ns_ = now_ns;
  if (recorder_ != nullptr) {
    recorder_->add(static_cast<double>(now_ns - first_publish_ns_) * 1e-9, cmd_.values);
  }
  return true;
}

void InputMixer::start() {
  thread_ = std::thread([this] { run(); });
}

void InputMixer::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

void InputMixer::run() {
  const auto period_ns = static_cast<std::int64_t>(std::llround(1e9 / plan_.rate_hz));
  std::int64_t deadline = monotonic_ns();
  while (!stop_.load(std::memory_order_relaxed)) {
    step(monotonic_ns());
    deadline += period_ns;
    const timespec ts{static_cast<time_t>(deadline / 1'000'000'000),
                      static_cast<long>(deadline % 1'000'000'000)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
  }
}

std::string InputMixer::describe() const {
  std::string out;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (!out.empty()) out += ", ";
    out += plan_.group_names[g] + ": ";
    out +=
        groups_[g].current >= 0 ? to_string(static_cast<MixSource>(groups_[g].current)) : "neutral";
    // The first change is from nothing to the first live source.
    if (const std::uint64_t n = groups_[g].changes; n > 1) {
      out += " (changed source " + std::to_string(n - 1) + (n == 2 ? " time)" : " times)");
    }
  }
  return out;
}

}  // namespace facectl
