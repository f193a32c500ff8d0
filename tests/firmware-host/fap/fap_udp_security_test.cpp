// The FAP stream's security model (docs/FAP.md, "Who may send"), over real
// UDP sockets on loopback: per-sender state, the allow list, bounds on every
// field, the loopback-only bind and the kernel's drop count (issue 21, item 7).
#include <gtest/gtest.h>
#include <sys/socket.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "default_fap_head.hpp"
#include "firmware-host/fap/fap_udp_stream.hpp"
#include "udp_sender.hpp"

namespace facectl {
namespace {

using testing::default_fap_head;
using testing::fap_frame_text;
using testing::poll_until;
using testing::poll_until_datagrams;
using testing::Sender;

const std::string kHeader = "2.1 live 25 0\n";

const FapMapping& mapping() {
  return default_fap_head().mapping;
}

double jaw_pitch(const FapUdpStream& s) {
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_TRUE(s.latest(pose));
  return pose[default_fap_head().head.layout.jaw_pitch()];
}

double open_jaw(double fapu) {
  return mapping().pitch_for_open_jaw(fapu);
}

const FapUdpPeerStats* find_peer(const std::vector<FapUdpPeerStats>& all, const Sender& s) {
  for (const auto& p : all) {
    if (p.peer == s.name()) return &p;
  }
  return nullptr;
}

// A stream and two senders on it, `a` already playing frame `first` (the
// jaw opened by 100).
struct TwoSenders {
  static FapUdpOptions with_takeover(double takeover_s) {
    FapUdpOptions o;
    o.takeover_s = takeover_s;
    return o;
  }
  explicit TwoSenders(double takeover_s, long first = 0)
      : stream(mapping(), with_takeover(takeover_s)), a(stream.port()), b(stream.port()) {
    a.send(kHeader + fap_frame_text(first, {{3, "100"}}));
    poll_until(stream, 1, 0);
  }
  FapUdpStream stream;
  Sender a;
  Sender b;
};

// Two frames played, the last opening the jaw by 200; one datagram refused
// as out of bounds with `error`; nothing malformed.
void expect_refused_then_played_on(const FapUdpStream& stream, const std::string& error) {
  const FapUdpStats st = stream.stats();
  EXPECT_EQ(st.frames, 2u);
  EXPECT_EQ(st.malformed, 0u);
  EXPECT_EQ(st.out_of_bounds, 1u);
  EXPECT_NE(st.last_error.find(error), std::string::npos) << st.last_error;
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(200), 1e-12);
}

// One datagram with frame 9223372036854775807 used to lock the playing
// sender out for good: it is refused, and the playing sender goes on.
TEST(FapUdpSecurity, AFrameFarAheadFromAnotherSenderLocksNobodyOut) {
  FapUdpStream stream(mapping(), {});
  Sender legit(stream.port());
  Sender rogue(stream.port());
  legit.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  rogue.send(kHeader + fap_frame_text(9223372036854775807L, {{3, "900"}}));
  poll_until_datagrams(stream, 2);
  legit.send(fap_frame_text(1, {{3, "200"}}));
  poll_until(stream, 2, 0);
  expect_refused_then_played_on(stream,
                                "expected a frame number after the header of at most 1000, "
                                "found 9223372036854775807");
}

// A header from one sender restarts its own numbering only, and while one
// sender plays, another's frames are held back.
TEST(FapUdpSecurity, AnotherSendersHeaderRestartsOnlyItsOwnNumbering) {
  TwoSenders t(60.0, 5);
  auto& [stream, a, b] = t;
  b.send(kHeader + fap_frame_text(0, {{3, "900"}}));
  poll_until_datagrams(stream, 2);
  a.send(fap_frame_text(3, {{3, "200"}}));  // not above a's own 5
  poll_until(stream, 1, 1);
  a.send(fap_frame_text(6, {{3, "300"}}));
  poll_until(stream, 2, 1);
  const FapUdpStats st = stream.stats();
  EXPECT_EQ(st.frames, 2u);
  EXPECT_EQ(st.malformed, 1u);
  EXPECT_EQ(st.held_back, 1u);
  EXPECT_EQ(st.peers, 2u);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(300), 1e-12);
  const auto peers = stream.peer_stats();
  const FapUdpPeerStats* pa = find_peer(peers, a);
  const FapUdpPeerStats* pb = find_peer(peers, b);
  ASSERT_TRUE(pa != nullptr && pb != nullptr);
  EXPECT_EQ(pa->datagrams, 3u);
  EXPECT_EQ(pa->frames, 2u);
  EXPECT_EQ(pa->malformed, 1u);
  EXPECT_NE(pa->last_error.find("from " + a.name() + ":2:1: expected a frame number greater"),
            std::string::npos)
      << pa->last_error;
  EXPECT_EQ(pb->datagrams, 1u);
  EXPECT_EQ(pb->frames, 0u);
  EXPECT_EQ(pb->held_back, 1u);
}

