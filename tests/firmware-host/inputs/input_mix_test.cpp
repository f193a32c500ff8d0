// Several inputs at once (the runtime file's `mix:`): each group of signals
// takes the first live source of its list, crossfades when that changes,
// and the face goes to the tick's input watchdog when no source is live.
#include "firmware-host/inputs/input_mix.hpp"

#include <gtest/gtest.h>

#include "firmware-host/config/runtime_config.hpp"
#include "tests/support/config_block.hpp"
#include "tests/support/default_head.hpp"

namespace facectl {
namespace {

constexpr std::int64_t kMs = 1'000'000;

const FaceLayout& layout() {
  static const FaceLayout l({"frontalis_l", "frontalis_r", "orbicularis_oris"});
  return l;
}

MixConfig mix_of(const std::string& yaml) {
  return testing::parse_block("mix", yaml, parse_mix_config);
}

using testing::config_error_of;

// mouth (the mandible and orbicularis oris) from the input, else capture;
// the rest from capture, else the show.
const char* kMouthFromSpeech =
    "  stale_ms: 100\n"
    "  fade_ms: 200\n"
    "  groups:\n"
    "    mouth: { signals: [jaw_*, orbicularis_oris], sources: [input, live_link_face] }\n"
    "  others: [live_link_face, show]\n";

void publish(InputMixer& m, MixSource s, double value, std::int64_t stamp) {
  FaceCommand c;
  c.values.fill(value);
  c.stamp_ns = stamp;
  m.input(s).publish(c);
}

TEST(InputMix, GroupsTakeTheirSignalsByKeyOrPatternAndTheRestAreOthers) {
  const InputMixPlan plan =
      resolve_input_mix(mix_of(kMouthFromSpeech), layout(),
                        {MixSource::kShow, MixSource::kInput, MixSource::kLiveLinkFace}, 250.0);
  ASSERT_EQ(plan.group_names, (std::vector<std::string>{"mouth", "others"}));
  EXPECT_EQ(plan.group_of[*layout().find("orbicularis_oris")], 0);
  EXPECT_EQ(plan.group_of[layout().jaw_pitch()], 0);
  EXPECT_EQ(plan.group_of[layout().jaw_protrusion()], 0);
  EXPECT_EQ(plan.group_of[*layout().find("frontalis_l")], 1);
  EXPECT_EQ(plan.sources[0], (std::vector<MixSource>{MixSource::kInput, MixSource::kLiveLinkFace}));
  EXPECT_EQ(plan.sources[1], (std::vector<MixSource>{MixSource::kLiveLinkFace, MixSource::kShow}));
  EXPECT_EQ(plan.stale_ns, 100 * kMs);
  EXPECT_EQ(plan.rate_hz, 250.0);
  // A source the run lacks drops out of the lists.
  const InputMixPlan two = resolve_input_mix(mix_of(kMouthFromSpeech), layout(),
                                             {MixSource::kInput, MixSource::kShow}, 250.0);
  EXPECT_EQ(two.sources[1], (std::vector<MixSource>{MixSource::kShow}));
}

TEST(InputMix, TheShippedBlockPlaysTheMouthFromSpeechAndTheBrowsFromCapture) {
  const RuntimeConfig rt =
      load_runtime_config(std::string(FACECTL_SOURCE_DIR) + "/config/facectl.yaml");
  ASSERT_TRUE(rt.mix.has_value());
  const FaceLayout& l = testing::default_head().head.layout;
  const InputMixPlan plan =
      resolve_input_mix(*rt.mix, l,
                        {MixSource::kShow, MixSource::kInput, MixSource::kGamepad,
                         MixSource::kFapStream, MixSource::kLiveLinkFace},
                        rt.show_rate_hz);
  ASSERT_EQ(plan.group_names, (std::vector<std::string>{"mouth", "brows_and_eyes", "others"}));
  const auto group = [&](std::string_view key) { return plan.group_of[*l.find_yaml_key(key)]; };
  for (const char* k : {"jaw_pitch_deg", "jaw_protrusion_mm", "orbicularis_oris",
                        "zygomaticus_major_l", "depressor_labii_inferioris_r", "mentalis_l"}) {
    EXPECT_EQ(group(k), 0) << k;
  }
  for (const char* k : {"frontalis_inner_l", "corrugator_supercilii_r", "orbicularis_oculi_l",
                        "eye_yaw_l_deg", "eyelid_closure_r"}) {
    EXPECT_EQ(group(k), 1) << k;
  }
  EXPECT_EQ(group("neck_pan_deg"), 2);
  EXPECT_EQ(plan.sources[0].front(), MixSource::kInput);
  EXPECT_EQ(plan.sources[1].front(), MixSource::kLiveLinkFace);
  EXPECT_EQ(plan.sources[2].front(), MixSource::kShow);
}

TEST(InputMix, MistakesAreRefusedAtTheirLine) {
  const std::vector<MixSource> both = {MixSource::kInput, MixSource::kShow};
  EXPECT_NE(config_error_of([] { mix_of("  others: [show, microphone]\n"); })
                .find(":2:18: mix.others[1]: expected one of show, input, gamepad, fap_stream, "
                      "live_link_face, midi, found 'microphone'"),
            std::string::npos);
  EXPECT_NE(
      config_error_of([] { mix_of("  others: [show, show]\n"); }).find("expected each source once"),
      std::string::npos);
  EXPECT_NE(config_error_of([] { mix_of("  groups: {}\n"); }).find("mix: expected key 'others'"),
            std::string::npos)
      << config_error_of([] { mix_of("  groups: {}\n"); });
  const std::string none = config_error_of([&] {
    resolve_input_mix(mix_of("  groups:\n    lips: { signals: [lip_*], sources: [input] }\n"
                             "  others: [show]\n"),
                      layout(), both, 250.0);
  });
  EXPECT_NE(none.find(":3:23: mix.groups.lips.signals[0]: expected a signal key or pattern of the "
                      "head (jaw_pitch_deg, frontalis_*), found 'lip_*', which matches none"),
            std::string::npos)
      << none;
  const std::string twice = config_error_of([&] {
    resolve_input_mix(mix_of("  groups:\n    a: { signals: [frontalis_*], sources: [input] }\n"
                             "    b: { signals: [frontalis_l], sources: [show] }\n"
                             "  others: [show]\n"),
                      layout(), both, 250.0);
  });
  EXPECT_NE(twice.find("expected each signal in one group, found frontalis_l in groups a and b"),
            std::string::npos)
      << twice;
  const std::string unplayed = config_error_of(
      [&] { resolve_input_mix(mix_of("  others: [show]\n"), layout(), both, 250.0); });
  EXPECT_EQ(unplayed,
            "mix: expected every source of the run in a group's sources or in others, found input "
            "in none");
}

TEST(InputMix, ASourceMayNotOutstayTheWatchdogNorTheMixRunSlowerThanIt) {
  const auto error_in = [](const std::string& blocks) {
    const testing::TempFile f("head: h.yaml\nrig: r.yaml\nexpressions: e.yaml\n" + blocks);
    return config_error_of([&] { load_runtime_config(f.path()); });
  };
  EXPECT_EQ(error_in("mix: { others: [show], stale_ms: 200 }\n"), "accepted");
  EXPECT_NE(error_in("mix: { others: [show], stale_ms: 300 }\n")
                .find("mix.stale_ms: expected a stale_ms of at most input_timeout_ms (200"),
            std::string::npos)
      << error_in("mix: { others: [show], stale_ms: 300 }\n");
  EXPECT_NE(error_in("runtime: { input_timeout_ms: 100 }\nmix: { others: [show] }\n")
                .find(": mix: expected a stale_ms of at most input_timeout_ms (100"),
            std::string::npos)
      << "the default 200 ms no longer fits: the block is named";
  EXPECT_NE(error_in("mix: { others: [show], rate_hz: 5 }\n")
                .find("mix.rate_hz: expected a rate_hz of at least 10"),
            std::string::npos);
  EXPECT_NE(error_in("runtime: { input_timeout_ms: 10 }\nmidi: { notes: [{ channel: 1, note: 60, "
                     "expression: joy }] }\n")
                .find(": midi: expected a rate_hz of at least 200"),
            std::string::npos)
      << error_in(
             "runtime: { input_timeout_ms: 10 }\nmidi: { notes: [{ channel: 1, note: 60, "
             "expression: joy }] }\n");
}

TEST(InputMix, EachGroupPlaysItsFirstLiveSourceAndCrossfadesWhenItGoes) {
  LatestValueMailbox<FaceCommand> out;
  std::array<double, kMaxFaceSignals> neutral{};
  InputMixer mix(
      resolve_input_mix(mix_of(kMouthFromSpeech), layout(),
                        {MixSource::kShow, MixSource::kInput, MixSource::kLiveLinkFace}, 250.0),
      neutral, out);
  const std::size_t lips = *layout().find("orbicularis_oris");
  const std::size_t brow = *layout().find("frontalis_l");
  FaceCommand got;
  // Nothing live yet: nothing for the tick (its watchdog holds neutral).
  EXPECT_FALSE(mix.step(0));
  EXPECT_FALSE(out.consume(got));

  publish(mix, MixSource::kInput, 0.8, 1);
  publish(mix, MixSource::kLiveLinkFace, 0.3, 2);
  publish(mix, MixSource::kShow, 0.1, 3);
  ASSERT_TRUE(mix.step(1000 * kMs));
  ASSERT_TRUE(out.consume(got));
  EXPECT_DOUBLE_EQ(got.values[lips], 0.0) << "fades in from neutral";
  EXPECT_EQ(got.stamp_ns, 2) << "the newest of the poses it plays";
  for (std::int64_t t = 1020; t <= 1200; t += 20) {
    publish(mix, MixSource::kInput, 0.8, t);
    publish(mix, MixSource::kLiveLinkFace, 0.3, t);
    mix.step(t * kMs);
  }
  ASSERT_TRUE(out.consume(got));
  EXPECT_DOUBLE_EQ(got.values[lips], 0.8);
  EXPECT_DOUBLE_EQ(got.values[layout().jaw_pitch()], 0.8);
  EXPECT_DOUBLE_EQ(got.values[brow], 0.3);
  EXPECT_EQ(mix.playing(0), static_cast<int>(MixSource::kInput));
  EXPECT_EQ(mix.playing(1), static_cast<int>(MixSource::kLiveLinkFace));

  // The input stops: 100 ms later the mouth goes to capture, over 200 ms.
  for (std::int64_t t = 1220; t <= 1280; t += 20) {
    publish(mix, MixSource::kLiveLinkFace, 0.3, t);
    mix.step(t * kMs);
  }
  EXPECT_EQ(mix.playing(0), static_cast<int>(MixSource::kInput)) << "still within stale_ms";
  publish(mix, MixSource::kLiveLinkFace, 0.3, 1301);
  mix.step(1301 * kMs);  // 101 ms since the input's last pose
  EXPECT_EQ(mix.playing(0), static_cast<int>(MixSource::kLiveLinkFace));
  publish(mix, MixSource::kLiveLinkFace, 0.3, 1401);
  mix.step(1401 * kMs);
  ASSERT_TRUE(out.consume(got));
  EXPECT_NEAR(got.values[lips], 0.55, 1e-12) << "halfway from 0.8 to 0.3";
  publish(mix, MixSource::kLiveLinkFace, 0.3, 1501);
  mix.step(1501 * kMs);
  ASSERT_TRUE(out.consume(got));
  EXPECT_DOUBLE_EQ(got.values[lips], 0.3);
  EXPECT_DOUBLE_EQ(got.values[brow], 0.3) << "the others kept capture throughout";
  mix.step(1520 * kMs);
  EXPECT_FALSE(out.consume(got)) << "nothing new, no fade: nothing for the tick's watchdog";

  // Capture stops too: the others fall to the show, whose last pose is too old.
  mix.step(1700 * kMs);
  EXPECT_EQ(mix.playing(1), -1);
  EXPECT_FALSE(out.consume(got)) << "no source live: nothing published";
  // Capture comes back: it fades in from neutral, where the watchdog took the face.
  publish(mix, MixSource::kLiveLinkFace, 0.3, 1800);
  ASSERT_TRUE(mix.step(1800 * kMs));
  ASSERT_TRUE(out.consume(got));
  EXPECT_DOUBLE_EQ(got.values[brow], 0.0);
  EXPECT_EQ(
      mix.describe(),
      "mouth: live_link_face (changed source 3 times), others: live_link_face (changed source 2 "
      "times)");
}

}  // namespace
}  // namespace facectl
