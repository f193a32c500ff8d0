// Runs inside the QEMU guest, whose kernel has ALSA's loopback card
// (snd-aloop): facectl's AudioPlayback plays a tone into hw:Loopback,0,0, a
// real kernel PCM device that takes the sound at its sample rate on the
// kernel's timer, and the test captures it at the cable's other end,
// timestamped on CLOCK_MONOTONIC. The AudioClock (which times the face)
// must run at one second a second and say when the tone is heard.
#include <alsa/asoundlib.h>
#include <gtest/gtest.h>
#include <sndfile.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "control/clock.hpp"
#include "firmware-host/inputs/audio_playback.hpp"

namespace facectl {
namespace {

constexpr int kRate = 16000;

void write_tone(const char* path) {
  SF_INFO info{};
  info.samplerate = kRate;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path, SFM_WRITE, &info);
  ASSERT_NE(f, nullptr);
  std::vector<float> s(kRate * 13 / 10, 0.0F);
  for (std::size_t i = kRate / 2; i < s.size(); ++i) {  // silence, then the tone at 0.5 s
    s[i] = static_cast<float>(0.5 * std::sin(2 * M_PI * 440.0 * static_cast<double>(i) / kRate));
  }
  sf_writef_float(f, s.data(), static_cast<sf_count_t>(s.size()));
  sf_close(f);
}

std::int64_t to_ns(const snd_htimestamp_t& t) {
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000LL + t.tv_nsec;
}

// The cable's other end (hw:Loopback,1,0), read on its own thread from
// before the sound starts. The card takes frames at its rate from the
// capture's start, so frame k was captured at start + k / rate: that times
// the tone's onset to the card's clock, not to when the thread woke to read
// it (a period and a read later, more under emulation). Its buffer is long
// (1 s) so a stalled reader loses no frames, which would shift the count.
class LoopbackCapture {
 public:
  LoopbackCapture() {
    if (snd_pcm_open(&pcm_, "hw:Loopback,1,0", SND_PCM_STREAM_CAPTURE, 0) < 0) return;
    if (snd_pcm_set_params(pcm_, SND_PCM_FORMAT_S16, SND_PCM_ACCESS_RW_INTERLEAVED, 1, kRate, 1,
                           1'000'000) < 0 ||
        !monotonic_timestamps() || snd_pcm_start(pcm_) < 0) {
      return;
    }
    snd_pcm_status_t* status = nullptr;
    snd_pcm_status_alloca(&status);
    if (snd_pcm_status(pcm_, status) < 0) return;
    snd_htimestamp_t trigger{};
    snd_pcm_status_get_trigger_htstamp(status, &trigger);
    start_ns_ = to_ns(trigger);
    thread_ = std::thread([this] { run(); });
    while (frames_.load() < kRate / 10 && error_.load() == 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  ~LoopbackCapture() {
    done_.store(true);
    if (thread_.joinable()) thread_.join();
    if (pcm_ != nullptr) snd_pcm_close(pcm_);
  }
  bool running() const { return thread_.joinable() && error_.load() == 0; }
  std::int64_t onset_ns() const { return onset_ns_.load(); }
  std::int64_t onset_read_ns() const { return onset_read_ns_.load(); }
  std::string report() const {
    return std::to_string(frames_.load()) + " frames read, the loudest " +
           std::to_string(loudest_.load()) + ", first error '" +
           (error_.load() != 0 ? snd_strerror(error_.load()) : "none") + "'";
  }

 private:
  void run() {
    std::vector<std::int16_t> buf(80);  // 5 ms
    while (!done_.load() && onset_ns_.load() == 0) {
      const snd_pcm_sframes_t n = snd_pcm_readi(pcm_, buf.data(), buf.size());
      const std::int64_t now = monotonic_ns();
      if (n < 0) {
        if (error_.load() == 0) error_.store(static_cast<int>(n));
        if (snd_pcm_recover(pcm_, static_cast<int>(n), 1) < 0) return;
        continue;
      }
      for (snd_pcm_sframes_t i = 0; i < n; ++i) {
        const int v = std::abs(static_cast<int>(buf[static_cast<std::size_t>(i)]));
        loudest_.store(std::max(loudest_.load(), v));
        if (v > 2000) {
          onset_read_ns_.store(now);  // first: onset_ns_ != 0 says both are set
          onset_ns_.store(start_ns_ + (frames_.load() + i) * 1'000'000'000LL / kRate);
          break;
        }
      }
      frames_.fetch_add(n);
    }
  }

  bool monotonic_timestamps() {
    snd_pcm_sw_params_t* sw = nullptr;
    snd_pcm_sw_params_alloca(&sw);
    return snd_pcm_sw_params_current(pcm_, sw) == 0 &&
           snd_pcm_sw_params_set_tstamp_mode(pcm_, sw, SND_PCM_TSTAMP_ENABLE) == 0 &&
           snd_pcm_sw_params_set_tstamp_type(pcm_, sw, SND_PCM_TSTAMP_TYPE_MONOTONIC) == 0 &&
           snd_pcm_sw_params(pcm_, sw) == 0;
  }

  snd_pcm_t* pcm_ = nullptr;
  std::thread thread_;
  std::atomic<bool> done_{false};
  std::atomic<std::int64_t> frames_{0};
  std::atomic<int> loudest_{0};
  std::atomic<int> error_{0};
  std::int64_t start_ns_ = 0;  // the card's first capture frame, CLOCK_MONOTONIC
  std::atomic<std::int64_t> onset_ns_{0};
  std::atomic<std::int64_t> onset_read_ns_{0};
};

TEST(AudioInGuest, TheClockFollowsTheDeviceInRealTime) {
  if (access("/dev/snd/pcmC0D0p", F_OK) != 0) GTEST_SKIP() << "no loopback card (snd-aloop)";
  write_tone("/tmp/tone.wav");
  AudioConfig cfg;
  cfg.device = "hw:Loopback,0,0";
  cfg.buffer_s = 0.05;
  AudioPlayback playback("/tmp/tone.wav", cfg);
  const LoopbackCapture capture;
  const std::int64_t t0 = monotonic_ns();
  playback.start();
  // (seconds since start, second of the sound heard) while the device runs.
  std::vector<std::pair<double, double>> samples;
  double last = 0.0;
  double most_back = 0.0;  // the largest step back of the clock between readings
  while (!playback.stats().finished && monotonic_ns() - t0 < 5'000'000'000) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    const std::int64_t now = monotonic_ns();
    const double media = playback.clock().at(now);
    most_back = std::max(most_back, last - media);
    last = media;
    if (media > 0.1 && media < 1.2)
      samples.emplace_back(static_cast<double>(now - t0) * 1e-9, media);
  }
  const double took = static_cast<double>(monotonic_ns() - t0) * 1e-9;
  playback.stop();
  const AudioStats st = playback.stats();
  EXPECT_TRUE(st.finished);
  EXPECT_EQ(st.last_error, "");
  EXPECT_EQ(st.underruns, 0U);
  EXPECT_DOUBLE_EQ(st.played_s, 1.3);
  ASSERT_GT(samples.size(), 20U);
  // Least squares: the sound moves at one second a second, and started
  // within the buffer (plus the thread's start) of start().
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& [x, y] : samples) sx += x, sy += y, sxx += x * x, sxy += x * y;
  const double n = static_cast<double>(samples.size());
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double began = -(sy - slope * sx) / n / slope;  // where media time 0 was
  std::printf(
      "clock: %.4f s of sound a second, sound began %.1f ms after start(), done in %.3f s\n", slope,
      began * 1e3, took);
  EXPECT_NEAR(slope, 1.0, 0.02);
  EXPECT_GT(began, -0.005);  // a fitted intercept: a few ms of noise (seen: -2.4 ms, loaded)
  EXPECT_LT(began, 0.15);
  EXPECT_GT(took, 1.3) << "a device with a clock does not take the sound at once";
  EXPECT_LT(took, 1.6);
  // The other end of the cable hears the tone when the clock said it would.
  ASSERT_TRUE(capture.running()) << capture.report();
  ASSERT_NE(capture.onset_ns(), 0) << capture.report();
  const double heard = static_cast<double>(capture.onset_ns() - t0) * 1e-9;
  const double read = static_cast<double>(capture.onset_read_ns() - t0) * 1e-9;
  const double predicted = began + 0.5 / slope;
  std::printf(
      "the tone heard at %.1f ms (read at %.1f ms), the clock said %.1f ms; it stepped back at "
      "most %.2f ms\n",
      heard * 1e3, read * 1e3, predicted * 1e3, most_back * 1e3);
  EXPECT_LE(heard, read) << "the card's frame count puts the tone after it was read";
  // Between statuses the clock runs on by the system's time; the next status
  // may put it up to a millisecond or two back (seen: 1.85 ms in the guest).
  EXPECT_LT(most_back, 0.003) << "the face must not jump back";
  // Seen here, by the card's frame count: heard 0.8 to 10.6 ms after the
  // clock said (sixteen runs here and in CI, six beside busy loops). The
  // loopback card moves both ends a timer tick (4 ms at HZ=250) at a time and
  // the fitted start has a few ms of noise either way. Heard late means the face leads the sound:
  // on top of the configured lead (audio.lead_ms, 70 ms by default), 20 ms
  // keeps the face inside the 125 ms of lead at which viewers notice
  // (ITU-R BT.1359); heard early, the sound leads, which they notice at 45.
  EXPECT_GT(heard - predicted, -0.005);
  EXPECT_LT(heard - predicted, 0.020);
}

}  // namespace
}  // namespace facectl