TEST(FapUdpSecurity, AnotherSenderPlaysOnceThePlayingOneFallsSilent) {
  TwoSenders t(0.05);
  auto& [stream, a, b] = t;
  std::this_thread::sleep_for(std::chrono::milliseconds(150));
  b.send(kHeader + fap_frame_text(0, {{3, "300"}}));
  poll_until(stream, 2, 0);
  EXPECT_EQ(stream.stats().held_back, 0u);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(300), 1e-12);
}

// Frame 0, then `refused` (a datagram whose frame `found` is too far ahead),
// then frame 1: the datagram is refused and frame 1 plays.
void expect_jump_refused(FapUdpStream& stream, Sender& tx, const std::string& refused, long found) {
  tx.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  tx.send(refused);
  tx.send(fap_frame_text(1, {{3, "200"}}));
  poll_until(stream, 2, 0);
  expect_refused_then_played_on(
      stream,
      "expected a frame number at most 1000 above frame 0, the sender's last before this "
      "datagram, found " +
          std::to_string(found));
}

TEST(FapUdpSecurity, AFrameNumberFarAheadIsRefusedNotAdopted) {
  FapUdpStream stream(mapping(), {});
  Sender tx(stream.port());
  expect_jump_refused(stream, tx, fap_frame_text(5000, {{3, "900"}}), 5000);
}

// The jump is bounded per datagram: 64 frames each 1000 ahead of the one
// before would move the numbering 64,000 frames in one datagram.
TEST(FapUdpSecurity, TheJumpIsBoundedPerDatagramNotPerFrame) {
  FapUdpStream stream(mapping(), {});
  Sender tx(stream.port());
  expect_jump_refused(stream, tx,
                      fap_frame_text(600, {{3, "500"}}) + fap_frame_text(1200, {{3, "900"}}), 1200);
  // A header inside the datagram restarts the count from 0.
  tx.send(fap_frame_text(900, {{3, "300"}}) + kHeader + fap_frame_text(800, {{3, "400"}}));
  poll_until(stream, 4, 0);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(400), 1e-12);
}

// Each field past its bound: counted, never played, and the sender is not
// locked out by it.
TEST(FapUdpSecurity, EveryFieldIsBounded) {
  FapUdpStream stream(mapping(), {});
  Sender tx(stream.port());
  std::uint64_t sent = 0;
  auto refused = [&](const std::string& datagram, const std::string& expected) {
    tx.send(datagram);
    poll_until_datagrams(stream, ++sent);
    const FapUdpStats st = stream.stats();
    EXPECT_EQ(st.out_of_bounds, sent) << expected;
    EXPECT_NE(st.last_error.find(expected), std::string::npos) << st.last_error;
  };
  refused("2.1 " + std::string(65000, 'n') + " 25 0\n",
          ":1: expected a header name of at most 64 characters, found 65000 characters");
  refused("2.1 slow 1e-300 0\n",
          "expected a frame rate in 1..1000 frames per second, found 1e-300");
  refused("2.1 fast 1e9 0\n", "found 1e+09");
  refused("2.1 long 25 9000000000000000000\n",
          "expected a frame count of at most 100000000, found 9000000000000000000");
  refused(kHeader + fap_frame_text(0, {{3, "1e300"}}),
          ":3: expected FAP 3 within +-100000 FAPU, found 1e+300");
  std::string many = kHeader;
  for (int i = 0; i < 65; ++i) many += fap_frame_text(i, {{3, "100"}});
  refused(many, ":131: expected at most 64 frames in one datagram, found frame 65");
  FapUdpStats st = stream.stats();
  EXPECT_EQ(st.frames, 0u);
  EXPECT_EQ(st.malformed, 0u);
  std::array<double, kMaxFaceSignals> pose{};
  EXPECT_FALSE(stream.latest(pose)) << "an out-of-bounds datagram was played";

  tx.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(100), 1e-12);
}

