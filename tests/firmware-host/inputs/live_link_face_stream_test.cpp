// The Live Link Face UDP stream: packets as PyLiveLinkFace (an independent
// implementation of the app's format) encodes them, every way a datagram can
// be broken, and a flood on loopback.
#include "firmware-host/inputs/live_link_face_stream.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <thread>

#include "../fap/udp_sender.hpp"
#include "default_retarget.hpp"
#include "firmware-host/inputs/arkit_capture.hpp"
#include "firmware-host/inputs/live_link_face_packet.hpp"

namespace facectl {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes read_fixture(const std::string& name) {
  std::ifstream in(std::string(INPUT_REAL_FILES) + "/live_link_face_udp/" + name, std::ios::binary);
  EXPECT_TRUE(in) << name;
  return Bytes(std::istreambuf_iterator<char>(in), {});
}

std::string text(const Bytes& b) {
  return std::string(b.begin(), b.end());
}

std::string error_of(const Bytes& b) {
  try {
    parse_live_link_face_packet(b);
  } catch (const LiveLinkFacePacketError& e) {
    return e.what();
  }
  return "parsed";
}

// The big-endian float at `at`, replaced.
void put_f32(Bytes& b, std::size_t at, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  for (int k = 0; k < 4; ++k) b[at + k] = static_cast<std::uint8_t>(bits >> (24 - 8 * k));
}

// Where the fixtures' fields sit: a 36-character device id, a 12-character name.
constexpr std::size_t kCountAt = 1 + 4 + 36 + 4 + 12 + 16;
constexpr std::size_t kValuesAt = kCountAt + 1;

TEST(LiveLinkFacePacket, ReadsWhatPyLiveLinkFaceEncodes) {
  const Bytes b = read_fixture("pylivelinkface_jaw_open_smile_left.bin");
  ASSERT_EQ(b.size(), kValuesAt + 61 * 4);
  const LiveLinkFacePacket p = parse_live_link_face_packet(b);
  EXPECT_EQ(p.device_id, "4B3A1C2D-5E6F-4071-8293-A4B5C6D7E8F9");
  EXPECT_EQ(p.subject, "facectl-test");
  EXPECT_TRUE(p.has_face);
  EXPECT_EQ(p.rate_numerator, 60);
  // The indices of PyLiveLinkFace's FaceBlendShape enum (Unreal's order).
  EXPECT_FLOAT_EQ(p.values[17], 0.6f);   // JawOpen
  EXPECT_FLOAT_EQ(p.values[15], 0.5f);   // JawLeft
  EXPECT_FLOAT_EQ(p.values[23], 0.8f);   // MouthSmileLeft
  EXPECT_FLOAT_EQ(p.values[43], 0.7f);   // BrowInnerUp
  EXPECT_FLOAT_EQ(p.values[52], 0.2f);   // HeadYaw
  EXPECT_FLOAT_EQ(p.values[53], -0.1f);  // HeadPitch
  double sum = 0;
  for (float v : p.values) sum += std::abs(v);
  EXPECT_NEAR(sum, 0.6 + 0.5 + 0.8 + 0.7 + 0.2 + 0.1, 1e-6) << "nothing else is set";
}

TEST(LiveLinkFacePacket, MapsUnrealsOrderOntoTheArkitNames) {
  EXPECT_EQ(live_link_face_arkit_index(15), *find_arkit("jawLeft"));
  EXPECT_EQ(live_link_face_arkit_index(16), *find_arkit("jawRight"));
  EXPECT_EQ(live_link_face_arkit_index(21), *find_arkit("mouthLeft"));
  EXPECT_EQ(live_link_face_arkit_index(22), *find_arkit("mouthRight"));
  EXPECT_EQ(live_link_face_arkit_index(51), *find_arkit("tongueOut"));
  std::vector<bool> seen(kArkitCount);
  for (std::size_t i = 0; i < kArkitCount; ++i) seen.at(live_link_face_arkit_index(i)) = true;
  EXPECT_EQ(std::count(seen.begin(), seen.end(), true), 52) << "a permutation";
}

TEST(LiveLinkFacePacket, APacketEndingAfterTheNameHasNoFace) {
  const Bytes b = read_fixture("pylivelinkface_neutral.bin");
  const Bytes head(b.begin(), b.begin() + 57);  // the packet's names point into it
  const LiveLinkFacePacket p = parse_live_link_face_packet(head);
  EXPECT_FALSE(p.has_face);
  EXPECT_EQ(p.subject, "facectl-test");
}

TEST(LiveLinkFacePacket, EveryTruncationIsRefusedWithItsByte) {
  const Bytes b = read_fixture("pylivelinkface_neutral.bin");
  for (std::size_t n = 0; n < b.size(); ++n) {
    if (n == 57) continue;  // the packet without a face
    const std::string e = error_of(Bytes(b.begin(), b.begin() + static_cast<long>(n)));
    EXPECT_EQ(e.rfind("byte ", 0), 0u) << n << ": " << e;
    EXPECT_NE(e.find("expected"), std::string::npos) << n << ": " << e;
  }
  EXPECT_EQ(error_of(Bytes(b.begin(), b.begin() + 60)),
            "byte 57: frame number: expected 4 bytes, found only 3");
  EXPECT_EQ(error_of({}),
            "byte 0: packet version: expected 1 bytes, found the end of the datagram");
}

TEST(LiveLinkFacePacket, RefusesWhatItCannotPlay) {
  const Bytes good = read_fixture("pylivelinkface_jaw_open_smile_left.bin");
  Bytes b = good;
  b[0] = 5;
  EXPECT_EQ(error_of(b), "byte 0: packet version: expected 6, found 5");
  b = good;
  b[kCountAt] = 52;  // the blendshapes alone, no rotations
  EXPECT_EQ(error_of(b), "byte 73: blendshape count: expected 61, found 52");
  b = good;
  put_f32(b, kValuesAt + 4 * 17, std::nanf(""));
  EXPECT_EQ(error_of(b),
            "byte 142: blendshape weight: expected a finite number, found NaN or "
            "infinity");
  b = good;
  put_f32(b, kValuesAt + 4 * 17, 1.6f);
  EXPECT_EQ(error_of(b), "byte 142: blendshape weight: expected -0.5..1.5, found 1.600000");
  b = good;
  put_f32(b, kValuesAt + 4 * 17, 1.5f);  // ARKit overshoots a little: clamped, not refused
  EXPECT_EQ(error_of(b), "parsed");
  b = good;
  put_f32(b, kValuesAt + 4 * 52, 3e38f);  // a head yaw that would swing the neck to its stop
  EXPECT_EQ(error_of(b).rfind("byte 282: rotation: expected radians within -pi..pi, found 3", 0),
            0u)
      << error_of(b);
  b = good;
  put_f32(b, kValuesAt + 4 * 52, INFINITY);
  EXPECT_NE(error_of(b).find("byte 282: rotation: expected a finite number"), std::string::npos);
  b = good;
  b.push_back(0);
  EXPECT_EQ(error_of(b),
            "byte 318: end of packet: expected the end of the datagram, found 1 "
            "more bytes");
  b = good;
  b[41] = 0xFF;  // the name's length, negative
  EXPECT_EQ(error_of(b).rfind("byte 41: subject name: expected a length 0..256, found -", 0), 0u)
      << error_of(b);
  b = good;
  b[3] = 0x01;  // the device id's length, 292
  EXPECT_EQ(error_of(b), "byte 1: device id: expected a length 0..256, found 292");
}

struct StreamFixture : ::testing::Test {
  const HeadConfig& head = testing::default_head_config();
  const RetargetTable& table = testing::default_retarget();
  LiveLinkFaceOptions options;
  StreamFixture() { options.port = 0; }

