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

constexpr std::int64_t kStallNs = 2'000'000'000;  // no progress this long: the device has failed

std::string alsa_error(snd_pcm_sframes_t err) {
  return snd_strerror(static_cast<int>(err));
}

}  // namespace

AudioPlayback::AudioPlayback(const std::string& path, const AudioConfig& config)
    : device_(config.device), reader_(path, kMaxAudioSeconds) {
  rate_ = reader_.sample_rate();
  stats_.file_s = reader_.seconds();
  quiet_alsa_lib();
  // Non-blocking, so a device that stalls cannot hold the thread, nor a
  // busy one the start.
  int err = snd_pcm_open(&pcm_, device_.c_str(), SND_PCM_STREAM_PLAYBACK, SND_PCM_NONBLOCK);
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
  if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
}

void AudioPlayback::stop() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

AudioStats AudioPlayback::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::int64_t AudioPlayback::status_time(const snd_pcm_status_t* status, bool trigger) {
  snd_htimestamp_t ts{};
  if (trigger) {
    snd_pcm_status_get_trigger_htstamp(status, &ts);
  } else {
    snd_pcm_status_get_htstamp(status, &ts);
  }
  const std::int64_t at = static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
  const std::int64_t now = monotonic_ns();
  // CLOCK_MONOTONIC (the sw params ask for it) and recent, else unusable.
  return at > 0 && at <= now && now - at < 3'600'000'000'000 ? at : 0;
}

// The frame heard is the last one written less what the device still holds
// (the delay: buffered plus the hardware's own), at the status's timestamp.
// Only a running or draining device reports its delay; otherwise the sound
// stands where it was.
void AudioPlayback::publish() {
  snd_pcm_status_t* status = nullptr;
  snd_pcm_status_alloca(&status);
  if (snd_pcm_status(pcm_, status) < 0) return;
  const snd_pcm_state_t state = snd_pcm_status_get_state(status);
  if (state != SND_PCM_STATE_RUNNING && state != SND_PCM_STATE_DRAINING) {
    // Stand where the clock had got to (never behind it: the face must not
    // jump back when a drain ends or an underrun is noticed a period late),
    // but not past what was written.
    const std::int64_t now = monotonic_ns();
    heard_s_ = std::min(std::max(heard_s_, clock_.at(now)), static_cast<double>(written_) / rate_);
    clock_.set(now, heard_s_, false, heard_s_);
    return;
  }
  const std::int64_t stamped = status_time(status, false);
  const std::int64_t now = stamped != 0 ? stamped : monotonic_ns();
  // When the device started: second 0 of the sound was heard then.
  if (started_ns_ == 0) {
    const std::int64_t trigger = status_time(status, true);
    started_ns_ = trigger != 0 ? trigger : now;
    std::lock_guard lock(mutex_);
    stats_.started_ns = started_ns_;
  }
  const snd_pcm_sframes_t delay = std::clamp<snd_pcm_sframes_t>(
      snd_pcm_status_get_delay(status), 0, static_cast<snd_pcm_sframes_t>(written_));
  double heard = static_cast<double>(written_ - delay) / rate_;
  if (delay == 0) heard = std::min(heard, real_time_cap(now));  // none buffered: no clock?
  heard_s_ = std::max(heard_s_, heard);
  clock_.set(now, heard_s_, true, static_cast<double>(written_) / rate_);
}

// A device without a clock (ALSA's null, a file plugin) reports no delay
// and takes the sound at once; the face then keeps real time from the
// device's start (or the first write, for one that never says it ran).
// 0.1% over real time allows any sound card's crystal.
double AudioPlayback::real_time_cap(std::int64_t now) const {
  const std::int64_t from = started_ns_ != 0 ? started_ns_ : first_write_ns_;
  if (from == 0) return 0.0;
  return static_cast<double>(now - from) * 1e-9 * 1.001;
}

// Waits up to 100 ms for the device to take more (or to finish draining);
// false, with `error` set, once it has made no progress for kStallNs.
bool AudioPlayback::wait_for_device(std::int64_t& progress_ns, double& progress_s,
                                    std::string& error) {
  snd_pcm_wait(pcm_, 100);
  publish();
  const std::int64_t now = monotonic_ns();
  if (heard_s_ > progress_s) {
    progress_s = heard_s_;
    progress_ns = now;
  } else if (now - progress_ns > kStallNs) {
    error = "the device took no sound for " + std::to_string(kStallNs / 1'000'000'000) + " s";
    return false;
  }
  return true;
}

void AudioPlayback::run() {
  std::vector<float> in;
  std::vector<std::int16_t> out;
  std::string error;
  std::uint64_t underruns = 0;
  std::int64_t progress_ns = monotonic_ns();
  double progress_s = 0.0;
  bool more = true;
  while (more && !stop_.load(std::memory_order_relaxed) && error.empty()) {
    const auto n = static_cast<snd_pcm_sframes_t>(reader_.read(in, kChunk));
    more = n > 0;
    out.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
      out[i] = static_cast<std::int16_t>(std::lround(in[i] * 32767.0));
    }
    snd_pcm_sframes_t done = 0;
    while (done < n && !stop_.load(std::memory_order_relaxed) && error.empty()) {
      const snd_pcm_sframes_t w =
          snd_pcm_writei(pcm_, out.data() + done, static_cast<snd_pcm_uframes_t>(n - done));
      if (w == -EPIPE || w == -ESTRPIPE) {
        ++underruns;  // the sound (and the face with it) waits for the next write
        if (snd_pcm_recover(pcm_, static_cast<int>(w), 1) < 0) error = alsa_error(w);
        publish();
      } else if (w == -EAGAIN) {
        wait_for_device(progress_ns, progress_s, error);
      } else if (w < 0 && w != -EINTR) {
        error = alsa_error(w);
      } else if (w > 0) {
        if (written_ == 0) first_write_ns_ = monotonic_ns();
        done += w;
        written_ += w;
        publish();
      }
    }
    std::lock_guard lock(mutex_);
    stats_.played_s = static_cast<double>(written_) / rate_;
    stats_.underruns = underruns;
  }
  // Play out what the device holds (a sound shorter than the buffer starts
  // here), keeping the clock, unless stopped.
  if (error.empty() && !stop_.load(std::memory_order_relaxed)) {
    const int err = snd_pcm_drain(pcm_);  // non-blocking: -EAGAIN while it drains
    if (err < 0 && err != -EAGAIN) error = alsa_error(err);
    while (error.empty() && !stop_.load(std::memory_order_relaxed)) {
      const snd_pcm_state_t state = snd_pcm_state(pcm_);
      if (state != SND_PCM_STATE_DRAINING && state != SND_PCM_STATE_RUNNING) break;
      if (!wait_for_device(progress_ns, progress_s, error)) break;
    }
    if (error
            .empty()) {  // all of it played, or for a device without a clock, what real time allows
      heard_s_ = std::max(
          heard_s_, std::min(static_cast<double>(written_) / rate_, real_time_cap(monotonic_ns())));
    }
  }
  // From here the clock runs on from where the sound ended or stopped, so the
  // poses still finish on time.
  const std::int64_t now = monotonic_ns();
  clock_.set(now, std::max(heard_s_, clock_.at(now)), true, 1e300);
  snd_pcm_drop(pcm_);
  std::lock_guard lock(mutex_);
  stats_.finished = true;
  if (stats_.started_ns == 0) stats_.started_ns = first_write_ns_;  // a device that never ran
  if (!error.empty()) stats_.last_error = "audio.device '" + device_ + "': " + error;
}

}  // namespace facectl
