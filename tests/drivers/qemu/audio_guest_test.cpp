// Runs inside the QEMU guest, whose kernel has ALSA's loopback card
// (snd-aloop): facectl's AudioPlayback plays into hw:Loopback,0,0, a real
// kernel PCM device that consumes the sound at its sample rate on the
// kernel's timer, so the AudioClock (which times the face) is read against
// a device clock. Capturing at the cable's other end was tried and left out:
// every capture read in this guest returned EIO (docs/INPUTS.md, "Audio").
#include <gtest/gtest.h>
#include <sndfile.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
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
  for (std::size_t i = 0; i < s.size(); ++i) {
    s[i] = static_cast<float>(0.5 * std::sin(2 * M_PI * 440.0 * static_cast<double>(i) / kRate));
  }
  sf_writef_float(f, s.data(), static_cast<sf_count_t>(s.size()));
  sf_close(f);
}

TEST(AudioInGuest, TheClockFollowsTheDeviceInRealTime) {
  if (access("/dev/snd/pcmC0D0p", F_OK) != 0) GTEST_SKIP() << "no loopback card (snd-aloop)";
  write_tone("/tmp/tone.wav");
  AudioConfig cfg;
  cfg.device = "hw:Loopback,0,0";
  cfg.buffer_s = 0.05;
  AudioPlayback playback("/tmp/tone.wav", cfg);
  const std::int64_t t0 = monotonic_ns();
  playback.start();
  // (seconds since start, second of the sound heard) while the device runs.
  std::vector<std::pair<double, double>> samples;
  while (!playback.stats().finished && monotonic_ns() - t0 < 5'000'000'000) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::int64_t now = monotonic_ns();
    const double media = playback.clock().at(now);
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
  EXPECT_GT(began, 0.0);
  EXPECT_LT(began, 0.15);
  EXPECT_GT(took, 1.3) << "a device with a clock does not take the sound at once";
  EXPECT_LT(took, 1.6);
}

}  // namespace
}  // namespace facectl
