#include "firmware-host/inputs/mono_audio_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_limits.hpp"

namespace facectl {

MonoAudioReader::MonoAudioReader(const std::string& path, double max_seconds)
    : file_(nullptr, sf_close) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw ConfigError(path + ": expected a regular audio file, found " +
                      (std::filesystem::exists(path, ec) ? "something else" : "nothing"));
  }
  file_.reset(sf_open(path.c_str(), SFM_READ, &info_));
  if (!file_)
    throw ConfigError(path +
                      ": expected an audio file libsndfile reads, found: " + sf_strerror(nullptr));
  if (info_.frames <= 0 || info_.channels <= 0 || info_.samplerate <= 0) {
    throw ConfigError(path + ": expected audio samples, found none");
  }
  if (info_.samplerate < kMinAudioRate || info_.samplerate > kMaxAudioRate) {
    throw ConfigError(path + ": expected a sample rate of " + std::to_string(kMinAudioRate) +
                      " to " + std::to_string(kMaxAudioRate) + " Hz, found " +
                      std::to_string(info_.samplerate));
  }
  if (info_.channels > 64) {
    throw ConfigError(path + ": expected at most 64 channels, found " +
                      std::to_string(info_.channels));
  }
  seconds_ = static_cast<double>(info_.frames) / info_.samplerate;
  if (seconds_ > max_seconds) {
    throw ConfigError(path + ": expected at most " + std::to_string(max_seconds) +
                      " s of audio, found " + std::to_string(seconds_));
  }
}

std::size_t MonoAudioReader::read(std::vector<float>& out, std::size_t frames) {
  const auto channels = static_cast<std::size_t>(info_.channels);
  block_.resize(frames * channels);
  const sf_count_t n = sf_readf_float(file_.get(), block_.data(), static_cast<sf_count_t>(frames));
  const std::size_t got = n > 0 ? static_cast<std::size_t>(n) : 0;
  out.resize(got);
  for (std::size_t i = 0; i < got; ++i) {
    double sum = 0;  // mixed to mono
    for (std::size_t c = 0; c < channels; ++c) {
      const double x = block_[i * channels + c];
      const bool ok = std::isfinite(x) && std::abs(x) <= 1.0;
      clamped_ += !ok;
      sum += ok ? x : (std::isfinite(x) ? std::clamp(x, -1.0, 1.0) : 0.0);
    }
    out[i] = static_cast<float>(sum / static_cast<double>(channels));
  }
  return got;
}

std::string MonoAudioReader::clamped_note() const {
  if (clamped_ == 0) return {};
  return "clamped " + std::to_string(clamped_) +
         " samples that were not finite or beyond full scale (NaN read as 0)";
}

}  // namespace facectl
