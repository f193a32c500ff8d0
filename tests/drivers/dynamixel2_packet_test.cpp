// DYNAMIXEL Protocol 2.0 packets against the examples of ROBOTIS's own
// e-Manual ("Protocol 2.0", docs/en/dxl/protocol2.md of ROBOTIS-GIT/emanual
// at 01179568a085, https://emanual.robotis.com/docs/en/dxl/protocol2/): every
// instruction packet byte for byte, every status packet read back.
#include "drivers/protocol/dynamixel2_packet.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace facectl::dxl2 {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes encoded(std::size_t n, const std::array<std::uint8_t, 256>& buf) {
  return Bytes(buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
}

TEST(Dynamixel2Packet, InstructionPacketsAreTheManualsByteForByte) {
  std::array<std::uint8_t, 256> out{};
  EXPECT_EQ(encoded(encode_instruction(1, kPing, {}, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E}));
  EXPECT_EQ(encoded(encode_instruction(kBroadcastId, kPing, {}, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x03, 0x00, 0x01, 0x31, 0x42}));
  // Read Present Position (132, 4 bytes) of ID 1.
  EXPECT_EQ(
      encoded(encode_read(1, 132, 4, out), out),
      (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15}));
  // Write 512 to Goal Position (116) of ID 1.
  const Bytes goal = {0x00, 0x02, 0x00, 0x00};
  EXPECT_EQ(encoded(encode_write(1, 116, goal, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x03, 0x74, 0x00, 0x00, 0x02, 0x00,
                   0x00, 0xCA, 0x89}));
  // Reg Write 200 to Goal Velocity (104), then Action.
  const Bytes reg = {0x68, 0x00, 0xC8, 0x00, 0x00, 0x00};
  EXPECT_EQ(encoded(encode_instruction(1, kRegWrite, reg, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x04, 0x68, 0x00, 0xC8, 0x00, 0x00,
                   0x00, 0xAE, 0x8E}));
  EXPECT_EQ(encoded(encode_instruction(1, kAction, {}, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x05, 0x02, 0xCE}));
  const Bytes reset_except_id = {0x01};
  EXPECT_EQ(encoded(encode_instruction(1, kFactoryReset, reset_except_id, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x06, 0x01, 0xA1, 0xE6}));
  EXPECT_EQ(encoded(encode_instruction(1, kReboot, {}, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x08, 0x2F, 0x4E}));
  const Bytes clear_multi_turn = {0x01, 0x44, 0x58, 0x4C, 0x22};
  EXPECT_EQ(encoded(encode_instruction(1, kClear, clear_multi_turn, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x10, 0x01, 0x44, 0x58, 0x4C, 0x22,
                   0xB1, 0xDC}));
  // Sync Read Present Position of IDs 1 and 2.
  const Bytes ids = {1, 2};
  EXPECT_EQ(encoded(encode_sync_read(132, 4, ids, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x09, 0x00, 0x82, 0x84, 0x00, 0x04, 0x00, 0x01,
                   0x02, 0xCE, 0xFA}));
  // Sync Write Goal Position 150 to ID 1 and 170 to ID 2.
  const Bytes goals = {0x96, 0x00, 0x00, 0x00, 0xAA, 0x00, 0x00, 0x00};
  EXPECT_EQ(encoded(encode_sync_write(116, 4, ids, goals, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x11, 0x00, 0x83, 0x74, 0x00, 0x04, 0x00,
                   0x01, 0x96, 0x00, 0x00, 0x00, 0x02, 0xAA, 0x00, 0x00, 0x00, 0x82, 0x87}));
  // Bulk Read: Present Voltage (144, 2 bytes) of ID 1, Present Temperature (146, 1) of ID 2.
  const Bytes bulk = {0x01, 0x90, 0x00, 0x02, 0x00, 0x02, 0x92, 0x00, 0x01, 0x00};
  EXPECT_EQ(encoded(encode_instruction(kBroadcastId, kBulkRead, bulk, out), out),
            (Bytes{0xFF, 0xFF, 0xFD, 0x00, 0xFE, 0x0D, 0x00, 0x92, 0x01, 0x90,
                   0x00, 0x02, 0x00, 0x02, 0x92, 0x00, 0x01, 0x00, 0x1A, 0x05}));
}

struct ManualStatus {
  Bytes wire;
  std::uint8_t id;
  Bytes params;
};

TEST(Dynamixel2Packet, StatusPacketsOfTheManualAreRead) {
  const ManualStatus cases[] = {
      // Ping: model 1030 (XM430-W210), firmware 38.
      {{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D},
       1,
       {0x06, 0x04, 0x26}},
      {{0xFF, 0xFF, 0xFD, 0x00, 0x02, 0x07, 0x00, 0x55, 0x00, 0x06, 0x04, 0x26, 0x6F, 0x6D},
       2,
       {0x06, 0x04, 0x26}},
      // Present Position 166 and 2079 (Read, Sync Read).
      {{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55, 0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0},
       1,
       {0xA6, 0x00, 0x00, 0x00}},
      {{0xFF, 0xFF, 0xFD, 0x00, 0x02, 0x08, 0x00, 0x55, 0x00, 0x1F, 0x08, 0x00, 0x00, 0xBA, 0xBE},
       2,
       {0x1F, 0x08, 0x00, 0x00}},
      // Write's acknowledgement; Bulk Read's voltage 119 and temperature 36.
      {{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x00, 0xA1, 0x0C}, 1, {}},
      {{0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x06, 0x00, 0x55, 0x00, 0x77, 0x00, 0xC3, 0x69},
       1,
       {0x77, 0x00}},
      {{0xFF, 0xFF, 0xFD, 0x00, 0x02, 0x05, 0x00, 0x55, 0x00, 0x24, 0x8B, 0xA9}, 2, {0x24}},
  };
  for (const ManualStatus& c : cases) {
    Status st;
    std::array<std::uint8_t, 16> params{};
    ASSERT_EQ(parse_status(c.wire, st, params), ParseResult::kOk);
    EXPECT_EQ(st.id, c.id);
    EXPECT_EQ(st.error, 0);
    EXPECT_EQ(st.consumed, c.wire.size());
    EXPECT_EQ(Bytes(params.begin(), params.begin() + static_cast<std::ptrdiff_t>(st.param_count)),
              c.params);
  }
}

