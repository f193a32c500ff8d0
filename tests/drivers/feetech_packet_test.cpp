// The Feetech SCS/STS codec against byte examples of the published protocol:
// the SCS communication protocol manual's PING and READ (which are
// DYNAMIXEL Protocol 1.0's packet layout), and packets the SDK's
// SCS.cpp builds (writeBuf, syncWrite, syncReadPacketTx).
#include "drivers/protocol/feetech_packet.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "drivers/protocol/feetech_table.hpp"

namespace facectl {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes take(const std::array<std::uint8_t, 300>& buf, std::size_t n) {
  return Bytes(buf.begin(), buf.begin() + static_cast<long>(n));
}

TEST(FeetechPacket, PingAndReadMatchTheManualsExamples) {
  std::array<std::uint8_t, 300> out{};
  // PING servo 1: FF FF 01 02 01 FB.
  EXPECT_EQ(take(out, scs::encode_instruction(1, scs::kPing, {}, out)),
            (Bytes{0xFF, 0xFF, 0x01, 0x02, 0x01, 0xFB}));
  // READ 2 bytes of Present Position (0x38) from servo 1: FF FF 01 04 02 38 02 BE.
  EXPECT_EQ(take(out, scs::encode_read(1, 0x38, 2, out)),
            (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x02, 0x38, 0x02, 0xBE}));
}

TEST(FeetechPacket, WriteAndBroadcastSyncWriteMatchTheProtocol) {
  std::array<std::uint8_t, 300> out{};
  // WRITE ID := 1 to every servo (broadcast): FF FF FE 04 03 05 01 F4.
  const std::uint8_t id = 1;
  EXPECT_EQ(take(out, scs::encode_write(scs::kBroadcastId, ft::kId, {&id, 1}, out)),
            (Bytes{0xFF, 0xFF, 0xFE, 0x04, 0x03, 0x05, 0x01, 0xF4}));
  // SYNC WRITE of Goal Position (42) to servos 1 and 2, STS byte order:
  // 2048 = 00 08, 1024 = 00 04. Length = (2 + 1) * 2 + 4 = 10.
  const std::uint8_t ids[] = {1, 2};
  std::uint8_t data[4];
  ft::put_u16(ft::Series::kSts, data, 2048);
  ft::put_u16(ft::Series::kSts, data + 2, 1024);
  const Bytes sync = take(out, scs::encode_sync_write(ft::kGoalPosition, 2, ids, data, out));
  const Bytes want{0xFF, 0xFF, 0xFE, 0x0A, 0x83, 0x2A, 0x02, 0x01, 0x00, 0x08, 0x02, 0x00, 0x04};
  ASSERT_EQ(sync.size(), want.size() + 1);
  EXPECT_EQ(Bytes(sync.begin(), sync.end() - 1), want);
  unsigned sum = 0;
  for (std::size_t i = 2; i < want.size(); ++i) sum += want[i];
  EXPECT_EQ(sync.back(), static_cast<std::uint8_t>(~sum));
  // SYNC READ of 8 feedback bytes from servos 1 and 2: FF FF FE 06 82 38 08 01 02 chk.
  const Bytes read = take(out, scs::encode_sync_read(0x38, 8, ids, out));
  EXPECT_EQ(read,
            (Bytes{0xFF, 0xFF, 0xFE, 0x06, 0x82, 0x38, 0x08, 0x01, 0x02,
                   static_cast<std::uint8_t>(~(0xFE + 0x06 + 0x82 + 0x38 + 0x08 + 0x01 + 0x02))}));
}

TEST(FeetechPacket, TheSeriesDifferInByteOrderAndSignBits) {
  std::uint8_t b[2];
  // Present Position 0x0800 = 2048: STS sends 00 08, SCS 08 00 (SCS.cpp Host2SCS).
  ft::put_u16(ft::Series::kSts, b, 2048);
  EXPECT_EQ(b[0], 0x00);
  EXPECT_EQ(b[1], 0x08);
  ft::put_u16(ft::Series::kScs, b, 2048);
  EXPECT_EQ(b[0], 0x08);
  EXPECT_EQ(b[1], 0x00);
  EXPECT_EQ(ft::get_u16(ft::Series::kScs, b), 2048);
  // Load: bit 10 is the sign; speed: bit 15.
  EXPECT_EQ(ft::sign_magnitude(0x0400 | 300, 10), -300);
  EXPECT_EQ(ft::sign_magnitude(300, 10), 300);
  EXPECT_EQ(ft::sign_magnitude(0x8000 | 50, 15), -50);
  EXPECT_EQ(ft::to_sign_magnitude(-300, 10), 0x0400 | 300);
}

TEST(FeetechPacket, ParsesAStatusAfterNoiseAndRejectsABadChecksum) {
  // Status of servo 1 answering the manual's READ: position 0x0800 (STS order)
  // and error 0; noise and a stray FF before it.
  std::array<std::uint8_t, 300> out{};
  const std::uint8_t pos[] = {0x00, 0x08};
  const std::size_t n = scs::encode_status(1, 0, pos, out);
  EXPECT_EQ(take(out, n), (Bytes{0xFF, 0xFF, 0x01, 0x04, 0x00, 0x00, 0x08, 0xF2}));
  Bytes wire{0x12, 0xFF, 0x34};
  wire.insert(wire.end(), out.begin(), out.begin() + static_cast<long>(n));
  std::array<std::uint8_t, scs::kMaxParams> params{};
  scs::Packet p;
  ASSERT_EQ(scs::parse_packet(wire, p, params), scs::ParseResult::kOk);
  EXPECT_EQ(p.id, 1);
  EXPECT_EQ(p.code, 0);
  EXPECT_EQ(p.param_count, 2u);
  EXPECT_EQ(p.consumed, wire.size());
  EXPECT_EQ(params[1], 0x08);
  // Error bits come through as they are: overheating and overload.
  scs::encode_status(1, ft::kErrOverheat | ft::kErrOverload, pos, out);
  ASSERT_EQ(scs::parse_packet({out.data(), n}, p, params), scs::ParseResult::kOk);
  EXPECT_EQ(p.code, 0x24);
  // A flipped bit: bad checksum, consumed whole.
  out[5] ^= 0x01;
  EXPECT_EQ(scs::parse_packet({out.data(), n}, p, params), scs::ParseResult::kBadChecksum);
  EXPECT_EQ(p.consumed, n);
  // Cut short: incomplete, nothing consumed.
  EXPECT_EQ(scs::parse_packet({out.data(), n - 1}, p, params), scs::ParseResult::kIncomplete);
  EXPECT_EQ(p.consumed, 0u);
  // A length byte below 2.
  const Bytes bad{0xFF, 0xFF, 0x01, 0x01, 0x00, 0x00};
  EXPECT_EQ(scs::parse_packet(bad, p, params), scs::ParseResult::kBadLength);
  EXPECT_GT(p.consumed, 0u);
  // More parameters than the caller's buffer.
  std::array<std::uint8_t, 1> small{};
  EXPECT_EQ(scs::parse_packet({out.data(), n}, p, small), scs::ParseResult::kBadLength);
}

}  // namespace
}  // namespace facectl
