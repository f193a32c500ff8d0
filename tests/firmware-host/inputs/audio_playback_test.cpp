// `facectl run --audio`: the audio: block, the clock the player follows, and
// the run with ALSA's null device (no sound card here; the kernel's loopback
// card is tested in the QEMU guest, tests/drivers/qemu/audio_guest_test.cpp).
#include <gtest/gtest.h>
#include <sndfile.h>

#include <atomic>
#include <cmath>
#include <fstream>
#include <regex>
#include <thread>
#include <vector>

#include "../simulate/simulate_process.hpp"
#include "control/clock.hpp"
#include "firmware-host/config/audio_config.hpp"
#include "firmware-host/inputs/audio_clock.hpp"
#include "firmware-host/inputs/show_player.hpp"
#include "tests/support/config_block.hpp"

namespace facectl {
namespace {

using testing::config_error_of;
using testing::run_facectl;
using testing::TempDir;

AudioConfig parse(const std::string& body) {
  return testing::parse_block("audio", body, parse_audio_config);
}

TEST(AudioConfig, DefaultsAndMistakesAtTheirLine) {
  const AudioConfig d = parse("  device: default\n");
  EXPECT_EQ(d.device, "default");
  EXPECT_DOUBLE_EQ(d.lead_s, 0.07);
  EXPECT_DOUBLE_EQ(d.buffer_s, 0.1);
  const AudioConfig c = parse("  device: plughw:1,0\n  lead_ms: 120\n  buffer_ms: 40\n");
  EXPECT_EQ(c.device, "plughw:1,0");
  EXPECT_DOUBLE_EQ(c.lead_s, 0.12);
  EXPECT_DOUBLE_EQ(c.buffer_s, 0.04);
  EXPECT_NE(config_error_of([] { parse("  lead_ms: 1500\n"); }).find(":2:"), std::string::npos);
  EXPECT_NE(config_error_of([] { parse("  lead_ms: -5\n"); }).find("lead_ms"), std::string::npos);
  EXPECT_NE(config_error_of([] { parse("  buffer_ms: 5\n"); }).find("buffer_ms"),
            std::string::npos);
  EXPECT_NE(config_error_of([] { parse("  device: \"\"\n"); }).find("ALSA device name"),
            std::string::npos);
  EXPECT_NE(config_error_of([] { parse("  delay_ms: 5\n"); }).find("delay_ms"), std::string::npos);
}

TEST(AudioClock, RunsOnWithTimeOnlyWhileTheSoundRunsAndNotPastWhatWasWritten) {
  AudioClock clock;
  EXPECT_EQ(clock.at(123), 0.0);
  clock.set(1'000'000'000, 0.25, false, 0.3);  // not started: the sound stands still
  EXPECT_DOUBLE_EQ(clock.at(1'500'000'000), 0.25);
  clock.set(2'000'000'000, 0.5, true, 0.8);
  EXPECT_DOUBLE_EQ(clock.at(2'100'000'000), 0.6);
  EXPECT_DOUBLE_EQ(clock.at(3'000'000'000), 0.8) << "a stalled device: no further than written";
}

// The player shows second t of its track when its clock says t, and plays
// once (a clocked player does not loop).
TEST(ShowPlayerClock, EvaluatesAtTheClocksTimeAndDoesNotLoop) {
  LatestValueMailbox<FaceCommand> mailbox;
  std::atomic<double> asked{-1.0};
  ShowPlayer player(
      [&asked](double t, std::array<double, kMaxFaceSignals>& out) {
        asked.store(t);
        out[0] = t;
      },
      1.0, mailbox, 250.0, /*loop=*/true);
  std::atomic<double> media{0.4};
  player.follow([&media](std::int64_t) { return media.load(); });
  player.start();
  FaceCommand cmd;
  for (int i = 0; i < 500 && asked.load() != 0.4; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_EQ(asked.load(), 0.4);
  EXPECT_FALSE(player.finished());
  media.store(2.5);  // past the end of a 1 s track: finished, not wrapped to 0.5
  for (int i = 0; i < 500 && !player.finished(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  EXPECT_TRUE(player.finished());
  player.stop();  // after its last publication, which follows finished()
  ASSERT_TRUE(mailbox.consume(cmd));
  EXPECT_EQ(cmd.values[0], 2.5);
}

// 16 kHz mono: 0.5 s of silence, 0.3 s of a 440 Hz tone, 0.5 s of silence.
void write_tone(const std::string& path) {
  SF_INFO info{};
  info.samplerate = 16000;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  ASSERT_NE(f, nullptr) << sf_strerror(nullptr);
  std::vector<float> s(16000 * 13 / 10, 0.0F);
  for (int i = 8000; i < 12800; ++i)
    s[i] = static_cast<float>(0.5 * std::sin(2 * M_PI * 440.0 * i / 16000.0));
  sf_writef_float(f, s.data(), static_cast<sf_count_t>(s.size()));
  sf_close(f);
}

// The shipped runtime file with paths made absolute and its audio: block
// replaced.
std::string config_with_audio(const TempDir& tmp, const std::string& audio) {
  const std::string dir = std::string(FACECTL_SOURCE_DIR) + "/config/";
  std::ifstream in(dir + "facectl.yaml");
  std::string text;
  const std::regex relative(R"(^(\w+): (\S+\.yaml)$)");
  bool in_audio = false;  // the shipped audio: block, replaced below
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') in_audio = line == "audio:";
    if (!in_audio) text += std::regex_replace(line, relative, "$1: " + dir + "$2") + "\n";
  }
  const std::string path = tmp / ("audio" + std::to_string(audio.size()) + ".yaml");
  testing::write_text(path, text + "audio:\n" + audio);
  return path;
}

// The time (telemetry's time_s) the jaw first opens by 0.2 deg.
double jaw_onset(const std::string& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> header;
  for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
    b = std::min(line.find(',', a), line.size());
    header.push_back(line.substr(a, b - a));
  }
  const auto jaw = std::find(header.begin(), header.end(), "face.jaw_pitch") - header.begin();
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::size_t a = 0, b; a <= line.size() && v.size() <= static_cast<std::size_t>(jaw);
         a = b + 1) {
      b = std::min(line.find(',', a), line.size());
      v.push_back(std::atof(line.substr(a, b - a).c_str()));
    }
    if (v[static_cast<std::size_t>(jaw)] > 0.2 * M_PI / 180.0) return v[1];
  }
  return -1.0;
}

double number_after(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  return at == std::string::npos ? -1.0 : std::atof(text.c_str() + at + label.size());
}

// ALSA's null device takes the sound at once; the face then keeps real
// time from the device's start. The jaw of the speech envelope opens with
// the tone at 0.5 s, earlier by the lead.
TEST(AudioProcess, TheFaceLeadsTheSoundByTheConfiguredLead) {
  TempDir tmp;
  write_tone(tmp / "tone.wav");
  double onset[2] = {};
  const int lead_ms[2] = {0, 150};
  for (int k = 0; k < 2; ++k) {
    const std::string cfg = config_with_audio(
        tmp, "  device: \"null\"\n  lead_ms: " + std::to_string(lead_ms[k]) + "\n");
    const auto r = run_facectl({"run", "--quiet", "--config", cfg, "--input", tmp / "tone.wav",
                                "--audio", tmp / "tone.wav", "--record", tmp / "t.csv"},
                               tmp / "log.txt");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("audio: 1.30 of 1.30 s played on 'null', the face " +
                            std::to_string(lead_ms[k]) + " ms ahead, 0 underruns"),
              std::string::npos)
        << r.output;
    onset[k] = jaw_onset(tmp / "t.csv");
    ASSERT_GT(onset[k], 0.0) << r.output;
    // On CLOCK_MONOTONIC, by the summary's two clock lines: the jaw opens as
    // the tone (0.5 s into the sound) is heard, less the lead and plus the
    // envelope's and the shaping's rise to 0.2 deg.
    const double loop_t0 = number_after(r.output, "telemetry time_s 0 is CLOCK_MONOTONIC ");
    const double sound_t0 =
        number_after(r.output, "second 0 of the sound heard at CLOCK_MONOTONIC ");
    ASSERT_GT(loop_t0, 0.0) << r.output;
    ASSERT_GT(sound_t0, 0.0) << r.output;
    EXPECT_NEAR(loop_t0 + onset[k] - (sound_t0 + 0.5 - lead_ms[k] * 1e-3), 0.0, 0.03);
  }
  std::printf("jaw onset: %.3f s with no lead, %.3f s with 150 ms\n", onset[0], onset[1]);
  EXPECT_NEAR(onset[0] - onset[1], 0.150, 0.025);
}

// The sound starts when the head runs, and the track follows the sound: a head
// that faults while it enables never starts either. The run ends with the
// fault's exit code rather than waiting for them (it hung until a signal).
TEST(AudioProcess, AFaultBeforeTheHeadRunsEndsTheRunWithoutTheSound) {
  TempDir tmp;
  write_tone(tmp / "tone.wav");
  const std::string cfg = config_with_audio(tmp, "  device: \"null\"\n");
  const auto r = run_facectl({"run", "--quiet", "--config", cfg, "--input", tmp / "tone.wav",
                              "--audio", tmp / "tone.wav", "--inject", "bus_fault:modbus0@0.2"},
                             tmp / "log.txt", 60);
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("ENABLING -> FAULT: bus fault"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("audio: 0.00 of 1.30 s played on 'null'"), std::string::npos) << r.output;
}

TEST(AudioProcess, NoDeviceOrNothingToTimeIsRefusedBeforeAnythingMoves) {
  TempDir tmp;
  write_tone(tmp / "tone.wav");
  const std::string cfg = config_with_audio(tmp, "  device: hw:99,0\n");
  auto r = run_facectl(
      {"run", "--quiet", "--config", cfg, "--input", tmp / "tone.wav", "--audio", tmp / "tone.wav"},
      tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("audio.device 'hw:99,0': cannot open it for playback"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("ALSA lib"), std::string::npos) << "alsa-lib's own stderr is quiet";
  EXPECT_EQ(r.output.find("ENABLING"), std::string::npos) << r.output;
  r = run_facectl({"run", "--quiet", "--config", cfg, "--input", tmp / "tone.wav", "--audio",
                   tmp / "missing.wav"},
                  tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("missing.wav: expected a regular audio file, found nothing"),
            std::string::npos)
      << r.output;
  // A live stream alone has no timeline to play by the sound.
  r = run_facectl(
      {"run", "--quiet", "--config", cfg, "--live-link-face", "--audio", tmp / "tone.wav"},
      tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--audio: expected --input or --show to time by the sound"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace facectl