// The e-Manual's receiver: bytes before the header are skipped; a packet
// cut short asks for more; a damaged one is refused and dropped whole.
TEST(Dynamixel2Packet, NoiseTruncationAndDamage) {
  const Bytes good = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55,
                      0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0};
  std::array<std::uint8_t, 16> params{};
  Status st;
  Bytes noisy = {0x00, 0xFF, 0x12, 0xFF, 0xFF};
  noisy.insert(noisy.end(), good.begin(), good.end());
  ASSERT_EQ(parse_status(noisy, st, params), ParseResult::kOk);
  EXPECT_EQ(st.consumed, noisy.size());
  EXPECT_EQ(params[0], 0xA6);

  for (std::size_t cut = 0; cut < good.size(); ++cut) {
    EXPECT_EQ(parse_status(std::span(good).first(cut), st, params), ParseResult::kIncomplete)
        << cut;
  }
  Bytes bad = good;
  bad[9] ^= 0x01;  // a bit flipped in the position
  EXPECT_EQ(parse_status(bad, st, params), ParseResult::kBadCrc);
  // Only its first byte is dropped: a damaged length field must not swallow
  // good packets after it. The rest holds no packet.
  EXPECT_EQ(st.consumed, 1u);
  EXPECT_EQ(parse_status(std::span(bad).subspan(1), st, params), ParseResult::kIncomplete);
  // Our own instruction echoed back (half-duplex adapters do): not a status.
  std::array<std::uint8_t, 256> out{};
  const std::size_t n = encode_read(1, 132, 4, out);
  EXPECT_EQ(parse_status(std::span(out).first(n), st, params), ParseResult::kNotStatus);
  EXPECT_EQ(st.consumed, n);
  // An error byte: alert (hardware error) and a data range error.
  Bytes err = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x84};
  const std::uint16_t crc = crc16(err);
  err.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  err.push_back(static_cast<std::uint8_t>(crc >> 8));
  ASSERT_EQ(parse_status(err, st, params), ParseResult::kOk);
  EXPECT_EQ(st.error & kErrorAlert, kErrorAlert);
  EXPECT_STREQ(result_error_name(st.error), "data range error");
  // More parameters than the caller's buffer: refused, not overrun.
  std::array<std::uint8_t, 2> small{};
  EXPECT_EQ(parse_status(good, st, small), ParseResult::kBadLength);
}

// FF FF FD inside the parameters is stuffed to FF FF FD FD, counted in the
// length and the CRC, and unstuffed on reading.
TEST(Dynamixel2Packet, ByteStuffingRoundTrips) {
  std::array<std::uint8_t, 256> out{};
  const Bytes data = {0xFF, 0xFF, 0xFD, 0x01, 0xFF, 0xFF, 0xFF, 0xFD};
  const std::size_t n = encode_write(1, 116, data, out);
  const Bytes expect_params = {0x74, 0x00, 0xFF, 0xFF, 0xFD, 0xFD,
                               0x01, 0xFF, 0xFF, 0xFF, 0xFD, 0xFD};
  ASSERT_EQ(n, 8 + expect_params.size() + 2);
  EXPECT_EQ(
      Bytes(out.begin() + 8, out.begin() + 8 + static_cast<std::ptrdiff_t>(expect_params.size())),
      expect_params);
  EXPECT_EQ(out[5] | (out[6] << 8), static_cast<int>(expect_params.size() + 3));
  // The same bytes as a status packet's parameters come back unstuffed.
  Bytes status = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0, 0, 0x55, 0x00};
  status.insert(status.end(), {0xFF, 0xFF, 0xFD, 0xFD, 0x01, 0xFF, 0xFF, 0xFF, 0xFD, 0xFD});
  status[5] = static_cast<std::uint8_t>(status.size() - 7 + 2);
  const std::uint16_t crc = crc16(status);
  status.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  status.push_back(static_cast<std::uint8_t>(crc >> 8));
  std::array<std::uint8_t, 16> params{};
  Status st;
  ASSERT_EQ(parse_status(status, st, params), ParseResult::kOk);
  EXPECT_EQ(Bytes(params.begin(), params.begin() + static_cast<std::ptrdiff_t>(st.param_count)),
            data);
}

TEST(Dynamixel2Packet, ABufferTooSmallGivesNoPacket) {
  std::array<std::uint8_t, 13> out{};
  EXPECT_EQ(encode_read(1, 132, 4, out), 0U) << "14 bytes needed";
  std::array<std::uint8_t, 14> fits{};
  EXPECT_EQ(encode_read(1, 132, 4, fits), 14U);
  const Bytes ids = {1, 2};
  const Bytes short_data = {0x96, 0x00, 0x00};
  std::array<std::uint8_t, 256> big{};
  EXPECT_EQ(encode_sync_write(116, 4, ids, short_data, big), 0U);
}

}  // namespace
}  // namespace facectl::dxl2