  // The pose the retargeting table gives for the fixture's values, built
  // from the ARKit names (not from the packet's order).
  std::array<double, kMaxFaceSignals> expected_pose() const {
    ArkitFrame f;
    f.weights[*find_arkit("jawOpen")] = 0.6;
    f.weights[*find_arkit("jawLeft")] = 0.5;
    f.weights[*find_arkit("mouthSmileLeft")] = 0.8;
    f.weights[*find_arkit("browInnerUp")] = 0.7;
    f.has_head = true;
    f.head_yaw = 0.2;
    f.head_pitch = -0.1;
    std::array<double, kMaxFaceSignals> pose{};
    arkit_frame_pose(f, table, head.layout, head.neutral, pose);
    return pose;
  }
};

void poll_until(LiveLinkFaceStream& s, std::uint64_t datagrams) {
  for (int i = 0; i < 500 && s.stats().datagrams + s.stats().kernel_drops < datagrams; ++i) {
    s.wait_and_poll(10);
  }
}

TEST_F(StreamFixture, PlaysAPacketThroughTheRetargetingTable) {
  LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
  testing::Sender tx(stream.port());
  tx.send(text(read_fixture("pylivelinkface_jaw_open_smile_left.bin")));
  poll_until(stream, 1);
  std::array<double, kMaxFaceSignals> pose{};
  ASSERT_TRUE(stream.latest(pose));
  const auto want = expected_pose();
  for (std::size_t i = 0; i < head.layout.size(); ++i) {
    EXPECT_NEAR(pose[i], want[i], 1e-6) << head.layout.signal(i).name;
  }
  const std::size_t jaw = *head.layout.find("jaw_pitch");
  const std::size_t pan = *head.layout.find("neck_pan");
  EXPECT_GT(pose[jaw], head.neutral[jaw] + 0.05) << "the jaw opens";
  EXPECT_NEAR(pose[pan], head.neutral[pan] + 0.2, 1e-6) << "the head turns on the neck";
  const LiveLinkFaceStats st = stream.stats();
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.subject, "facectl-test");
  EXPECT_EQ(st.device_id, "4B3A1C2D-5E6F-4071-8293-A4B5C6D7E8F9");
}

