#include "drivers/protocol/feetech_packet.hpp"

#include <algorithm>

namespace facectl::scs {

std::uint8_t checksum(std::uint8_t id, std::uint8_t length, std::uint8_t instruction,
                      std::span<const std::uint8_t> params) {
  unsigned sum = id + length + instruction;
  for (const std::uint8_t b : params) sum += b;
  return static_cast<std::uint8_t>(~sum & 0xFF);
}

std::size_t encode_instruction(std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params, std::span<std::uint8_t> out) {
  if (params.size() > kMaxParams || out.size() < kOverhead + params.size()) return 0;
  const auto length = static_cast<std::uint8_t>(params.size() + 2);
  out[0] = 0xFF;
  out[1] = 0xFF;
  out[2] = id;
  out[3] = length;
  out[4] = instruction;
  std::copy(params.begin(), params.end(), out.begin() + 5);
  out[5 + params.size()] = checksum(id, length, instruction, params);
  return kOverhead + params.size();
}

std::size_t encode_read(std::uint8_t id, std::uint8_t address, std::uint8_t length,
                        std::span<std::uint8_t> out) {
  const std::uint8_t p[2] = {address, length};
  return encode_instruction(id, kRead, p, out);
}

std::size_t encode_write(std::uint8_t id, std::uint8_t address, std::span<const std::uint8_t> data,
                         std::span<std::uint8_t> out) {
  std::uint8_t p[kMaxParams];
  if (data.size() + 1 > kMaxParams) return 0;
  p[0] = address;
  std::copy(data.begin(), data.end(), p + 1);
  return encode_instruction(id, kWrite, {p, data.size() + 1}, out);
}

std::size_t encode_sync_write(std::uint8_t address, std::uint8_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                              std::span<std::uint8_t> out) {
  const std::size_t n = 2 + ids.size() * (1 + length);
  if (n > kMaxParams || data.size() != ids.size() * length) return 0;
  std::uint8_t p[kMaxParams];
  p[0] = address;
  p[1] = length;
  std::size_t k = 2;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    p[k++] = ids[i];
    std::copy_n(data.begin() + static_cast<long>(i * length), length, p + k);
    k += length;
  }
  return encode_instruction(kBroadcastId, kSyncWrite, {p, n}, out);
}

std::size_t encode_sync_read(std::uint8_t address, std::uint8_t length,
                             std::span<const std::uint8_t> ids, std::span<std::uint8_t> out) {
  if (2 + ids.size() > kMaxParams) return 0;
  std::uint8_t p[kMaxParams];
  p[0] = address;
  p[1] = length;
  std::copy(ids.begin(), ids.end(), p + 2);
  return encode_instruction(kBroadcastId, kSyncRead, {p, 2 + ids.size()}, out);
}

std::size_t encode_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params,
                          std::span<std::uint8_t> out) {
  return encode_instruction(id, error, params, out);
}

const char* parse_result_name(ParseResult r) {
  switch (r) {
    case ParseResult::kOk:
      return "ok";
    case ParseResult::kIncomplete:
      return "incomplete";
    case ParseResult::kBadChecksum:
      return "bad checksum";
    case ParseResult::kBadLength:
      return "bad length";
  }
  return "?";
}

ParseResult parse_packet(std::span<const std::uint8_t> in, Packet& packet,
                         std::span<std::uint8_t> params) {
  packet = Packet{};
  // Skip to the first FF FF that is not followed by a third FF (an ID of
  // 0xFF cannot be: the header is the last two FFs of a run).
  std::size_t start = 0;
  while (start + 1 < in.size() && !(in[start] == 0xFF && in[start + 1] == 0xFF)) ++start;
  if (start + 1 >= in.size()) {
    // No header: drop the noise, keeping a last FF that may begin one.
    packet.consumed = !in.empty() && in.back() == 0xFF ? in.size() - 1 : in.size();
    return ParseResult::kIncomplete;
  }
  while (start + 2 < in.size() && in[start + 2] == 0xFF) ++start;
  if (start + 4 > in.size()) {
    packet.consumed = start;
    return ParseResult::kIncomplete;
  }
  const std::uint8_t id = in[start + 2];
  const std::uint8_t length = in[start + 3];
  if (length < 2) {
    packet.consumed = start + 4;
    return ParseResult::kBadLength;
  }
  const std::size_t count = length - 2u;
  if (count > params.size()) {
    packet.consumed = start + 4;
    return ParseResult::kBadLength;
  }
  const std::size_t end = start + 4 + length;
  if (end > in.size()) {
    packet.consumed = start;
    return ParseResult::kIncomplete;
  }
  const std::uint8_t code = in[start + 4];
  const std::span<const std::uint8_t> p = in.subspan(start + 5, count);
  packet.consumed = end;
  if (checksum(id, length, code, p) != in[end - 1]) return ParseResult::kBadChecksum;
  std::copy(p.begin(), p.end(), params.begin());
  packet.id = id;
  packet.code = code;
  packet.param_count = count;
  return ParseResult::kOk;
}

}  // namespace facectl::scs
