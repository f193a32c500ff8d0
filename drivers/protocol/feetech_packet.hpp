#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

// Feetech SCS/STS packets (docs/PROTOCOLS.md, "Feetech"): FF FF, ID, length
// (= parameters + 2), the instruction (or, in a status packet, the error
// byte), the parameters, and checksum = ~(ID + length + instruction +
// parameters) & 0xFF. The layout and instruction codes are those of
// Feetech's SDK (FTServo / SCServo_Linux INST.h, SCS.cpp) and the SCS
// communication protocol manual. Pure encode/decode into caller-owned
// buffers, no allocation: shared by the driver and the simulated servo.
namespace facectl::scs {

inline constexpr std::uint8_t kBroadcastId = 0xFE;
inline constexpr std::uint8_t kMaxId = 0xFD;  // 0..253 (the manual), 254 broadcast

enum Instruction : std::uint8_t {
  kPing = 0x01,
  kRead = 0x02,
  kWrite = 0x03,
  kRegWrite = 0x04,
  kAction = 0x05,
  kSyncRead = 0x82,  // STS/SMS only; SCS servos do not answer it
  kSyncWrite = 0x83,
};

// A whole packet is 6 bytes plus its parameters; the length byte caps them.
inline constexpr std::size_t kOverhead = 6;
inline constexpr std::size_t kMaxParams = 253;

std::uint8_t checksum(std::uint8_t id, std::uint8_t length, std::uint8_t instruction,
                      std::span<const std::uint8_t> params);

// An instruction packet into `out`; returns its size, 0 if `out` is too
// small or the parameters do not fit the length byte.
std::size_t encode_instruction(std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params, std::span<std::uint8_t> out);
std::size_t encode_read(std::uint8_t id, std::uint8_t address, std::uint8_t length,
                        std::span<std::uint8_t> out);
std::size_t encode_write(std::uint8_t id, std::uint8_t address, std::span<const std::uint8_t> data,
                         std::span<std::uint8_t> out);
// Sync write to broadcast: `data` holds `length` bytes for each of `ids`.
std::size_t encode_sync_write(std::uint8_t address, std::uint8_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                              std::span<std::uint8_t> out);
// Sync read: each of `ids` answers, in order, with `length` bytes at `address`.
std::size_t encode_sync_read(std::uint8_t address, std::uint8_t length,
                             std::span<const std::uint8_t> ids, std::span<std::uint8_t> out);
// A status packet: what a servo sends (the simulated servo's encoder).
std::size_t encode_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params,
                          std::span<std::uint8_t> out);

// Any packet read from the wire. Requests and replies share the layout; in a
// reply `code` is the error byte.
struct Packet {
  std::uint8_t id = 0;
  std::uint8_t code = 0;
  std::size_t param_count = 0;
  std::size_t consumed = 0;  // bytes of the input up to the packet's end
};

enum class ParseResult {
  kOk,
  kIncomplete,  // no whole packet yet: read more
  kBadChecksum,
  kBadLength,  // a length byte below 2, or more parameters than `params` holds
};
const char* parse_result_name(ParseResult r);

// Finds the first packet in `in` (bytes before an FF FF header are skipped,
// as the SDK's receiver does) and copies its parameters into `params`.
// `packet.consumed` says how much of `in` to drop afterwards, for every
// result but kIncomplete with nothing to skip.
ParseResult parse_packet(std::span<const std::uint8_t> in, Packet& packet,
                         std::span<std::uint8_t> params);

}  // namespace facectl::scs
