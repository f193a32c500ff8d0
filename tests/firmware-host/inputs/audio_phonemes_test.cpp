// Phonemes from audio: speech synthesised by eSpeak NG (real/audio/SOURCES.md)
// through libsamplerate and PocketSphinx's allphone search into visemes.
// Recognition of synthetic speech is modest (docs/INPUTS.md), so the tests
// assert what must hold whatever the exact phones: bilabials are heard where
// the text has many and hardly where it has none, the lips seal on each one
// heard, silence rests the mouth, the same file gives the same phones, and a
// missing model is named with the package that installs it.
#include "firmware-host/inputs/audio_phonemes.hpp"

#include <gtest/gtest.h>
#include <sndfile.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "default_retarget.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/fap/viseme_table.hpp"
#include "firmware-host/inputs/coarticulation.hpp"
#include "firmware-host/inputs/lip_sync_track.hpp"
#include "firmware-host/inputs/speech_16k.hpp"

namespace facectl {
namespace {

const std::string kAudio = std::string(INPUT_REAL_FILES) + "/audio";
const std::string kBilabials = kAudio + "/espeak_bilabials.wav";
const std::string kNoBilabials = kAudio + "/espeak_no_bilabials.wav";

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / (std::to_string(getpid()) + "_" + name))
      .string();
}

std::string write_wav(const std::string& name, const std::vector<float>& interleaved, int rate,
                      int channels) {
  const std::string path = temp_path(name);
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = channels;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  EXPECT_NE(f, nullptr);
  sf_writef_float(f, interleaved.data(), static_cast<sf_count_t>(interleaved.size() / channels));
  sf_close(f);
  return path;
}

void print(const std::string& what, const PhonemeTrack& t) {
  std::string s;
  for (const PhonemeSegment& p : t.segments) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " %s@%.2f-%.2f", p.label.c_str(), p.start_s, p.end_s);
    s += buf;
  }
  std::printf("%s:%s\n", what.c_str(), s.c_str());
  for (const std::string& n : t.notes) std::printf("  note: %s\n", n.c_str());
}

int count_viseme(const PhonemeTrack& t, int viseme) {
  int n = 0;
  for (const PhonemeSegment& p : t.segments) n += p.viseme == viseme;
  return n;
}

const PhonemeTrack& bilabials() {
  static const PhonemeTrack t = audio_phoneme_track(kBilabials);
  return t;
}

TEST(AudioPhonemes, HearsBilabialsWhereTheTextHasManyAndHardlyWhereItHasNone) {
  const PhonemeTrack& with = bilabials();
  const PhonemeTrack without = audio_phoneme_track(kNoBilabials);
  print("bilabials", with);
  print("no bilabials", without);
  // eSpeak NG says 12 bilabials in the first text and none in the second.
  const int heard_with = count_viseme(with, kVisemePBM);
  const int heard_without = count_viseme(without, kVisemePBM);
  EXPECT_GE(heard_with, 4);
  EXPECT_LE(heard_without, 2);
  EXPECT_GE(heard_with, 3 * std::max(heard_without, 1));
  // The phones are CMU phones: each has a viseme, none was unknown.
  for (const PhonemeSegment& p : with.segments) {
    EXPECT_EQ(p.viseme == kVisemeNone, p.label == "SIL" || p.label.front() == '+') << p.label;
  }
  // Speech fills the file: most of it is phones, not rest.
  int spoken = 0;
  for (const PhonemeSegment& p : with.segments) spoken += p.viseme != kVisemeNone;
  EXPECT_GE(spoken, 15);
  EXPECT_NEAR(with.duration_s, 65947.0 / 22050.0, 1e-9);  // the file's frames
  EXPECT_LE(with.segments.back().end_s, with.duration_s);
  EXPECT_NE(with.notes.back().find("phones recognised"), std::string::npos);
  EXPECT_EQ(with.notes.front(), "resampled from 22050 Hz to 16 kHz for the phone recogniser");
}

