// `facectl serve`'s OSC control: datagrams built by python-osc (an
// independent implementation of OSC 1.0, tests/firmware-host/inputs/peers)
// reach the head service as operations, and what is not OSC, not in the
// address space or out of range is counted and leaves the face as it was.
#include "firmware-host/serve/osc_control.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>

#include "firmware-host/serve/osc_message.hpp"
#include "tests/firmware-host/serve/served_head.hpp"
#include "tests/support/loopback_udp.hpp"
#include "tests/support/text_files.hpp"

namespace facectl {
namespace {

using testing::send_udp;

void poll_until(OscControl& osc, std::uint64_t datagrams) {
  for (int i = 0; i < 500 && osc.stats().datagrams < datagrams; ++i) osc.wait_and_poll(10);
}

// An OSC string: its bytes, a NUL, padded to 4.
std::string osc_string(const std::string& s) {
  std::string out = s;
  out.push_back('\0');
  while (out.size() % 4 != 0) out.push_back('\0');
  return out;
}

std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

TEST(OscControl, AppliesWhatPythonOscSendsAndCountsTheRest) {
  testing::ServedHead head;
  UdpListenOptions options;
  OscControl osc(head.service(), options);
  const std::string peer =
      std::string(FACECTL_SOURCE_DIR) + "/tests/firmware-host/inputs/peers/osc_peer.py";
  ASSERT_EQ(
      std::system(
          ("python3 " + peer + " send " + std::to_string(osc.port()) + " > /dev/null").c_str()),
      0);
  poll_until(osc, 5);
  const OscStats st = osc.stats();
  EXPECT_EQ(st.datagrams, 5u);
  EXPECT_EQ(st.messages, 5u) << "one, two in the bundle, one unknown, one out of range";
  EXPECT_EQ(st.applied, 3u);
  EXPECT_EQ(st.unknown_address, 1u);
  EXPECT_EQ(st.refused, 1u);
  EXPECT_EQ(st.malformed, 1u);
  EXPECT_NE(st.last_error.find("expected an OSC message"), std::string::npos) << st.last_error;
  // The bundle's two signals are held together, on top of neutral (the
  // event log names both); the refused 30 deg left them as they were.
  const FaceDirector::Status status = head.session().director->status();
  EXPECT_EQ(status.source, FaceDirector::Source::kPose);
  bool jaw_seen = false;
  for (int i = 0; i < 200 && !jaw_seen; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    const auto log = testing::read_text(head.log_path());
    jaw_seen = log.find("jaw_pitch_deg=12") != std::string::npos &&
               log.find("neck_pan_deg=10") != std::string::npos;
  }
  EXPECT_TRUE(jaw_seen) << testing::read_text(head.log_path());
  const std::string log = testing::read_text(head.log_path());
  EXPECT_NE(log.find("\"source\":\"osc 127.0.0.1:"), std::string::npos) << log;
  EXPECT_NE(log.find("hold expression joy at 0.5"), std::string::npos) << log;
  EXPECT_NE(log.find("refused: /facectl/signal/jaw_pitch_deg: expected -4..18, found 30"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("refused: /facectl/no_such_thing: no such address"), std::string::npos) << log;
}

TEST(OscControl, RefusesWhatIsNotOscAndNamesWhy) {
  const auto error_of = [](const std::string& bytes) {
    try {
      decode_osc_datagram(bytes);
    } catch (const OscFormatError& e) {
      return std::string(e.what());
    }
    return std::string("decoded");
  };
  const std::string msg = osc_string("/facectl/neutral") + osc_string(",");
  EXPECT_EQ(error_of(msg), "decoded");
  EXPECT_NE(error_of(msg.substr(0, 10)).find("expected an OSC message"), std::string::npos);
  const std::string head = osc_string("#bundle") + std::string(8, '\0');
  EXPECT_EQ(error_of(head + be32(static_cast<std::uint32_t>(msg.size())) + msg), "decoded");
  EXPECT_EQ(error_of(head + be32(1000) + msg),
            "expected a bundle element of a multiple of 4 bytes within the datagram, found a "
            "size of 1000");
  EXPECT_EQ(error_of(head.substr(0, 12)), "expected a bundle's time tag, found the end");
  std::string nested = msg;
  for (int i = 0; i < 5; ++i)
    nested = head + be32(static_cast<std::uint32_t>(nested.size())) + nested;
  EXPECT_EQ(error_of(nested), "expected bundles nested at most 4 deep, found deeper");
  const std::string blob =
      osc_string("/facectl/expression") + osc_string(",b") + be32(4) + std::string("abcd");
  EXPECT_EQ(error_of(blob),
            "/facectl/expression: expected number or string arguments, found type 'b'");
  std::string many;
  for (int i = 0; i < 65; ++i) many += be32(static_cast<std::uint32_t>(msg.size())) + msg;
  EXPECT_EQ(error_of(head + many), "expected at most 64 messages in a datagram, found more");
}

TEST(OscControl, WrongArgumentsAndStoppingAreRefusedWithTheirReason) {
  testing::ServedHead head;
  OscControl osc(head.service(), UdpListenOptions{});
  send_udp(osc.port(), {osc_string("/facectl/expression") + osc_string(",f") + be32(0x3f000000)});
  send_udp(osc.port(), {osc_string("/facectl/show/play") + osc_string(",s") + osc_string("nope")});
  poll_until(osc, 2);
  OscStats st = osc.stats();
  EXPECT_EQ(st.refused, 2u);
  EXPECT_NE(st.last_error.find("no show 'nope'"), std::string::npos) << st.last_error;
  send_udp(osc.port(), {osc_string("/facectl/show/play") + osc_string(",s") + osc_string("demo")});
  poll_until(osc, 3);
  st = osc.stats();
  EXPECT_EQ(st.applied, 1u) << st.last_error;
  EXPECT_EQ(head.session().director->status().source, FaceDirector::Source::kShow);
}

TEST(OscControl, ARunawaySenderIsCountedWithoutFillingTheEventLog) {
  testing::ServedHead head;
  OscControl osc(head.service(), UdpListenOptions{});
  const std::vector<std::string> refused(
      40, osc_string("/facectl/expression") + osc_string(",s") + osc_string("nope"));
  send_udp(osc.port(), refused);
  poll_until(osc, 40);
  EXPECT_EQ(osc.stats().refused, 40u);
  const std::string log = testing::read_text(head.log_path());
  std::size_t logged = 0;
  for (auto at = log.find("refused: no expression 'nope'"); at != std::string::npos;
       at = log.find("refused: no expression 'nope'", at + 1)) {
    ++logged;
  }
  EXPECT_EQ(logged, 10u) << log;
}

TEST(OscControl, NeutralLeavesAnExpressionAndStrangeBytesAreLoggedEscaped) {
  testing::ServedHead head;
  OscControl osc(head.service(), UdpListenOptions{});
  send_udp(osc.port(), {osc_string("/facectl/expression") + osc_string(",s") + osc_string("joy")});
  poll_until(osc, 1);
  EXPECT_EQ(head.session().director->status().source, FaceDirector::Source::kExpression);
  send_udp(osc.port(), {osc_string("/facectl/neutral") + osc_string(",")});
  poll_until(osc, 2);
  EXPECT_EQ(osc.stats().applied, 2u) << osc.stats().last_error;
  EXPECT_EQ(head.session().director->status().source, FaceDirector::Source::kPose);
  EXPECT_NE(testing::read_text(head.log_path()).find("hold pose neutral (OSC)"), std::string::npos);
  // A show queued before neutral does not come back after it.
  send_udp(osc.port(), {osc_string("/facectl/show/play") + osc_string(",s") + osc_string("demo"),
                        osc_string("/facectl/show/queue") + osc_string(",s") + osc_string("demo"),
                        osc_string("/facectl/neutral") + osc_string(",")});
  poll_until(osc, 5);
  EXPECT_TRUE(head.session().director->status().queue.empty());
  EXPECT_EQ(head.session().director->status().source, FaceDirector::Source::kPose);
  // A refused name with a byte that is not text, and an escape sequence.
  send_udp(osc.port(),
           {osc_string("/facectl/expression") + osc_string(",s") + osc_string("j\xff\x1b[2Jy")});
  poll_until(osc, 6);
  const OscStats st = osc.stats();
  EXPECT_EQ(st.refused, 1u);
  EXPECT_NE(st.last_error.find("no expression 'j\\xff\\x1b[2Jy'"), std::string::npos)
      << st.last_error;
  EXPECT_NE(testing::read_text(head.log_path()).find("j\\\\xff\\\\x1b[2Jy"), std::string::npos)
      << "JSON-escaped backslashes in the log file";
}

TEST(OscControl, ListensOnLoopbackUnlessAllowedBeyond) {
  testing::ServedHead head;
  UdpListenOptions o;
  o.bind_address = "0.0.0.0";
  try {
    OscControl osc(head.service(), o);
    FAIL() << "bound beyond loopback";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("osc.allow_remote: true"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facectl
