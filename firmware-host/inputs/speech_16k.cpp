#include "firmware-host/inputs/speech_16k.hpp"

#include <samplerate.h>

#include <cmath>
#include <memory>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/mono_audio_reader.hpp"

namespace facectl {
namespace {

constexpr std::size_t kBlock = 4096;

void append_int16(std::vector<std::int16_t>& out, const float* in, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n);
  // Scales by 32768 and clips: MonoAudioReader has already clamped to +-1.
  src_float_to_short_array(in, out.data() + at, static_cast<int>(n));
}

}  // namespace

Speech16k read_speech_16k(const std::string& path, double max_seconds) {
  MonoAudioReader audio(path, max_seconds);
  Speech16k out;
  out.seconds = audio.seconds();
  out.source_rate = audio.sample_rate();
  out.source_channels = audio.channels();
  const double ratio = static_cast<double>(kSpeechRate) / audio.sample_rate();
  out.samples.reserve(static_cast<std::size_t>(std::ceil(out.seconds * kSpeechRate)) + kBlock);
  std::vector<float> in;
  if (audio.sample_rate() == kSpeechRate) {
    while (audio.read(in, kBlock) > 0) append_int16(out.samples, in.data(), in.size());
  } else {
    int err = 0;
    const std::unique_ptr<SRC_STATE, SRC_STATE* (*)(SRC_STATE*)> src(
        src_new(SRC_SINC_MEDIUM_QUALITY, 1, &err), src_delete);
    if (!src) throw ConfigError(path + ": resampling to 16 kHz failed: " + src_strerror(err));
    std::vector<float> resampled(static_cast<std::size_t>(std::ceil(kBlock * ratio)) + 64);
    bool end = false;
    while (!end) {
      end = audio.read(in, kBlock) == 0;
      SRC_DATA d{};
      d.data_in = in.data();
      d.input_frames = static_cast<long>(in.size());
      d.src_ratio = ratio;
      d.end_of_input = end ? 1 : 0;
      // At the end the converter drains its filter's delay in as many calls
      // as that takes; before it, every input frame is taken in one call.
      do {
        d.data_out = resampled.data();
        d.output_frames = static_cast<long>(resampled.size());
        if (const int e = src_process(src.get(), &d); e != 0) {
          throw ConfigError(path + ": resampling to 16 kHz failed: " + src_strerror(e));
        }
        append_int16(out.samples, resampled.data(), static_cast<std::size_t>(d.output_frames_gen));
        if (d.input_frames_used == 0 && d.output_frames_gen == 0) break;  // no progress
        d.data_in += d.input_frames_used;
        d.input_frames -= d.input_frames_used;
      } while (d.input_frames > 0 || (end && d.output_frames_gen > 0));
    }
    out.notes.push_back("resampled from " + std::to_string(out.source_rate) +
                        " Hz to 16 kHz for the phone recogniser");
  }
  if (const std::string n = audio.clamped_note(); !n.empty()) out.notes.push_back(n);
  return out;
}

}  // namespace facectl