TEST(FapUdpSecurity, SendersOffTheAllowListAreCountedAndDropped) {
  EXPECT_EQ(FapUdpOptions{}.allow, (std::vector<UdpSenderRule>{{kIpv4Loopback, 0}}))
      << "default: loopback, any port";
  FapUdpOptions o;
  o.allow = {*parse_udp_sender_rule("127.0.0.2/32")};
  FapUdpStream stream(mapping(), o);
  Sender other(stream.port(), "127.0.0.1");
  Sender allowed(stream.port(), "127.0.0.2");
  other.send(kHeader + fap_frame_text(0, {{3, "900"}}));
  poll_until_datagrams(stream, 1);
  FapUdpStats st = stream.stats();
  EXPECT_EQ(st.refused_senders, 1u);
  EXPECT_EQ(st.frames, 0u);
  EXPECT_EQ(st.peers, 0u) << "a refused sender gets no state";
  EXPECT_EQ(st.last_refused, other.name());
  EXPECT_EQ(st.last_error, "") << "nothing of its datagram was read";
  allowed.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  st = stream.stats();
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.refused_senders, 1u);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(100), 1e-12);
}

// Every local process passes a loopback allow list: pinning the real
// sender's port is what keeps the others out, before and after the real
// one falls silent.
TEST(FapUdpSecurity, APinnedPortShutsOutOtherLocalProcesses) {
  Sender real(0);
  FapUdpOptions o;
  o.allow = {*parse_udp_sender_rule("127.0.0.1:" + std::to_string(real.own_port()))};
  o.takeover_s = 0.0;  // any silence would let another sender play
  FapUdpStream stream(mapping(), o);
  real.aim(stream.port());
  Sender intruder(stream.port());
  intruder.send(kHeader + fap_frame_text(0, {{3, "900"}}));
  poll_until_datagrams(stream, 1);
  real.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  intruder.send(kHeader + fap_frame_text(0, {{3, "900"}}));
  poll_until_datagrams(stream, 3);
  const FapUdpStats st = stream.stats();
  EXPECT_EQ(st.refused_senders, 2u);
  EXPECT_EQ(st.last_refused, intruder.name());
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.peers, 1u);
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(100), 1e-12);
}

// A full table takes the slot of the sender heard least recently, never
// the one playing: a flood of new ports churns the other slots, and the
// playing sender keeps its numbering and plays on.
TEST(FapUdpSecurity, AFullTableEvictsTheLeastRecentlyHeardButNotThePlayingSender) {
  FapUdpOptions o;
  o.max_peers = 2;
  o.takeover_s = 60.0;
  FapUdpStream stream(mapping(), o);
  Sender playing(stream.port());
  playing.send(kHeader + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  constexpr std::uint64_t kFlood = 10;
  std::vector<std::unique_ptr<Sender>> flood;  // all open: no port is used twice
  for (std::uint64_t i = 0; i < kFlood; ++i) {
    flood.push_back(std::make_unique<Sender>(stream.port()));
    flood.back()->send(kHeader + fap_frame_text(0, {{3, "900"}}));
    poll_until_datagrams(stream, 2 + i);
  }
  Sender newest(stream.port());
  newest.send(kHeader);
  poll_until_datagrams(stream, 2 + kFlood);
  FapUdpStats st = stream.stats();
  EXPECT_EQ(st.peers, 2u);
  EXPECT_EQ(st.evicted, kFlood);
  EXPECT_EQ(st.held_back, kFlood) << "every newcomer was heard, none played";
  const auto peers = stream.peer_stats();
  EXPECT_TRUE(find_peer(peers, playing) != nullptr) << "the playing sender was evicted";
  EXPECT_TRUE(find_peer(peers, newest) != nullptr) << "the newest sender got no slot";

  playing.send(fap_frame_text(1, {{3, "200"}}));  // no header: its numbering was kept
  poll_until(stream, 2, 0);
  st = stream.stats();
  EXPECT_EQ(st.frames, 2u);
  EXPECT_EQ(st.malformed, 0u) << st.last_error;
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(200), 1e-12);
}

