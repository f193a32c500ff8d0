// MIDI to the face (the runtime file's `midi:` map): controls move signals
// over their mapped range, notes hold expressions at their velocity, and
// mistakes in the map are refused at their line. The ALSA sequencer client
// itself is tested in the QEMU guest (tests/drivers/qemu/midi_guest_test.cpp).
#include "firmware-host/inputs/midi_face.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "control/units.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "firmware-host/inputs/midi_input.hpp"
#include "tests/support/config_block.hpp"
#include "tests/support/default_head.hpp"

namespace facectl {
namespace {

MidiConfig midi_of(const std::string& yaml) {
  return testing::parse_block("midi", yaml, parse_midi_config);
}

using testing::config_error_of;

const char* kMap =
    "  controls:\n"
    "    - { channel: 1, cc: 1, signal: jaw_pitch_deg, min: 0, max: 12 }\n"
    "    - { channel: 1, cc: 2, signal: neck_pan_deg, min: -30, max: 30 }\n"
    "  notes:\n"
    "    - { channel: 1, note: 60, expression: joy }\n"
    "    - { channel: 10, note: 62, expression: surprise }\n";

MidiFaceMap default_map(const std::string& yaml = kMap) {
  const auto& h = testing::default_head();
  return resolve_midi_map(midi_of(yaml), h.head.layout, h.expressions);
}

TEST(MidiFace, ControlsMoveTheirSignalOverTheMappedRange) {
  const auto& h = testing::default_head();
  const MidiFaceMap map = default_map();
  MidiFaceState face(map, h.head.neutral);
  std::array<double, kMaxFaceSignals> pose{};
  face.pose(pose);
  EXPECT_EQ(pose, h.head.neutral) << "nothing moved yet";
  EXPECT_EQ(face.control(0, 1, 127), MidiFaceState::Applied::kControl);
  EXPECT_EQ(face.control(0, 2, 0), MidiFaceState::Applied::kControl);
  EXPECT_EQ(face.control(1, 1, 127), MidiFaceState::Applied::kUnmapped) << "channel 2";
  face.pose(pose);
  const FaceLayout& l = h.head.layout;
  EXPECT_NEAR(pose[l.jaw_pitch()], 12 * kDeg, 1e-12);
  EXPECT_NEAR(pose[*l.find_yaml_key("neck_pan_deg")], -30 * kDeg, 1e-12);
  face.control(0, 1, 64);
  face.pose(pose);
  EXPECT_NEAR(pose[l.jaw_pitch()], 64.0 / 127.0 * 12 * kDeg, 1e-12);
}

TEST(MidiFace, NotesHoldTheirExpressionAtTheirVelocityUntilLetGo) {
  const auto& h = testing::default_head();
  const MidiFaceMap map = default_map();
  MidiFaceState face(map, h.head.neutral);
  const std::size_t smile = *h.head.layout.find("zygomaticus_major_l");
  const double joy_smile = h.expressions.find("joy")->values[smile];
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_EQ(face.note_on(0, 60, 127), MidiFaceState::Applied::kNoteOn);
  face.pose(pose);
  EXPECT_NEAR(pose[smile], joy_smile, 1e-12);
  // A second note takes over (the last pressed wins); letting it go falls
  // back to the first, still down (legato); then letting the first go
  // while the second is down changes nothing.
  EXPECT_EQ(face.note_on(9, 62, 64), MidiFaceState::Applied::kNoteOn);
  face.pose(pose);
  EXPECT_NEAR(pose[smile], h.head.neutral[smile], 1e-12);
  EXPECT_NE(pose, h.head.neutral) << "surprise at 64/127";
  EXPECT_EQ(face.note_off(9, 62), MidiFaceState::Applied::kNoteOff);
  face.pose(pose);
  EXPECT_NEAR(pose[smile], joy_smile, 1e-12) << "back to joy, still down";
  face.note_on(9, 62, 64);
  EXPECT_EQ(face.note_off(0, 60), MidiFaceState::Applied::kNoteOff);
  face.pose(pose);
  EXPECT_NEAR(pose[smile], h.head.neutral[smile], 1e-12);
  EXPECT_NE(pose, h.head.neutral) << "surprise at 64/127";
  // Note on with velocity 0 is a note off, as running status senders write it.
  EXPECT_EQ(face.note_on(9, 62, 0), MidiFaceState::Applied::kNoteOff);
  face.pose(pose);
  EXPECT_EQ(pose, h.head.neutral);
  EXPECT_EQ(face.note_on(0, 61, 100), MidiFaceState::Applied::kUnmapped);
  face.control(0, 1, 100);
  face.reset();
  face.pose(pose);
  EXPECT_EQ(pose, h.head.neutral) << "reset forgets the controls too";
}

TEST(MidiFace, TheShippedMapMovesBothEyesWithOneControl) {
  const RuntimeConfig rt =
      load_runtime_config(std::string(FACECTL_SOURCE_DIR) + "/config/facectl.yaml");
  ASSERT_TRUE(rt.midi.has_value());
  const auto& h = testing::default_head();
  const MidiFaceMap map = resolve_midi_map(*rt.midi, h.head.layout, h.expressions);
  EXPECT_EQ(map.notes.size(), 6u);
  MidiFaceState face(map, h.head.neutral);
  face.control(0, 4, 127);
  std::array<double, kMaxFaceSignals> pose{};
  face.pose(pose);
  EXPECT_NEAR(pose[*h.head.layout.find_yaml_key("eye_yaw_l_deg")], 25 * kDeg, 1e-12);
  EXPECT_NEAR(pose[*h.head.layout.find_yaml_key("eye_yaw_r_deg")], 25 * kDeg, 1e-12);
}

TEST(MidiFace, MistakesInTheMapAreRefusedAtTheirLine) {
  EXPECT_NE(config_error_of([] {
              midi_of("  controls:\n    - { channel: 17, cc: 1, signal: x, min: 0, max: 1 }\n");
            }).find(":3:18: midi.controls[0].channel: expected an integer in [1, 16], found '17'"),
            std::string::npos)
      << config_error_of([] {
           midi_of("  controls:\n    - { channel: 17, cc: 1, signal: x, min: 0, max: 1 }\n");
         });
  EXPECT_NE(config_error_of([] {
              midi_of(
                  "  notes:\n    - { channel: 1, note: 60, expression: joy }\n"
                  "    - { channel: 1, note: 60, expression: fear }\n");
            }).find("expected each channel and note mapped once"),
            std::string::npos);
  EXPECT_NE(config_error_of([] {
              midi_of("  client: facectl\n");
            }).find("midi: expected controls or notes mapped to the face, found neither"),
            std::string::npos);
  EXPECT_NE(
      config_error_of([] {
        default_map("  controls:\n    - { channel: 1, cc: 1, signal: jaw_open, min: 0, max: 1 }\n");
      }).find(":3:7: midi.controls[0].signal: expected a signal key of the head"),
      std::string::npos)
      << config_error_of([] {
           default_map(
               "  controls:\n    - { channel: 1, cc: 1, signal: jaw_open, min: 0, max: 1 }\n");
         });
  EXPECT_NE(config_error_of([] {
              default_map(
                  "  controls:\n    - { channel: 1, cc: 1, signal: zygomaticus_major_l, min: 0, "
                  "max: 2 }\n");
            })
                .find("expected min and max within zygomaticus_major_l's domain "
                      "0.000000..1.000000, found 2"),
            std::string::npos);
  EXPECT_NE(
      config_error_of([] {
        default_map("  notes:\n    - { channel: 1, note: 60, expression: glee }\n");
      }).find("midi.notes[0].expression: expected an expression of the library, found 'glee'"),
      std::string::npos);
}

TEST(MidiInput, WithoutTheSequencerSaysWhichModuleToLoad) {
  struct stat st {};
  if (stat("/dev/snd/seq", &st) == 0)
    GTEST_SKIP() << "/dev/snd/seq exists, so the missing-sequencer error cannot be provoked "
                    "here; MidiInGuest (QEMU) tests the sequencer itself";
  const auto& h = testing::default_head();
  const MidiFaceMap map = default_map();
  try {
    MidiInput midi(map, h.head.neutral, MidiConfig{}, nullptr);
    FAIL() << "opened a sequencer that is not there";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("MIDI: cannot open the ALSA sequencer"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("load the snd-seq module"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facectl
