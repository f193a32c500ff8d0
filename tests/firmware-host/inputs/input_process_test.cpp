// `--input` as a user runs it: facectl simulate and facectl run on files other
// tools wrote, a broken one refused with its line and nothing written, and a
// performance recorded as a show that --show plays back.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <regex>
#include <thread>

#include "../simulate/simulate_process.hpp"
#include "tests/support/facectl_child.hpp"
#include "tests/support/loopback_udp.hpp"

namespace facectl {
namespace {

using testing::run_facectl;
using testing::TempDir;

const std::string kReal = std::string(INPUT_REAL_FILES);
const std::string kRig = std::string(FACECTL_SOURCE_DIR) + "/config/rigs/default.yaml";
// These tests check what the inputs do, not the loop's timing (RunFaults' overrun_storm
// does). A config without a runtime block faults after the built-in 10 missed deadlines,
// and under ctest -j2 and a busy loop one stall of 27.7 ms faulted the speech mix's run
// about one time in ten.
const std::string kRuntime = "runtime: { rate_hz: 1000, overrun_fault_count: 100 }\n";

TEST(InputProcess, SimulateDetectsAndPlaysEachCaptureFormat) {
  const std::pair<std::string, const char*> files[] = {
      {kReal + "/live_link_face/S07-001.first9lines.csv", "live_link_face"},
      {kReal + "/openface/OpenFace_Test.first3lines.csv", "openface"},
      {kReal + "/mediapipe/mediapipe-labeler_blendshapes.json", "mediapipe"},
  };
  for (const auto& [file, kind] : files) {
    TempDir tmp;
    const auto r = run_facectl({"simulate", "--rig", kRig, "--input", file, "--duration", "0.5",
                                "--out", tmp / "out", "--quiet"},
                               tmp / "log.txt");
    EXPECT_EQ(r.exit_code, 0) << file << "\n" << r.output;
    const std::string summary = testing::read_text(tmp / "out/summary.json");
    EXPECT_NE(summary.find(std::string("\"kind\": \"") + kind + "\""), std::string::npos)
        << file << "\n"
        << summary.substr(0, 400);
  }
}

TEST(InputProcess, ABrokenInputIsRefusedAtItsLineAndNothingIsWritten) {
  TempDir tmp;
  std::string text = testing::read_text(kReal + "/live_link_face/S07-001.first9lines.csv");
  text.replace(text.find("12:27:47:51.168"), 15, "12:27:47:51.1x8");
  testing::write_text(tmp / "broken.csv", text);
  const auto r = run_facectl(
      {"simulate", "--rig", kRig, "--input", tmp / "broken.csv", "--out", tmp / "out", "--quiet"},
      tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(tmp / "broken.csv" + ":4: expected a timecode"), std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(tmp / "out"));
}

TEST(InputProcess, LipSyncLongerThanTwoHoursIsRefusedBeforeItCostsMemory) {
  // 14 bytes that would be 8.6 million poses.
  TempDir tmp;
  testing::write_text(tmp / "long.tsv", "0.00\tA\n86400\tX\n");
  const auto r = run_facectl(
      {"simulate", "--rig", kRig, "--input", tmp / "long.tsv", "--out", tmp / "out", "--quiet"},
      tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(tmp / "long.tsv" + ": expected lip sync of at most 7200 s"),
            std::string::npos)
      << r.output;
}

TEST(InputProcess, SimulateLipSyncsAWavFromItsPhonesWhenAskedAndItsJawByDefault) {
  const std::string wav = kReal + "/audio/espeak_bilabials.wav";
  for (const char* format : {"audio_phonemes", ""}) {
    TempDir tmp;
    std::vector<std::string> args = {"simulate", "--rig", kRig,        "--input",
                                     wav,        "--out", tmp / "out", "--quiet"};
    if (*format != 0) args.insert(args.end(), {"--format", format});
    const auto r = run_facectl(args, tmp / "log.txt");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string summary = testing::read_text(tmp / "out/summary.json");
    const std::string kind = *format != 0 ? format : "audio";
    EXPECT_NE(summary.find("\"kind\": \"" + kind + "\""), std::string::npos)
        << summary.substr(0, 400);
    // Phoneme recognition says what it heard; the envelope jaw does not.
    EXPECT_EQ(summary.find("phones recognised") != std::string::npos, *format != 0)
        << summary.substr(0, 2000);
  }
}

TEST(InputProcess, AnUnknownFormatOrFormatNameIsRefused) {
  TempDir tmp;
  testing::write_text(tmp / "x.txt", "hello\n");
  auto r = run_facectl({"simulate", "--rig", kRig, "--input", tmp / "x.txt", "--out", tmp / "out"},
                       tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("name it with --format"), std::string::npos) << r.output;
  r = run_facectl({"simulate", "--rig", kRig, "--input", tmp / "x.txt", "--format", "csv", "--out",
                   tmp / "out"},
                  tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--format: expected one of show, fap, live_link_face"), std::string::npos)
      << r.output;
}

TEST(InputProcess, RunRecordsAPerformanceAsAShowThatPlaysBack) {
  TempDir tmp;
  const std::string take = tmp / "take.yaml";
  auto r = run_facectl({"run", "--quiet", "--duration", "1.5", "--input",
                        kReal + "/live_link_face/S07-001.first9lines.csv", "--record-show", take},
                       tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("recorded"), std::string::npos) << r.output;
  ASSERT_TRUE(std::filesystem::exists(take)) << r.output;
  // The take's gaze: EyeLookUpLeft 0.47 is 9.4 deg of eye pitch through the table.
  const std::string yaml = testing::read_text(take);
  EXPECT_NE(yaml.find("eye_pitch_l_deg: 9."), std::string::npos) << yaml.substr(0, 600);
  r = run_facectl({"run", "--quiet", "--show", take}, tmp / "log2.txt");
  EXPECT_EQ(r.exit_code, 0) << r.output;
}

// The largest value a recorded take gives `key` (0 when it never names it).
double max_in_take(const std::string& yaml, const std::string& key) {
  double most = 0.0;
  for (auto at = yaml.find(key + ": "); at != std::string::npos;
       at = yaml.find(key + ": ", at + 1)) {
    most = std::max(most, std::strtod(yaml.c_str() + at + key.size() + 2, nullptr));
  }
  return most;
}

TEST(InputProcess, RunMixesSpeechForTheMouthWithTheShowForTheRest) {
  TempDir tmp;
  const std::string config = std::string(FACECTL_SOURCE_DIR) + "/config/";
  const std::string head = kRuntime + "head: " + config +
                           "heads/default/head.yaml\nrig: " + config +
                           "rigs/default.yaml\nexpressions: " + config +
                           "expressions/library.yaml\nvisemes: " + config + "fap/visemes.yaml\n";
  const std::string speech = kReal + "/rhubarb/en_male_electricity-expected.json";
  const std::string show = config + "shows/demo.yaml";
  testing::write_text(tmp / "alone.yaml", head);
  auto r = run_facectl(
      {"run", "--quiet", "--config", tmp / "alone.yaml", "--show", show, "--input", speech},
      tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("or a mix: block in " + tmp / "alone.yaml"), std::string::npos)
      << r.output;

  testing::write_text(tmp / "mix.yaml",
                      head +
                          "mix:\n  groups:\n    mouth: { signals: [jaw_*], sources: [input] }\n"
                          "  others: [show]\n");
  const std::string take = tmp / "take.yaml";
  r = run_facectl({"run", "--quiet", "--config", tmp / "mix.yaml", "--show", show, "--input",
                   speech, "--duration", "2.4", "--record-show", take},
                  tmp / "log.txt");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The speech (1.1 s) played once and gave way; nothing else plays the mouth.
  EXPECT_NE(r.output.find("  mix: mouth: neutral (changed source 1 time), others: show"),
            std::string::npos)
      << r.output;
  const std::string yaml = testing::read_text(take);
  // The show's joy (1.5 s on) and its 5 deg of neck tilt are in the take; its
  // mandible (3 deg at most before 2.5 s) is not: the speech opens the jaw wider.
  EXPECT_GT(max_in_take(yaml, "zygomaticus_major_l"), 0.5) << yaml.substr(0, 800);
  EXPECT_NEAR(max_in_take(yaml, "neck_tilt_deg"), 5.0, 0.1);
  EXPECT_GT(max_in_take(yaml, "pitch_deg"), 5.0);

  // Losing the input rehearsed on a mix silences the mix: the tick's watchdog
  // sees it; a stream alone has nothing the rehearsal could silence.
  r = run_facectl({"run", "--quiet", "--config", tmp / "mix.yaml", "--show", show, "--input",
                   speech, "--duration", "2.5", "--inject", "input_loss@1.2"},
                  tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const std::regex stale(R"(stale-input ticks (\d+))");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, stale)) << r.output;
  EXPECT_GT(std::stoi(m[1]), 500) << r.output;
  r = run_facectl({"run", "--quiet", "--live-link-face", "--inject", "input_loss@1"},
                  tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--inject input_loss: expected a show or --input to silence"),
            std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace facectl

// ---- the live FAP stream, wired into facectl run

namespace facectl {
namespace {

using testing::free_udp_port;
using testing::send_udp;

// A FAP frame moving FAP 3 (open_jaw) only.
std::string jaw_frame(int number, int value) {
  std::string mask;
  for (int f = 1; f <= 68; ++f) mask += (f == 3 ? "1 " : "0 ");
  return mask + "\n" + std::to_string(number) + " " + std::to_string(value) + "\n";
}

// Spawns `facectl run` with `args` and waits (up to 60 s: a sanitizer build
// on a busy machine loads the head slowly) until it prints `listening`;
// nullopt (a failure recorded, the child reaped) when it does not.
std::optional<testing::Child> spawn_listening(const std::vector<std::string>& args,
                                              const std::string& listening) {
  const testing::Child child = testing::spawn_facectl(args);
  std::string out;
  for (int i = 0; i < 3000 && out.find(listening) == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    out = testing::read_text(child.out_path);
  }
  if (out.find(listening) == std::string::npos) {
    kill(child.pid, SIGKILL);
    testing::wait_exit(child);
    ADD_FAILURE() << "not listening within 60 s:\n" << out;
    return std::nullopt;
  }
  return child;
}

TEST(InputProcess, RunPlaysTheLiveFapStreamAndCountsWhatItRefuses) {
  TempDir tmp;
  const std::uint16_t port = free_udp_port();
  const std::string config = std::string(FACECTL_SOURCE_DIR) + "/config/";
  testing::write_text(tmp / "facectl.yaml",
                      kRuntime + "head: " + config + "heads/default/head.yaml\n" +
                          "rig: " + config + "rigs/default.yaml\n" + "expressions: " + config +
                          "expressions/library.yaml\n" + "visemes: " + config +
                          "fap/visemes.yaml\n" + "fap_stream: { port: " + std::to_string(port) +
                          " }\n");
  const auto listening = spawn_listening(
      {"run", "--quiet", "--config", tmp / "facectl.yaml", "--fap-stream", "--duration", "3"},
      "FAP stream listening on UDP port " + std::to_string(port));
  if (!listening) return;
  const testing::Child& child = *listening;
  send_udp(port, {"2.1 live 25 1000\n" + jaw_frame(0, 200), jaw_frame(1, 300) + jaw_frame(2, 400),
                  "not a FAP line\n"});
  EXPECT_EQ(testing::wait_exit_within(child, 120.0), 0) << testing::read_text(child.out_path);
  const std::string out = testing::read_text(child.out_path);
  EXPECT_NE(out.find("FAP stream: 3 datagrams, 3 frames played, 1 malformed"), std::string::npos)
      << out;
  std::remove(child.out_path.c_str());
}

// PyLiveLinkFace (tests/.../peers, an independent implementation of the
// app's format) sends a second of performance at 60 fps and one malformed
// datagram; the take is recorded as a show.
TEST(InputProcess, RunPlaysTheLiveLinkFaceStreamFromAnIndependentSender) {
  TempDir tmp;
  const std::uint16_t port = free_udp_port();
  const std::string config = std::string(FACECTL_SOURCE_DIR) + "/config/";
  testing::write_text(tmp / "facectl.yaml",
                      kRuntime + "head: " + config + "heads/default/head.yaml\n" +
                          "rig: " + config + "rigs/default.yaml\n" + "expressions: " + config +
                          "expressions/library.yaml\n" +
                          "live_link_face: { port: " + std::to_string(port) + " }\n");
  // Long enough for any start-up of the peer; Ctrl-C ends it once it has sent.
  const auto listening =
      spawn_listening({"run", "--quiet", "--config", tmp / "facectl.yaml", "--live-link-face",
                       "--duration", "120", "--record-show", tmp / "take.yaml"},
                      "Live Link Face stream listening on UDP port " + std::to_string(port));
  if (!listening) return;
  const testing::Child& child = *listening;
  const std::string peer =
      std::string(FACECTL_SOURCE_DIR) + "/tests/firmware-host/inputs/peers/llf_peer.py";
  EXPECT_EQ(std::system(("python3 " + peer + " send " + std::to_string(port) + " 1.0 > " +
                         (tmp / "peer.txt"))
                            .c_str()),
            0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the last datagram's way
  kill(child.pid, SIGINT);
  EXPECT_EQ(testing::wait_exit_within(child, 120.0), 0) << testing::read_text(child.out_path);
  const std::string out = testing::read_text(child.out_path);
  EXPECT_NE(out.find("Live Link Face stream: 61 datagrams, 60 frames played, 0 without a face, 1 "
                     "malformed, 0 held back, 0 from refused senders, 0 dropped by the kernel, "
                     "0 values clamped"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("subject 'facectl-test', device 4B3A1C2D-5E6F-4071-8293-A4B5C6D7E8F9"),
            std::string::npos)
      << out;
  // The take: the jaw open to 0.6 of 18 deg (jawOpen through the retargeting table) and
  // the inner brows raised, played back by --show.
  const std::string take = testing::read_text(tmp / "take.yaml");
  EXPECT_NE(take.find("mandible: { pitch_deg: 10.8"), std::string::npos) << take.substr(0, 600);
  EXPECT_NE(take.find("frontalis_inner"), std::string::npos) << take.substr(0, 600);
  const auto r =
      run_facectl({"run", "--quiet", "--config", tmp / "facectl.yaml", "--show", tmp / "take.yaml"},
                  tmp / "replay.txt");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  std::remove(child.out_path.c_str());
}

TEST(InputProcess, TheFapStreamNeedsItsBlock) {
  TempDir tmp;
  const std::string config = std::string(FACECTL_SOURCE_DIR) + "/config/";
  testing::write_text(tmp / "facectl.yaml", "head: " + config + "heads/default/head.yaml\n" +
                                                "rig: " + config + "rigs/default.yaml\n" +
                                                "expressions: " + config +
                                                "expressions/library.yaml\n");
  const auto r = run_facectl({"run", "--quiet", "--config", tmp / "facectl.yaml", "--fap-stream"},
                             tmp / "log.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--fap-stream: expected a fap_stream block"), std::string::npos)
      << r.output;
}

}  // namespace
}  // namespace facectl