TEST_F(StreamFixture, BadPacketsAreCountedAndNeverPlayed) {
  LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
  testing::Sender tx(stream.port());
  const Bytes good = read_fixture("pylivelinkface_jaw_open_smile_left.bin");
  tx.send(text(good));
  Bytes nan = good;
  put_f32(nan, kValuesAt + 4 * 17, std::nanf(""));
  tx.send(text(nan));
  tx.send(std::string(4000, '\x06'));                     // longer than any packet
  tx.send(text(Bytes(good.begin(), good.begin() + 57)));  // no face
  poll_until(stream, 4);
  std::array<double, kMaxFaceSignals> pose{};
  ASSERT_TRUE(stream.latest(pose));
  const auto want = expected_pose();
  for (std::size_t i = 0; i < head.layout.size(); ++i) EXPECT_NEAR(pose[i], want[i], 1e-6);
  const LiveLinkFaceStats st = stream.stats();
  EXPECT_EQ(st.datagrams, 4u);
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.malformed, 2u);
  EXPECT_EQ(st.no_face, 1u);
  EXPECT_NE(st.last_error.find("expected a packet of at most 2047 bytes"), std::string::npos)
      << st.last_error;
}

TEST_F(StreamFixture, OneSenderPlaysUntilItFallsSilent) {
  options.takeover_s = 0.2;
  LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
  testing::Sender first(stream.port()), second(stream.port());
  const std::string neutral = text(read_fixture("pylivelinkface_neutral.bin"));
  const std::string jaw = text(read_fixture("pylivelinkface_jaw_open_smile_left.bin"));
  first.send(neutral);
  second.send(jaw);
  poll_until(stream, 2);
  EXPECT_EQ(stream.stats().held_back, 1u);
  std::array<double, kMaxFaceSignals> pose{};
  ASSERT_TRUE(stream.latest(pose));
  const std::size_t jaw_pitch = *head.layout.find("jaw_pitch");
  EXPECT_NEAR(pose[jaw_pitch], head.neutral[jaw_pitch], 1e-9) << "the first sender plays";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  second.send(jaw);
  poll_until(stream, 3);
  ASSERT_TRUE(stream.latest(pose));
  EXPECT_GT(pose[jaw_pitch], head.neutral[jaw_pitch] + 0.05) << "the second took over";
}