// A sender that numbers its frames by its clock (frame = t * rate) skips
// numbers while silent: the jump allowed grows with the silence, so it is
// not shut out, while a number beyond what the silence explains still is.
TEST(FapUdpSecurity, FrameNumbersThatFollowTheClockSurviveSilence) {
  FapUdpOptions o;
  o.limits.frame_jump = 5;
  FapUdpStream stream(mapping(), o);
  Sender tx(stream.port());
  tx.send("2.1 clocked 1000 0\n" + fap_frame_text(0, {{3, "100"}}));
  poll_until(stream, 1, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(60));  // >= 60 frames at 1000 fps
  tx.send(fap_frame_text(50, {{3, "300"}}));
  tx.send(fap_frame_text(50 + 1'000'000, {{3, "900"}}));  // 1000 s ahead
  tx.send(fap_frame_text(51, {{3, "200"}}));
  poll_until(stream, 3, 0);
  const FapUdpStats st = stream.stats();
  EXPECT_EQ(st.frames, 3u) << st.last_error;
  EXPECT_EQ(st.out_of_bounds, 1u);
  EXPECT_NE(
      st.last_error.find("above frame 50, the sender's last before this datagram, found 1000050"),
      std::string::npos)
      << st.last_error;
  EXPECT_NEAR(jaw_pitch(stream), open_jaw(200), 1e-12);
}

TEST(FapUdpSecurity, BindingBeyondLoopbackNeedsAllowRemote) {
  FapUdpOptions o;
  o.bind_address = "0.0.0.0";
  try {
    FapUdpStream stream(mapping(), o);
    FAIL() << "0.0.0.0 was bound without allow_remote";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("FAP stream 0.0.0.0:0: expected a loopback address"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("allow_remote"), std::string::npos) << e.what();
  }
  o.allow_remote = true;
  ::testing::internal::CaptureStderr();
  EXPECT_NO_THROW({ FapUdpStream stream(mapping(), o); });
  const std::string warning = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(warning.find("warning: FAP stream 0.0.0.0:"), std::string::npos) << warning;
  EXPECT_NE(warning.find("listens beyond loopback"), std::string::npos) << warning;
  ::testing::internal::CaptureStderr();
  { FapUdpStream quiet(mapping(), {}); }
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "") << "loopback needs no warning";
}

// A full receive buffer drops datagrams in the kernel; SO_RXQ_OVFL stamps
// each datagram queued after them with the running count. The flood is sent
// while nothing reads; then, until the count shows, the queue is drained and
// a marker sent, which the kernel queues after the flood (loopback may still
// be delivering it when sendto returns, so the first marker can come early
// or be dropped).
TEST(FapUdpSecurity, KernelDropsAreCounted) {
  FapUdpStream stream(mapping(), {});
  const int small = 4096;
  ASSERT_EQ(::setsockopt(stream.fd(), SOL_SOCKET, SO_RCVBUF, &small, sizeof small), 0);
  Sender tx(stream.port());
  constexpr std::uint64_t kFlood = 300;
  for (std::uint64_t i = 0; i < kFlood; ++i) tx.send(kHeader);
  std::uint64_t markers = 0;
  for (int i = 0; i < 100 && stream.stats().kernel_drops == 0; ++i) {
    stream.poll();
    tx.send("marker\n");
    ++markers;
    stream.wait_and_poll(20);
  }
  const FapUdpStats st = stream.stats();
  EXPECT_GT(st.kernel_drops, 0u);
  EXPECT_GT(st.malformed, 0u) << "no marker was read";
  EXPECT_LT(st.datagrams, kFlood) << "the receive buffer held the whole flood";
  EXPECT_LE(st.datagrams + st.kernel_drops, kFlood + markers);
}

}  // namespace
}  // namespace facectl
