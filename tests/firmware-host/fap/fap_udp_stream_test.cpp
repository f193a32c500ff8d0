#include "firmware-host/fap/fap_udp_stream.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <numbers>
#include <stdexcept>
#include <thread>

#include "default_fap_head.hpp"
#include "udp_sender.hpp"

namespace facectl {
namespace {

using testing::default_fap_head;
using testing::fap_frame_text;
using testing::poll_until;
using testing::Sender;

double pitch(const std::array<double, kMaxFaceSignals>& pose) {
  return pose[default_fap_head().head.layout.jaw_pitch()];
}

TEST(FapUdpStream, BindsToLoopbackByDefault) {
  EXPECT_EQ(FapUdpOptions{}.bind_address, "127.0.0.1");
  FapUdpStream s(default_fap_head().mapping, {});
  EXPECT_NE(s.port(), 0);
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_FALSE(s.latest(pose));
  EXPECT_EQ(s.poll(), 0u) << "nothing queued: returns at once";
}

TEST(FapUdpStream, BadBindAddressIsAnError) {
  FapUdpOptions o;
  o.bind_address = "not-an-address";
  EXPECT_THROW(FapUdpStream(default_fap_head().mapping, o), ConfigError);
}

TEST(FapUdpStream, DeliversFramesAndRejectsBadDatagrams) {
  LatestValueMailbox<FaceCommand> mailbox;
  FapUdpStream stream(default_fap_head().mapping, {}, &mailbox);
  Sender tx(stream.port());
  tx.send("# live\n2.1 live 25 0\n");
  tx.send(fap_frame_text(0, {{3, "400"}}));
  poll_until(stream, 1, 0);
  FapUdpStats st = stream.stats();
  EXPECT_EQ(st.datagrams, 2u);
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.malformed, 0u);
  std::array<double, kMaxFaceSignals> pose{};
  ASSERT_TRUE(stream.latest(pose));
  const double good = pitch(pose);
  EXPECT_NEAR(good, default_fap_head().mapping.pitch_for_open_jaw(400), 1e-12);
  EXPECT_GT(good, 0.0);
  FaceCommand cmd;
  ASSERT_TRUE(mailbox.consume(cmd));
  EXPECT_EQ(cmd.values[default_fap_head().head.layout.jaw_pitch()], good);
  EXPECT_EQ(cmd.sequence, 1u);

  // Malformed: a non-numeric value; a frame without its values; an old frame number.
  std::string bad = fap_frame_text(1, {{3, "800"}});
  bad.replace(bad.find("800"), 3, "8x0");
  tx.send(bad);
  const std::string frame = fap_frame_text(2, {{3, "800"}});
  tx.send(frame.substr(0, frame.find('\n') + 1));
  tx.send(fap_frame_text(0, {{3, "900"}}));
  poll_until(stream, 1, 3);
  st = stream.stats();
  EXPECT_EQ(st.malformed, 3u);
  EXPECT_EQ(st.frames, 1u);
  EXPECT_NE(st.last_error.find("datagram 5"), std::string::npos) << st.last_error;
  EXPECT_NE(st.last_error.find(":2:"), std::string::npos) << st.last_error;
  EXPECT_NE(st.last_error.find("greater than the previous frame's 0"), std::string::npos)
      << st.last_error;
  ASSERT_TRUE(stream.latest(pose));
  EXPECT_EQ(pitch(pose), good) << "a bad datagram never changes the last good pose";
  EXPECT_FALSE(mailbox.consume(cmd)) << "nor reaches the mailbox";

  // The stream goes on after them, holding FAPs a frame does not send.
  tx.send(fap_frame_text(3, {{12, "100"}}));
  poll_until(stream, 2, 3);
  ASSERT_TRUE(stream.latest(pose));
  EXPECT_EQ(pitch(pose), good);
  EXPECT_GT(pose[*default_fap_head().head.layout.find("zygomaticus_major_l")], 0.0);
  EXPECT_TRUE(mailbox.consume(cmd));
}

TEST(FapUdpStream, FramesBeforeAHeaderAreRejected) {
  FapUdpStream stream(default_fap_head().mapping, {});
  Sender tx(stream.port());
  tx.send(fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 0, 1);
  const FapUdpStats st = stream.stats();
  EXPECT_EQ(st.malformed, 1u);
  EXPECT_NE(st.last_error.find("header"), std::string::npos) << st.last_error;
}

TEST(FapUdpStream, ReceiverThreadFeedsTheMailbox) {
  LatestValueMailbox<FaceCommand> mailbox;
  FapUdpStream stream(default_fap_head().mapping, {}, &mailbox);
  stream.start();
  Sender tx(stream.port());
  tx.send("2.1 live 25 0\n" + fap_frame_text(7, {{3, "300"}}));
  FaceCommand cmd;
  bool got = false;
  for (int i = 0; i < 200 && !got; ++i) {
    got = mailbox.consume(cmd);
    if (!got) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  stream.stop();
  ASSERT_TRUE(got);
  EXPECT_NEAR(cmd.values[default_fap_head().head.layout.jaw_pitch()],
              default_fap_head().mapping.pitch_for_open_jaw(300), 1e-12);
}

// The readers are the receiving thread's alone: a second thread polling
// them would race it.
TEST(FapUdpStream, PollingBesideTheReceiverThreadIsRefused) {
  FapUdpStream stream(default_fap_head().mapping, {});
  stream.start();
  EXPECT_THROW(stream.poll(), std::logic_error);
  stream.stop();
  EXPECT_NO_THROW(stream.poll());
}

}  // namespace
}  // namespace facectl