TEST(AudioPhonemes, TheLipsSealOnEachBilabialHeardAndOpenOnItsVowels) {
  const PhonemeTrack& t = bilabials();
  const HeadConfig& head = testing::default_head_config();
  const VisemeTable visemes =
      VisemeTable::load(std::string(FACECTL_SOURCE_DIR) + "/config/fap/visemes.yaml", head.layout);
  const VisemeTimeline timeline = VisemeTimeline::build(t, {});
  const PoseTrack poses = lip_sync_pose_track(timeline, visemes, head.layout, head.neutral);
  const FacePose& closed = visemes.pose(kVisemePBM);
  std::array<double, kVisemeCount> w{};
  std::array<double, kMaxFaceSignals> pose{};
  int sealed = 0, opened = 0;
  for (const PhonemeSegment& p : t.segments) {
    const double mid = 0.5 * (p.start_s + p.end_s);
    timeline.weights(mid, w);
    poses.evaluate(mid, pose);
    if (p.viseme == kVisemePBM) {
      // The closure's hold: exactly the p_b_m pose, whatever the neighbours.
      EXPECT_DOUBLE_EQ(w[kVisemePBM], 1.0) << p.label << " at " << mid;
      for (std::size_t i = 0; i < head.layout.size(); ++i) {
        if (closed.set.test(i)) {
          EXPECT_NEAR(pose[i], closed.values[i], 1e-12) << head.layout.signal(i).name;
        }
      }
      ++sealed;
    } else if (p.viseme == kVisemeA && p.end_s - p.start_s >= 0.08) {
      EXPECT_LT(w[kVisemePBM], 0.1) << p.label << " at " << mid;
      ++opened;
    }
  }
  EXPECT_GE(sealed, 4);
  EXPECT_GE(opened, 2);  // "Bob", "papa", "mama" have long open vowels
}

TEST(AudioPhonemes, TheSameFileGivesTheSamePhones) {
  // Dither (noise against digital silence) runs from a fixed seed.
  const PhonemeTrack again = audio_phoneme_track(kBilabials);
  ASSERT_EQ(again.segments.size(), bilabials().segments.size());
  for (std::size_t i = 0; i < again.segments.size(); ++i) {
    EXPECT_EQ(again.segments[i].label, bilabials().segments[i].label) << i;
    EXPECT_EQ(again.segments[i].start_s, bilabials().segments[i].start_s) << i;
  }
}

TEST(AudioPhonemes, SilenceIsRestThroughout) {
  const std::string path =
      write_wav("facectl_silence.wav", std::vector<float>(16000, 0.0f), kSpeechRate, 1);
  const PhonemeTrack t = audio_phoneme_track(path);
  print("silence", t);
  ASSERT_FALSE(t.segments.empty());
  EXPECT_EQ(count_viseme(t, kVisemeNone), static_cast<int>(t.segments.size()));
  EXPECT_DOUBLE_EQ(t.duration_s, 1.0);
  for (const std::string& n : t.notes) EXPECT_EQ(n.find("resampled"), std::string::npos) << n;
  const HeadConfig& head = testing::default_head_config();
  const VisemeTable visemes =
      VisemeTable::load(std::string(FACECTL_SOURCE_DIR) + "/config/fap/visemes.yaml", head.layout);
  const PoseTrack poses =
      lip_sync_pose_track(VisemeTimeline::build(t, {}), visemes, head.layout, head.neutral);
  std::array<double, kMaxFaceSignals> pose{};
  for (double s = 0.0; s <= 1.0; s += 0.1) {
    poses.evaluate(s, pose);
    for (std::size_t i = 0; i < head.layout.size(); ++i) {
      EXPECT_NEAR(pose[i], head.neutral[i], 1e-9) << head.layout.signal(i).name << " at " << s;
    }
  }
  std::filesystem::remove(path);
}

