// The speech-driven jaw: a WAV written through libsndfile, syllables of tone
// between pauses; the jaw opens on each, closes in the pauses, closes more
// slowly than it opens, leads the sound when asked, and ignores the level.
#include "firmware-host/inputs/speech_envelope.hpp"

#include <gtest/gtest.h>
#include <sndfile.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "firmware-host/config/config_node.hpp"

namespace facectl {
namespace {

const FaceLayout& layout() {
  static const FaceLayout l({"m"});
  return l;
}

// A file name of this process (ctest runs tests in parallel).
std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name))
      .string();
}

// 0.3 s pause, then `syllables` of 0.2 s tone at `level` with 0.3 s pauses.
std::string write_wav(const std::string& name, double level, int syllables = 2, int rate = 16000,
                      int format = SF_FORMAT_WAV | SF_FORMAT_PCM_16, float spike = 0.0f) {
  const std::string path = temp_path(name);
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = 1;
  info.format = format;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  EXPECT_NE(f, nullptr);
  std::vector<float> s;
  auto pause = [&](double secs) { s.insert(s.end(), static_cast<std::size_t>(secs * rate), 0.0f); };
  pause(0.3);
  for (int k = 0; k < syllables; ++k) {
    for (int i = 0; i < static_cast<int>(0.2 * rate); ++i) {
      s.push_back(static_cast<float>(level * std::sin(2 * M_PI * 220.0 * i / rate)));
    }
    pause(0.3);
  }
  if (spike != 0.0f) s[s.size() / 5] = spike;  // in the first pause
  sf_writef_float(f, s.data(), static_cast<sf_count_t>(s.size()));
  sf_close(f);
  return path;
}

double jaw_deg(const PoseTrack& t, double time) {
  std::array<double, kMaxFaceSignals> p{};
  t.evaluate(time, p);
  return p[layout().jaw_pitch()] * 180.0 / M_PI;
}

TEST(SpeechEnvelope, TheJawOpensOnEachSyllableAndClosesInThePauses) {
  std::vector<std::string> notes;
  const PoseTrack t =
      speech_envelope_track(write_wav("facectl_speech.wav", 0.5), layout(), {}, {}, notes);
  EXPECT_NEAR(t.duration(), 1.3, 0.02);
  EXPECT_LT(jaw_deg(t, 0.2), 0.5);          // before the first syllable
  EXPECT_GT(jaw_deg(t, 0.45), 0.9 * 12.0);  // in it
  EXPECT_LT(jaw_deg(t, 0.75), 1.0);         // in the pause after it
  EXPECT_GT(jaw_deg(t, 0.95), 0.9 * 12.0);  // the second
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("1.3 s of audio at 16000 Hz"), std::string::npos) << notes[0];
}

TEST(SpeechEnvelope, ItClosesMoreSlowlyThanItOpens) {
  std::vector<std::string> notes;
  const PoseTrack t =
      speech_envelope_track(write_wav("facectl_speech.wav", 0.5), layout(), {}, {}, notes);
  // 30 ms after the onset (0.3 s) and after the end (0.5 s, +20 ms window).
  const double opened = jaw_deg(t, 0.3 + 0.03);
  const double closed_by = 12.0 - jaw_deg(t, 0.52 + 0.03);
  EXPECT_GT(opened, closed_by + 2.0) << opened << " " << closed_by;
}

TEST(SpeechEnvelope, TheRecordingLevelDoesNotMatter) {
  std::vector<std::string> notes;
  const PoseTrack loud =
      speech_envelope_track(write_wav("facectl_loud.wav", 0.8), layout(), {}, {}, notes);
  const PoseTrack quiet =
      speech_envelope_track(write_wav("facectl_quiet.wav", 0.02), layout(), {}, {}, notes);
  for (double time : {0.2, 0.35, 0.45, 0.6, 0.9}) {
    EXPECT_NEAR(jaw_deg(loud, time), jaw_deg(quiet, time), 0.3) << time;
  }
}

TEST(SpeechEnvelope, TheJawLeadsTheSoundByTheLeadTime) {
  std::vector<std::string> notes;
  SpeechEnvelopeParams p;
  p.lead_s = 0.1;
  const std::string wav = write_wav("facectl_speech.wav", 0.5);
  const PoseTrack plain = speech_envelope_track(wav, layout(), {}, {}, notes);
  const PoseTrack led = speech_envelope_track(wav, layout(), {}, p, notes);
  for (double time : {0.25, 0.3, 0.4, 0.55}) {
    EXPECT_NEAR(jaw_deg(led, time), jaw_deg(plain, time + 0.1), 1e-9) << time;
  }
}

TEST(SpeechEnvelope, ANonFiniteSampleInAFloatFileIsCountedNotSpread) {
  std::vector<std::string> notes;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PoseTrack t = speech_envelope_track(
      write_wav("facectl_nan.wav", 0.5, 2, 16000, SF_FORMAT_WAV | SF_FORMAT_FLOAT, nan), layout(),
      {}, {}, notes);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("clamped 1 samples"), std::string::npos) << notes[0];
  EXPECT_GT(jaw_deg(t, 0.95), 0.9 * 12.0);  // the second syllable still opens the jaw
}

TEST(SpeechEnvelope, RefusesSampleRatesItCannotTime) {
  std::vector<std::string> notes;
  for (int rate : {100, 999}) {
    try {
      speech_envelope_track(write_wav("facectl_rate.wav", 0.5, 1, rate), layout(), {}, {}, notes);
      FAIL() << rate;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("expected a sample rate of 1000 to 768000 Hz"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(SpeechEnvelope, RefusesWhatIsNotAudioByName) {
  const std::string path = temp_path("facectl_not.wav");
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("RIFF....WAVEnot really", f);
  std::fclose(f);
  std::vector<std::string> notes;
  try {
    speech_envelope_track(path, layout(), {}, {}, notes);
    FAIL() << "read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": expected an audio file"), std::string::npos)
        << e.what();
  }
  try {
    speech_envelope_track("/tmp", layout(), {}, {}, notes);
    FAIL() << "read";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp: expected a regular audio file"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace facectl
