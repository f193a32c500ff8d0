#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "firmware-host/config/audio_config.hpp"
#include "firmware-host/inputs/audio_clock.hpp"
#include "firmware-host/inputs/mono_audio_reader.hpp"

typedef struct _snd_pcm snd_pcm_t;                // NOLINT: alsa/asoundlib.h's own declaration
typedef struct _snd_pcm_status snd_pcm_status_t;  // NOLINT: likewise

namespace facectl {

struct AudioStats {
  double played_s = 0.0;        // seconds of the file handed to the device
  double file_s = 0.0;          // its length
  std::uint64_t underruns = 0;  // the device ran dry (recovered; the sound paused)
  bool finished = false;        // played to the end, or stopped by an error
  std::int64_t started_ns = 0;  // CLOCK_MONOTONIC when second 0 was heard; 0 before
  std::string last_error;       // the device failing mid-run (the poses go on, timed by the clock)
};

// `facectl run --audio FILE` (docs/INPUTS.md, "Playing the sound"): plays a sound file
// (anything libsndfile reads, mixed to mono) through an ALSA PCM on its own
// thread, and keeps an AudioClock of which second of it is heard, from the
// device's delay after each write. The player of the input or show reads
// that clock, so the face follows the sound, not the other way round.
class AudioPlayback {
 public:
  // Opens the file and the device; ConfigError naming the file, or the
  // device and what ALSA said, so a run fails before anything moves.
  AudioPlayback(const std::string& path, const AudioConfig& config);
  ~AudioPlayback();
  AudioPlayback(const AudioPlayback&) = delete;
  AudioPlayback& operator=(const AudioPlayback&) = delete;

  void start();  // once; later calls do nothing
  void stop();   // stops the sound at once (snd_pcm_drop)

  const AudioClock& clock() const { return clock_; }
  AudioStats stats() const;
  int sample_rate() const { return rate_; }

 private:
  void run();
  void publish();
  bool wait_for_device(std::int64_t& progress_ns, double& progress_s, std::string& error);
  static std::int64_t status_time(const snd_pcm_status_t* status, bool trigger);
  double real_time_cap(std::int64_t now) const;

  std::string device_;
  MonoAudioReader reader_;  // read on the audio thread, a chunk at a time
  snd_pcm_t* pcm_ = nullptr;
  int rate_ = 0;
  std::int64_t written_ = 0;     // frames handed to ALSA
  std::int64_t started_ns_ = 0;  // when the device started: second 0 heard
  std::int64_t first_write_ns_ = 0;
  double heard_s_ = 0.0;  // the sound's second at the last status
  AudioClock clock_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;  // stats_, between the audio thread and the summary
  AudioStats stats_;
};

}  // namespace facectl