TEST(AudioPhonemes, AMissingModelIsNamedWithThePackageThatInstallsIt) {
  PhoneModel model = PhoneModel::debian_en_us();
  model.acoustic_dir = "/nonexistent/en-us";
  try {
    (void)audio_phoneme_track(kBilabials, model);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(kBilabials + ": phoneme recognition needs PocketSphinx's acoustic model "
                                  "/nonexistent/en-us, found nothing there"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("pocketsphinx-en-us"), std::string::npos) << m;
  }
  model = PhoneModel::debian_en_us();
  model.phone_lm = "/nonexistent/en-us-phone.lm.bin";
  EXPECT_THROW(
      {
        try {
          (void)audio_phoneme_track(kBilabials, model);
        } catch (const ConfigError& e) {
          EXPECT_NE(std::string(e.what()).find("phone language model /nonexistent/en-us-phone"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      ConfigError);
}

// The message of the ConfigError `f` throws, or "" for none.
template <class F>
std::string config_error(F f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(AudioPhonemes, ADamagedModelIsAnErrorNotAnExitOrAnUnweightedLoop) {
  namespace fs = std::filesystem;
  const PhoneModel good = PhoneModel::debian_en_us();
  const fs::path dir = temp_path("facectl_bad_model");
  fs::remove_all(dir);
  fs::create_directories(dir / "en-us");
  for (const auto& e : fs::directory_iterator(good.acoustic_dir))
    fs::create_symlink(e.path(), dir / "en-us" / e.path().filename());
  std::FILE* f = std::fopen((dir / "bad.lm.bin").c_str(), "w");
  std::fputs("not a language model\n", f);
  std::fclose(f);

  // A phone model PocketSphinx cannot read: it would go on with an
  // unweighted phone loop after logging an error.
  std::string m = config_error([&] {
    (void)audio_phoneme_track(kBilabials, {good.acoustic_dir, dir / "bad.lm.bin"});
  });
  EXPECT_NE(m.find(kBilabials + ": phoneme recognition with "), std::string::npos) << m;
  EXPECT_NE(m.find("the model did not load: ERROR"), std::string::npos) << m;
  EXPECT_NE(m.find("bad.lm.bin is not a dump file"), std::string::npos) << m;

  // A damaged acoustic model: PocketSphinx's fatal error would exit().
  fs::remove(dir / "en-us" / "mdef");
  f = std::fopen((dir / "en-us" / "mdef").c_str(), "w");
  std::fputs("garbage\n", f);
  std::fclose(f);
  m = config_error([&] { (void)audio_phoneme_track(kBilabials, {dir / "en-us", good.phone_lm}); });
  EXPECT_NE(m.find("PocketSphinx stopped: FATAL"), std::string::npos) << m;
  EXPECT_NE(m.find("pocketsphinx-en-us"), std::string::npos) << m;

  // And the next file decodes as before.
  EXPECT_EQ(audio_phoneme_track(kBilabials).segments.size(), bilabials().segments.size());
  fs::remove_all(dir);
}

TEST(AudioPhonemes, AFileThatIsNotAudioIsRefusedByName) {
  const std::string path = temp_path("facectl_not_audio.wav");
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs("RIFF but not really\n", f);
  std::fclose(f);
  const std::string m = config_error([&] { (void)audio_phoneme_track(path); });
  EXPECT_EQ(m.rfind(path + ": expected an audio file libsndfile reads", 0), 0u) << m;
  std::filesystem::remove(path);
}

TEST(Speech16k, ResamplingKeepsPitchLengthAndLevelAndMixesChannels) {
  // 1 s of a 440 Hz tone at 44.1 kHz, stereo: the left at 0.5, the right at 0.3.
  const int rate = 44100;
  std::vector<float> s;
  for (int i = 0; i < rate; ++i) {
    const auto x = static_cast<float>(std::sin(2 * M_PI * 440.0 * i / rate));
    s.push_back(0.5f * x);
    s.push_back(0.3f * x);
  }
  const std::string path = write_wav("facectl_tone.wav", s, rate, 2);
  const Speech16k out = read_speech_16k(path, 10.0);
  EXPECT_EQ(out.source_rate, rate);
  EXPECT_EQ(out.source_channels, 2);
  EXPECT_NEAR(static_cast<double>(out.samples.size()), 16000.0, 2.0);
  // Away from the ends: 440 rising zero crossings a second, amplitude 0.4.
  int crossings = 0;
  int peak = 0;
  for (std::size_t i = 1000; i + 1000 < out.samples.size(); ++i) {
    crossings += out.samples[i - 1] < 0 && out.samples[i] >= 0;
    peak = std::max(peak, std::abs(static_cast<int>(out.samples[i])));
  }
  EXPECT_NEAR(crossings, 440.0 * 14000.0 / 16000.0, 2.0);
  EXPECT_NEAR(peak / 32768.0, 0.4, 0.01);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace facectl