TEST_F(StreamFixture, SendersOffTheAllowListAreRefused) {
  testing::Sender pinned(0), other(0);
  options.allow = {{kIpv4Loopback, pinned.own_port()}};
  LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
  pinned.aim(stream.port());
  other.aim(stream.port());
  const std::string jaw = text(read_fixture("pylivelinkface_jaw_open_smile_left.bin"));
  other.send(jaw);
  pinned.send(jaw);
  poll_until(stream, 2);
  EXPECT_EQ(stream.stats().refused_senders, 1u);
  EXPECT_EQ(stream.stats().frames, 1u);
}

TEST_F(StreamFixture, RefusesToListenBeyondLoopbackUnlessAllowed) {
  options.bind_address = "0.0.0.0";
  try {
    LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
    FAIL() << "bound beyond loopback";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("live_link_face.allow_remote: true"), std::string::npos)
        << e.what();
  }
}

// 100 000 datagrams as fast as loopback takes them, while the receiver
// thread runs: good packets, malformed ones and oversized ones. Every
// datagram is accounted for (received or dropped by the kernel), and only
// good packets are ever played.
TEST_F(StreamFixture, AFloodIsCountedAndOnlyGoodPacketsPlay) {
  LiveLinkFaceStream stream(table, head.layout, head.neutral, options);
  stream.start();
  testing::Sender tx(stream.port());
  const std::string good = text(read_fixture("pylivelinkface_jaw_open_smile_left.bin"));
  std::mt19937 rng(7);
  constexpr int kFlood = 100'000;
  int sent_good = 0;
  for (int i = 0; i < kFlood; ++i) {
    if (i % 10 == 0) {
      tx.send(good);
      ++sent_good;
    } else if (i % 10 == 1) {
      tx.send(std::string(9000, '\x06'));
    } else {
      std::string junk = good;
      junk[rng() % junk.size()] = static_cast<char>(rng());
      junk.resize(rng() % (junk.size() + 1));
      tx.send(junk);
    }
  }
  // The kernel reports drops with the next datagram it queues: markers (good
  // packets) until every datagram is accounted for.
  std::uint64_t sent = kFlood;
  for (int i = 0; i < 500; ++i) {
    const LiveLinkFaceStats st = stream.stats();
    if (st.datagrams + st.kernel_drops >= sent) break;
    if (i % 10 == 9) {
      tx.send(good);
      ++sent;
      ++sent_good;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  stream.stop();
  const LiveLinkFaceStats st = stream.stats();
  EXPECT_EQ(st.datagrams + st.kernel_drops, sent);
  EXPECT_EQ(st.frames + st.malformed + st.no_face, st.datagrams);
  EXPECT_GE(st.frames, 1u);
  EXPECT_GE(st.malformed, st.datagrams / 20) << "the oversized ones at least";
  // A junk packet that still parses (one changed byte inside a value) may
  // play; what played is a pose of the table, never past a signal's range.
  std::array<double, kMaxFaceSignals> pose{};
  ASSERT_TRUE(stream.latest(pose));
  for (std::size_t i = 0; i < head.layout.size(); ++i) EXPECT_TRUE(std::isfinite(pose[i]));
  std::printf(
      "flood: %llu received, %llu dropped by the kernel, %llu played (%d good sent), "
      "%llu malformed\n",
      static_cast<unsigned long long>(st.datagrams),
      static_cast<unsigned long long>(st.kernel_drops), static_cast<unsigned long long>(st.frames),
      sent_good, static_cast<unsigned long long>(st.malformed));
}

}  // namespace
}  // namespace facectl
