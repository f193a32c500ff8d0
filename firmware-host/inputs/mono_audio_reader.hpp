// An audio file read through libsndfile as mono samples, in blocks, after the
// checks every audio input shares: a readable file, samples, a sample rate
// and a length within input_limits.hpp.
#pragma once

#include <sndfile.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace facectl {

class MonoAudioReader {
 public:
  // Throws ConfigError naming `path` for a file libsndfile cannot read, no
  // samples, a sample rate outside kMinAudioRate..kMaxAudioRate, more than 64
  // channels, or more than `max_seconds` of audio.
  MonoAudioReader(const std::string& path, double max_seconds);

  // Reads up to `frames` frames into `out` (resized to what was read), each
  // the mean of its channels. Samples that are not finite or beyond full
  // scale (a float file can hold them) are clamped, NaN read as 0, and
  // counted in clamped(). Returns how many were read; 0 at the end.
  std::size_t read(std::vector<float>& out, std::size_t frames);

  int sample_rate() const { return info_.samplerate; }
  int channels() const { return info_.channels; }
  double seconds() const { return seconds_; }
  std::uint64_t clamped() const { return clamped_; }
  // "clamped N samples ..." when some were, for the input's notes.
  std::string clamped_note() const;

 private:
  std::unique_ptr<SNDFILE, int (*)(SNDFILE*)> file_;
  SF_INFO info_{};
  double seconds_ = 0.0;
  std::uint64_t clamped_ = 0;
  std::vector<float> block_;  // interleaved
};

}  // namespace facectl
