// Speech audio as a speech recogniser's models want it: 16 kHz, mono,
// 16-bit. Files at other rates are resampled with libsamplerate.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facectl {

inline constexpr int kSpeechRate = 16000;

struct Speech16k {
  std::vector<std::int16_t> samples;  // mono, kSpeechRate per second
  double seconds = 0.0;               // the file's length
  int source_rate = 0;                // the file's sample rate
  int source_channels = 0;
  std::vector<std::string> notes;  // samples clamped, resampling
};

// Reads `path` through libsndfile (MonoAudioReader: channels averaged,
// out-of-range samples clamped) and resamples it to 16 kHz with
// libsamplerate's SRC_SINC_MEDIUM_QUALITY, whose band limit is well above
// the 6.8 kHz the en-us model's filter bank reaches. Throws ConfigError
// naming the file as MonoAudioReader does, for more than `max_seconds`, and
// for a resampler error.
Speech16k read_speech_16k(const std::string& path, double max_seconds);

}  // namespace facectl
