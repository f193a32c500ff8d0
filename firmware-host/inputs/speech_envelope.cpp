#include "firmware-host/inputs/speech_envelope.hpp"

#include <sndfile.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"

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
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ConfigError(path + ": expected a regular audio file, found " +
                      (std::filesystem::exists(path, ec) ? "something else" : "nothing"));
  }
  SF_INFO info{};
  const std::unique_ptr<SNDFILE, int (*)(SNDFILE*)> file(sf_open(path.c_str(), SFM_READ, &info),
                                                         sf_close);
  if (!file)
    throw ConfigError(path +
                      ": expected an audio file libsndfile reads, found: " + sf_strerror(nullptr));
  if (info.frames <= 0 || info.channels <= 0 || info.samplerate <= 0) {
    throw ConfigError(path + ": expected audio samples, found none");
  }
  if (info.samplerate < kMinAudioRate || info.samplerate > kMaxAudioRate) {
    throw ConfigError(path + ": expected a sample rate of " + std::to_string(kMinAudioRate) +
                      " to " + std::to_string(kMaxAudioRate) + " Hz, found " +
                      std::to_string(info.samplerate));
  }
  if (info.channels > 64) {
    throw ConfigError(path + ": expected at most 64 channels, found " +
                      std::to_string(info.channels));
  }
  const double seconds = static_cast<double>(info.frames) / info.samplerate;
  if (seconds > kMaxAudioSeconds) {
    throw ConfigError(path + ": expected at most " + std::to_string(kMaxAudioSeconds) +
                      " s of audio, found " + std::to_string(seconds));
  }
  LevelMeter meter(info.samplerate, params.rate_hz);
  std::vector<float> block(4096 * static_cast<std::size_t>(info.channels));
  std::uint64_t bad = 0;  // non-finite or beyond full scale: a float file can hold anything
  for (;;) {
    const sf_count_t n = sf_readf_float(file.get(), block.data(), 4096);
    if (n <= 0) break;
    for (sf_count_t i = 0; i < n; ++i) {
      double sum = 0;  // mixed to mono
      for (int c = 0; c < info.channels; ++c) {
        const double x = block[static_cast<std::size_t>(i * info.channels + c)];
        const bool ok = std::isfinite(x) && std::abs(x) <= 1.0;
        bad += !ok;
        sum += ok ? x : (std::isfinite(x) ? std::clamp(x, -1.0, 1.0) : 0.0);
      }
      meter.add(sum / info.channels);
    }
  }
  if (bad > 0) {
    notes.push_back("clamped " + std::to_string(bad) +
                    " samples that were not finite or beyond full scale (NaN read as 0)");
  }
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
      seconds, info.samplerate, info.channels, params.open_deg);
  notes.push_back(note);
  return track;
}

}  // namespace facectl
