#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

// DYNAMIXEL Protocol 2.0 packets (ROBOTIS e-Manual, "Protocol 2.0";
// docs/PROTOCOLS.md, "Dynamixel"): header FF FF FD 00, ID, length, the
// instruction, its parameters byte-stuffed, CRC-16. Pure encode/decode into
// caller-owned buffers, no allocation: shared by the Dynamixel bus driver
// and its simulated servo, so both speak the published layout.
namespace facectl::dxl2 {

inline constexpr std::uint8_t kBroadcastId = 0xFE;
inline constexpr std::uint8_t kMaxId = 0xFC;  // 253 (0xFD) and 255 would read as header bytes

enum Instruction : std::uint8_t {
  kPing = 0x01,
  kRead = 0x02,
  kWrite = 0x03,
  kRegWrite = 0x04,
  kAction = 0x05,
  kFactoryReset = 0x06,
  kReboot = 0x08,
  kClear = 0x10,
  kStatus = 0x55,
  kSyncRead = 0x82,
  kSyncWrite = 0x83,
  kBulkRead = 0x92,
  kBulkWrite = 0x93,
};

// The status packet's error byte: bit 7 "alert" (the device has a hardware
// error: read its Hardware Error Status), bits 0..6 the instruction's result.
inline constexpr std::uint8_t kErrorAlert = 0x80;
enum class ResultError : std::uint8_t {
  kNone = 0x00,
  kResultFail = 0x01,
  kInstruction = 0x02,
  kCrc = 0x03,
  kDataRange = 0x04,
  kDataLength = 0x05,
  kDataLimit = 0x06,
  kAccess = 0x07,
};
const char* result_error_name(std::uint8_t error);  // of the low 7 bits

// CRC-16 of the e-Manual ("CRC Calculation"): polynomial 0x8005, initial
// value 0, not reflected. Continues from `crc`.
std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0);

// Worst case of byte stuffing: one 0xFD added per three parameter bytes.
constexpr std::size_t max_packet_size(std::size_t params) {
  return 10 + params + params / 3 + 1;
}

// An instruction packet for `id`, its parameters stuffed, into `out`.
// Returns its size; 0 if `out` is too small or the stuffed length would not
// fit the 16-bit length field.
std::size_t encode_instruction(std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params, std::span<std::uint8_t> out);

// The instructions facectl sends. Multi-byte values are little-endian.
std::size_t encode_read(std::uint8_t id, std::uint16_t address, std::uint16_t length,
                        std::span<std::uint8_t> out);
std::size_t encode_write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                         std::span<std::uint8_t> out);
// Sync read of `length` bytes at `address` from each of `ids`.
std::size_t encode_sync_read(std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids, std::span<std::uint8_t> out);
// Sync write: `data` holds `length` bytes for each of `ids`, in order.
std::size_t encode_sync_write(std::uint16_t address, std::uint16_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                              std::span<std::uint8_t> out);

// Any packet read from the wire (the simulated servo reads instructions).
struct Packet {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::size_t param_count = 0;
  std::size_t consumed = 0;  // bytes of the input up to the packet's end
};

// A status packet read from the wire.
struct Status {
  std::uint8_t id = 0;
  std::uint8_t error = 0;  // kErrorAlert | ResultError
  std::size_t param_count = 0;
  std::size_t consumed = 0;  // bytes of the input up to the packet's end
};

enum class ParseResult {
  kOk,
  kIncomplete,  // no whole packet yet: read more
  kBadCrc,      // the CRC does not match: the packet is discarded
  kBadLength,   // a length below the minimum or over the limit
  kNotStatus,   // a whole packet whose instruction is not 0x55 (an echo of our own?)
};
const char* parse_result_name(ParseResult r);

// Finds the first packet in `in` (bytes before its header are skipped, as
// the e-Manual's receiver does) and, for a status packet with a good CRC,
// unstuffs its parameters into `params` (at most its size; more is
// kBadLength). `status.consumed` says how much of `in` to drop afterwards,
// also for kBadCrc and kNotStatus.
ParseResult parse_status(std::span<const std::uint8_t> in, Status& status,
                         std::span<std::uint8_t> params);
// The same for any packet: its instruction, and everything after it up to
// the CRC unstuffed into `params` (kNotStatus is never returned).
ParseResult parse_packet(std::span<const std::uint8_t> in, Packet& packet,
                         std::span<std::uint8_t> params);

// A status packet (instruction 0x55): the error byte, then the parameters.
// What a servo sends; the simulated servo's encoder. Returns its size, 0 if
// `out` is too small.
std::size_t encode_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params,
                          std::span<std::uint8_t> out);

}  // namespace facectl::dxl2
