// The Maestro's serial commands against the byte examples of Pololu's
// Maestro Servo Controller User's Guide (https://www.pololu.com/docs/0J40,
// sections 5.c "Serial protocols" and 5.e "Serial Servo Commands"), and the
// simulated Maestro parsing the same bytes.
#include "drivers/protocol/maestro_serial.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "sim/devices/maestro_sim.hpp"

namespace facectl {
namespace {

using Bytes = std::vector<std::uint8_t>;
constexpr maestro::Addressing kCompact{maestro::Protocol::kCompact, 12};
constexpr maestro::Addressing kPololu12{maestro::Protocol::kPololu, 12};

template <typename F>
Bytes encoded(F&& f) {
  std::uint8_t buf[64];
  const std::size_t n = f(std::span<std::uint8_t>(buf));
  return Bytes(buf, buf + n);
}

TEST(MaestroSerial, SetTargetMatchesTheGuidesExamples) {
  // 5.e: channel 2 to 1500 us (6000 quarter-us): 0x84, 0x02, 0x70, 0x2E.
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_target(kCompact, 2, 6000, o); }),
            (Bytes{0x84, 0x02, 0x70, 0x2E}));
  // 5.c: servo 0 to 1500 us on device 12: 0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E.
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_target(kPololu12, 0, 6000, o); }),
            (Bytes{0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E}));
  // 0 stops the pulses; 14 bits at most.
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_target(kCompact, 1, 0, o); }),
            (Bytes{0x84, 0x01, 0x00, 0x00}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_target(kCompact, 1, 0x3FFF, o); }),
            (Bytes{0x84, 0x01, 0x7F, 0x7F}));
  EXPECT_TRUE(
      encoded([](auto o) { return maestro::encode_set_target(kCompact, 1, 0x4000, o); }).empty());
  EXPECT_TRUE(
      encoded([](auto o) { return maestro::encode_set_target(kCompact, 128, 6000, o); }).empty());
  std::uint8_t small[3];
  EXPECT_EQ(maestro::encode_set_target(kCompact, 1, 6000, small), 0u);
}

TEST(MaestroSerial, SpeedMultipleTargetsPositionAndErrorsMatchTheGuide) {
  // 5.e: "0x87, 0x05, 0x0C, 0x01 sets the speed of servo channel 5 to 140".
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_speed(kCompact, 5, 140, o); }),
            (Bytes{0x87, 0x05, 0x0C, 0x01}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_set_acceleration(kPololu12, 5, 4, o); }),
            (Bytes{0xAA, 0x0C, 0x09, 0x05, 0x04, 0x00}));
  // 5.e: channel 3 to 0 (off) and channel 4 to 6000: 0x9F, 0x02, 0x03, 0x00,
  // 0x00, 0x70, 0x2E.
  const std::uint16_t two[] = {0, 6000};
  EXPECT_EQ(
      encoded([&](auto o) { return maestro::encode_set_multiple_targets(kCompact, 3, two, o); }),
      (Bytes{0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_get_position(kCompact, 7, o); }),
            (Bytes{0x90, 0x07}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_get_position(kPololu12, 7, o); }),
            (Bytes{0xAA, 0x0C, 0x10, 0x07}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_get_errors(kCompact, o); }), (Bytes{0xA1}));
  EXPECT_EQ(encoded([](auto o) { return maestro::encode_get_errors(kPololu12, o); }),
            (Bytes{0xAA, 0x0C, 0x21}));
  // Replies are little-endian: 0x70, 0x17 is 6000.
  const std::uint8_t reply[] = {0x70, 0x17};
  EXPECT_EQ(maestro::reply_u16(reply), 6000);
}

