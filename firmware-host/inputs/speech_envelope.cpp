#include "firmware-host/inputs/speech_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/mono_audio_reader.hpp"

namespace facectl {
namespace {

constexpr double kWindowS = 0.020;
constexpr double kSilentDb = -120.0;  // digital silence, in place of -inf

double percentile(std::vector<double> v, double p) {
  const auto k = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

// RMS level in dB of 20 ms windows every 1/rate_hz, streamed: only the levels
// are kept, never the samples.
class LevelMeter {
 public:
  LevelMeter(double sample_rate, double rate_hz)
      : window_(std::max<std::size_t>(1, static_cast<std::size_t>(kWindowS * sample_rate))),
        hop_(std::max(1.0, sample_rate / rate_hz)),
        squares_(window_, 0.0) {}

  void add(double x) {
    sum_ += x * x - squares_[at_];
    squares_[at_] = x * x;
    at_ = (at_ + 1) % window_;
    ++count_;
    if (static_cast<double>(count_) >= next_) {
      const double rms = std::sqrt(std::max(sum_, 0.0) / static_cast<double>(window_));
      levels_.push_back(rms > 0 ? std::max(20.0 * std::log10(rms), kSilentDb) : kSilentDb);
      next_ += hop_;
    }
  }
  const std::vector<double>& levels() const { return levels_; }

 private:
  std::size_t window_;
  double hop_;
  std::vector<double> squares_;
  std::size_t at_ = 0;
  double sum_ = 0;
  std::uint64_t count_ = 0;
  double next_ = 1;
  std::vector<double> levels_;
};

std::vector<double> openness_of_levels(const std::vector<double>& levels,
                                       const SpeechEnvelopeParams& p) {
  std::vector<double> out(levels.size(), 0.0);
  if (levels.empty()) return out;
  const double loud = percentile(levels, 0.95);
  const double floor = std::max(percentile(levels, 0.10), loud - p.range_db);
  const double span = std::max(loud - floor, 1.0);
  const double dt = 1.0 / p.rate_hz;
  const double a_up = 1.0 - std::exp(-dt / p.attack_s);
  const double a_down = 1.0 - std::exp(-dt / p.release_s);
  double y = 0;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const double target = std::clamp((levels[i] - floor) / span, 0.0, 1.0);
    y += (target > y ? a_up : a_down) * (target - y);
    out[i] = y;
  }
  return out;
}

}  // namespace

std::vector<double> speech_openness(const std::vector<float>& mono, double sample_rate,
                                    const SpeechEnvelopeParams& params) {
  LevelMeter meter(sample_rate, params.rate_hz);
  for (float x : mono) meter.add(x);
  return openness_of_levels(meter.levels(), params);
}

PoseTrack speech_envelope_track(const std::string& path, const FaceLayout& layout,
                                const std::array<double, kMaxFaceSignals>& neutral,
                                const SpeechEnvelopeParams& params,
                                std::vector<std::string>& notes) {
  MonoAudioReader audio(path, kMaxAudioSeconds);
  LevelMeter meter(audio.sample_rate(), params.rate_hz);
  std::vector<float> block;
  while (audio.read(block, 4096) > 0) {
    for (float x : block) meter.add(x);
  }
  if (audio.clamped() > 0) notes.push_back(audio.clamped_note());
  const std::vector<double> open = openness_of_levels(meter.levels(), params);
  if (open.empty()) throw ConfigError(path + ": expected audio samples, found none");

  PoseTrack track(layout.size());
  track.reserve(open.size());
  const std::size_t lead = static_cast<std::size_t>(std::lround(params.lead_s * params.rate_hz));
  const double open_rad = params.open_deg * M_PI / 180.0;
  for (std::size_t i = 0; i < open.size(); ++i) {
    std::array<double, kMaxFaceSignals> pose = neutral;
    // Leading: the pose at t is the sound's at t + lead.
    pose[layout.jaw_pitch()] += open_rad * open[std::min(i + lead, open.size() - 1)];
    track.add(static_cast<double>(i) / params.rate_hz, pose);
  }
  char note[160];
  std::snprintf(
      note, sizeof note,
      "speech-driven jaw from %.1f s of audio at %d Hz, %d channel(s): opens up to %.0f deg",
      audio.seconds(), audio.sample_rate(), audio.channels(), params.open_deg);
  notes.push_back(note);
  return track;
}

}  // namespace facectl
