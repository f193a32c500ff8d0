// Runs inside the QEMU guest, whose kernel has the ALSA sequencer (snd-seq):
// facectl's MIDI input is a sequencer client, and aplaymidi (alsa-utils, a
// peer this project did not write) plays it a MIDI file written by mido
// (tests/drivers/qemu/midi/). Checks what was played, counted and held,
// and that the input stops publishing once its sender has gone.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

#include "control/units.hpp"
#include "firmware-host/inputs/midi_input.hpp"

namespace facectl {
namespace {

TEST(MidiInGuest, PlaysWhatAplaymidiSendsAndStopsWhenItLeaves) {
  if (access("/bin/aplaymidi", X_OK) != 0) GTEST_SKIP() << "no aplaymidi (package alsa-utils)";
  const FaceLayout layout({"zygomaticus_major_l", "frontalis_l"});
  const std::size_t smile = *layout.find("zygomaticus_major_l");
  const std::size_t brow = *layout.find("frontalis_l");
  FacePose joy;
  joy.values[smile] = 0.8;
  joy.set.set(smile);
  FacePose surprise;
  surprise.values[brow] = 1.0;
  surprise.set.set(brow);
  MidiFaceMap map;
  map.controls.push_back({0, 1, layout.jaw_pitch(), 0.0, 12 * kDeg});
  map.notes.push_back({0, 60, &joy});
  map.notes.push_back({0, 62, &surprise});
  MidiConfig config;
  config.client = "facectl-test";
  std::array<double, kMaxFaceSignals> neutral{};
  LatestValueMailbox<FaceCommand> mailbox;
  MidiInput midi(map, neutral, config, &mailbox);
  midi.start();
  std::printf("MIDI in on %s\n", midi.address().c_str());

  ASSERT_EQ(std::system("aplaymidi -p facectl-test:0 /midi/cc_and_notes.mid"), 0);
  MidiStats st;
  for (int i = 0; i < 500; ++i) {
    st = midi.stats();
    if (st.events >= 6 && st.senders == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(st.controls, 2u);
  EXPECT_EQ(st.notes, 3u);
  EXPECT_EQ(st.unmapped, 1u) << "channel 2's cc 7";
  EXPECT_EQ(st.most_senders, 1);
  EXPECT_EQ(st.senders, 0);
  EXPECT_GT(st.published, 20u) << "the held pose is repeated while aplaymidi is connected";

  FaceCommand last;
  ASSERT_TRUE(mailbox.consume(last));
  EXPECT_NEAR(last.values[layout.jaw_pitch()], 64.0 / 127.0 * 12 * kDeg, 1e-12);
  EXPECT_NEAR(last.values[brow], 64.0 / 127.0, 1e-12) << "note 62 held at velocity 64";
  EXPECT_EQ(last.values[smile], 0.0) << "note 60 was let go";

  // Gone: nothing more for the tick, whose watchdog eases to neutral.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::uint64_t published = midi.stats().published;
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(midi.stats().published, published);
  midi.stop();
}

}  // namespace
}  // namespace facectl