TEST(MaestroSerial, NamesTheErrorBitsWorstFirst) {
  EXPECT_EQ(maestro::error_text(0), "none");
  EXPECT_EQ(maestro::error_text(0x0010 | 0x0020), "serial timeout, serial protocol error");
  EXPECT_EQ(maestro::error_text(0x0100), "script program counter error");
  EXPECT_EQ(maestro::error_text(0x0201), "serial signal error (baud rate?), unknown bits 0x0200");
  EXPECT_EQ(maestro::worst_error(0x0011), maestro::kErrSerialSignal);
  EXPECT_EQ(maestro::worst_error(0x0031), maestro::kErrSerialTimeout);
  EXPECT_EQ(maestro::worst_error(0x0400), 0x0400);
  EXPECT_EQ(maestro::worst_error(0), 0);
}

TEST(MaestroSerial, CycleBytesCountEveryCommandAndReply) {
  // Compact, 10 channels: 10 x 4 targets + 10 x (2 + 2) positions + 1 + 2 errors.
  EXPECT_EQ(maestro::cycle_bytes(maestro::Protocol::kCompact, 10, false, 10), 83u);
  // One Set Multiple Targets: 1 + 2 + 20.
  EXPECT_EQ(maestro::cycle_bytes(maestro::Protocol::kCompact, 10, true, 10), 66u);
  // Pololu: two more header bytes per command.
  EXPECT_EQ(maestro::cycle_bytes(maestro::Protocol::kPololu, 1, false, 1), 6u + 6u + 5u);
}

// The simulated Maestro takes the guide's bytes as the real one does.
std::vector<std::uint8_t> feed(sim::MaestroSim& m, const Bytes& bytes) {
  std::vector<std::uint8_t> reply;
  for (const std::uint8_t b : bytes) m.feed(b, 0, reply);
  return reply;
}

TEST(MaestroSim, ParsesBothProtocolsAsTheGuideSays) {
  sim::MaestroSim m(12, 12);
  EXPECT_TRUE(feed(m, {0x84, 0x02, 0x70, 0x2E}).empty());
  EXPECT_EQ(m.target(2), 6000);
  EXPECT_EQ(feed(m, {0x90, 0x02}), (Bytes{0x70, 0x17}));
  feed(m, {0xAA, 0x0C, 0x04, 0x00, 0x70, 0x2E});
  EXPECT_EQ(m.target(0), 6000);
  // Another device number: ignored, no error.
  feed(m, {0xAA, 0x0D, 0x04, 0x00, 0x00, 0x00});
  EXPECT_EQ(m.target(0), 6000);
  feed(m, {0x9F, 0x02, 0x03, 0x00, 0x00, 0x70, 0x2E});
  EXPECT_EQ(m.target(3), 0);
  EXPECT_EQ(m.target(4), 6000);
  feed(m, {0x87, 0x05, 0x0C, 0x01});
  EXPECT_EQ(m.speed(5), 140);
  EXPECT_EQ(feed(m, {0xAA, 0x0C, 0x21}), (Bytes{0x00, 0x00}));
  // Outside the channel's range (factory 992..2000 us): clamped.
  feed(m, {0x84, 0x01, 0x00, 0x40});  // 8192 quarter-us
  EXPECT_EQ(m.target(1), 8000);
}

TEST(MaestroSim, AnInterruptedPacketIsAProtocolErrorThatGetErrorsClears) {
  sim::MaestroSim m(12);
  feed(m, {0x84, 0x02, 0x70, 0x2E});
  // Set Target cut short by Get Errors, which reports (and clears) it.
  EXPECT_EQ(feed(m, {0x84, 0x02, 0xA1}), (Bytes{0x10, 0x00}));
  EXPECT_EQ(m.target(2), 0) << "an error sends the outputs home (Off)";
  EXPECT_EQ(feed(m, {0xA1}), (Bytes{0x00, 0x00}));
  // Set Multiple Targets on a Micro Maestro 6: unknown there.
  sim::MaestroSim micro(6);
  feed(micro, {0x9F, 0x01, 0x00, 0x70, 0x2E});
  EXPECT_EQ(micro.errors(), maestro::kErrSerialProtocol);
}

}  // namespace
}  // namespace facectl
