#include "firmware-host/inputs/audio_playback.hpp"

#include <alsa/asoundlib.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "control/clock.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/alsa_messages.hpp"
#include "firmware-host/inputs/input_limits.hpp"

namespace facectl {
namespace {

constexpr std::size_t kChunk = 256;  // frames a write: 16 ms at 16 kHz, 5 ms at 48 kHz

std::string alsa_error(int err) {
  return snd_strerror(err);
}

}  // namespace

AudioPlayback::AudioPlayback(const std::string& path, const AudioConfig& config)
    : path_(path), device_(config.device), reader_(path, kMaxAudioSeconds) {
  rate_ = reader_.sample_rate();
  stats_.file_s = reader_.seconds();
  quiet_alsa_lib();
  int err = snd_pcm_open(&pcm_, device_.c_str(), SND_PCM_STREAM_PLAYBACK, 0);
  if (err < 0) {
    pcm_ = nullptr;
    throw ConfigError("audio.device '" + device_ + "': cannot open it for playback: " +
                      alsa_error(err) + " (aplay -L lists the devices)");
  }
  // Mono, 16-bit: what every device takes; ALSA's plug layer resamples when
  // the device does not run at the file's rate.
  err = snd_pcm_set_params(pcm_, SND_PCM_FORMAT_S16, SND_PCM_ACCESS_RW_INTERLEAVED, 1,
                           static_cast<unsigned>(rate_), 1,
                           static_cast<unsigned>(std::lround(config.buffer_s * 1e6)));
  if (err < 0) {
    snd_pcm_close(pcm_);
    pcm_ = nullptr;
    throw ConfigError("audio.device '" + device_ + "': cannot play mono 16-bit at " +
                      std::to_string(rate_) + " Hz: " + alsa_error(err) +
                      " (a plughw: device converts)");
  }
  // Each status then says when, on CLOCK_MONOTONIC, the device last moved
  // its position: the clock is set for that moment, not for when it was
  // asked (a device may move its position a period at a time).
  snd_pcm_sw_params_t* sw = nullptr;
  snd_pcm_sw_params_alloca(&sw);
  if (snd_pcm_sw_params_current(pcm_, sw) == 0 &&
      snd_pcm_sw_params_set_tstamp_mode(pcm_, sw, SND_PCM_TSTAMP_ENABLE) == 0 &&
      snd_pcm_sw_params_set_tstamp_type(pcm_, sw, SND_PCM_TSTAMP_TYPE_MONOTONIC) == 0) {
    snd_pcm_sw_params(pcm_, sw);  // without it, the clock is set for the time it was asked
  }
}

AudioPlayback::~AudioPlayback() {
  stop();
  if (pcm_ != nullptr) snd_pcm_close(pcm_);
}

void AudioPlayback::start() {
  thread_ = std::thread([this] { run(); });
}

void AudioPlayback::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

AudioStats AudioPlayback::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

// The frame heard is the last one written less what the device still holds
// (the delay: buffered plus the hardware's own), at the status's timestamp.
void AudioPlayback::publish(bool running) {
  snd_pcm_status_t* status = nullptr;
  snd_pcm_status_alloca(&status);
  snd_pcm_sframes_t delay = 0;
  bool moving = false;
  const int err = snd_pcm_status(pcm_, status);
  const std::int64_t asked = monotonic_ns();
  std::int64_t now = asked;
  if (err == 0) {
    delay = snd_pcm_status_get_delay(status);
    moving = running && snd_pcm_status_get_state(status) == SND_PCM_STATE_RUNNING;
    snd_htimestamp_t ts{};
    snd_pcm_status_get_htstamp(status, &ts);
    const std::int64_t at = static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
    if (at > 0 && at <= asked && asked - at < 1'000'000'000) now = at;
  }
  if (moving && started_ns_ == 0) started_ns_ = now;
  double heard_s = static_cast<double>(std::max<std::int64_t>(0, written_ - delay)) / rate_;
  // A device without a clock (ALSA's null, a file plugin) takes the sound
  // at once; the face then keeps real time. 0.1% over it allows any sound
  // card's crystal.
  if (started_ns_ != 0) {
    heard_s = std::min(heard_s, static_cast<double>(now - started_ns_) * 1e-9 * 1.001);
  }
  clock_.set(now, heard_s, moving);
}

void AudioPlayback::run() {
  std::vector<float> in;
  std::vector<std::int16_t> out;
  std::string error;
  std::uint64_t underruns = 0;
  while (!stop_.load(std::memory_order_relaxed) && error.empty()) {
    const auto n = static_cast<snd_pcm_sframes_t>(reader_.read(in, kChunk));
    if (n == 0) break;
    out.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      out[i] = static_cast<std::int16_t>(std::lround(in[i] * 32767.0));
    }
    snd_pcm_sframes_t done = 0;
    while (done < n && !stop_.load(std::memory_order_relaxed)) {
      const snd_pcm_sframes_t w =
          snd_pcm_writei(pcm_, out.data() + done, static_cast<snd_pcm_uframes_t>(n - done));
      if (w == -EPIPE || w == -ESTRPIPE) {
        ++underruns;
        if (snd_pcm_recover(pcm_, static_cast<int>(w), 1) < 0)
          error = alsa_error(static_cast<int>(w));
      } else if (w < 0 && w != -EAGAIN && w != -EINTR) {
        error = alsa_error(static_cast<int>(w));
      } else if (w > 0) {
        done += w;
        written_ += w;
      }
      if (!error.empty()) break;
      publish(true);
    }
    std::lock_guard lock(mutex_);
    stats_.played_s = static_cast<double>(written_) / rate_;
    stats_.underruns = underruns;
  }
  // Play out what the device holds, keeping the clock, unless stopped.
  if (error.empty() && !stop_.load(std::memory_order_relaxed)) {
    if (snd_pcm_state(pcm_) == SND_PCM_STATE_PREPARED)
      snd_pcm_start(pcm_);  // shorter than a buffer
    for (;;) {
      publish(true);
      snd_pcm_sframes_t delay = 0;
      if (stop_.load(std::memory_order_relaxed) || snd_pcm_delay(pcm_, &delay) < 0 || delay <= 0 ||
          snd_pcm_state(pcm_) != SND_PCM_STATE_RUNNING) {
        break;
      }
      timespec ts{0, 5'000'000};
      nanosleep(&ts, nullptr);
    }
  }
  // From here the clock runs on from where the sound ended or stopped, so the
  // poses still finish on time.
  const std::int64_t now = monotonic_ns();
  clock_.set(now, clock_.at(now), true);
  snd_pcm_drop(pcm_);
  std::lock_guard lock(mutex_);
  stats_.finished = true;
  if (!error.empty()) stats_.last_error = "audio.device '" + device_ + "': " + error;
}

}  // namespace facectl
