#include "drivers/protocol/dynamixel2_packet.hpp"

#include <algorithm>

namespace facectl::dxl2 {
namespace {

constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> t{};
  for (unsigned i = 0; i < 256; ++i) {
    auto c = static_cast<std::uint16_t>(i << 8);
    for (int b = 0; b < 8; ++b) {
      c = static_cast<std::uint16_t>((c & 0x8000U) != 0 ? (c << 1) ^ 0x8005U : c << 1);
    }
    t[i] = c;
  }
  return t;
}
constexpr std::array<std::uint16_t, 256> kCrcTable = make_crc_table();

constexpr std::size_t kHeaderSize = 7;    // FF FF FD 00, ID, LEN_L, LEN_H
constexpr std::size_t kMaxLength = 4096;  // no instruction facectl sends or reads comes near

bool valid_id(std::uint8_t id) {
  return id <= kMaxId || id == kBroadcastId;
}

void store16(std::span<std::uint8_t> out, std::size_t at, std::uint16_t v) {
  out[at] = static_cast<std::uint8_t>(v & 0xFF);
  out[at + 1] = static_cast<std::uint8_t>(v >> 8);
}

std::uint16_t get16(std::span<const std::uint8_t> in, std::size_t at) {
  return static_cast<std::uint16_t>(in[at] | (in[at + 1] << 8));
}

// Builds one instruction packet in place: the header, then parameters
// stuffed as they come (a 0xFD added after each FF FF FD, also across
// pieces), then the length and the CRC.
class PacketWriter {
 public:
  PacketWriter(std::uint8_t id, std::uint8_t instruction, std::span<std::uint8_t> out)
      : out_(out), ok_(out.size() >= kHeaderSize + 3) {
    if (!ok_) return;
    const std::array<std::uint8_t, kHeaderSize> header = {0xFF, 0xFF, 0xFD, 0x00, id, 0, 0};
    std::copy(header.begin(), header.end(), out.begin());
    out_[kHeaderSize] = instruction;  // no instruction is 0xFF or 0xFD: no pattern starts here
    at_ = kHeaderSize + 1;
  }

  void put(std::uint8_t b) {
    if (!room()) return;
    out_[at_++] = b;
    if (b == 0xFD && ff_ >= 2) {
      if (!room()) return;
      out_[at_++] = 0xFD;
      ff_ = 0;
    } else {
      ff_ = b == 0xFF ? ff_ + 1 : 0;
    }
  }
  void put(std::span<const std::uint8_t> bytes) {
    for (std::uint8_t b : bytes) put(b);
  }
  void put16(std::uint16_t v) {
    put(static_cast<std::uint8_t>(v & 0xFF));
    put(static_cast<std::uint8_t>(v >> 8));
  }

  // The packet's size; 0 if it did not fit.
  std::size_t finish() {
    const std::size_t length = at_ - kHeaderSize + 2;  // instruction, parameters, CRC
    if (!ok_ || length > 0xFFFF) return 0;
    store16(out_, 5, static_cast<std::uint16_t>(length));
    store16(out_, at_, crc16(out_.first(at_)));
    return at_ + 2;
  }

 private:
  bool room() {  // a byte more, and the CRC after it
    ok_ = ok_ && at_ + 3 <= out_.size();
    return ok_;
  }

  std::span<std::uint8_t> out_;
  bool ok_;
  std::size_t at_ = 0;
  int ff_ = 0;  // 0xFF bytes just written
};

}  // namespace

const char* result_error_name(std::uint8_t error) {
  switch (static_cast<ResultError>(error & 0x7F)) {
    case ResultError::kNone:
      return "none";
    case ResultError::kResultFail:
      return "result fail";
    case ResultError::kInstruction:
      return "instruction error";
    case ResultError::kCrc:
      return "CRC error";
    case ResultError::kDataRange:
      return "data range error";
    case ResultError::kDataLength:
      return "data length error";
    case ResultError::kDataLimit:
      return "data limit error";
    case ResultError::kAccess:
      return "access error";
  }
  return "unknown error";
}

const char* parse_result_name(ParseResult r) {
  switch (r) {
    case ParseResult::kOk:
      return "ok";
    case ParseResult::kIncomplete:
      return "incomplete";
    case ParseResult::kBadCrc:
      return "bad CRC";
    case ParseResult::kBadLength:
      return "bad length";
    case ParseResult::kNotStatus:
      return "not a status packet";
  }
  return "?";
}

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (std::uint8_t b : bytes) {
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xFF]);
  }
  return crc;
}

std::size_t encode_instruction(std::uint8_t id, std::uint8_t instruction,
                               std::span<const std::uint8_t> params, std::span<std::uint8_t> out) {
  PacketWriter w(id, instruction, out);
  w.put(params);
  return w.finish();
}

std::size_t encode_read(std::uint8_t id, std::uint16_t address, std::uint16_t length,
                        std::span<std::uint8_t> out) {
  PacketWriter w(id, kRead, out);
  w.put16(address);
  w.put16(length);
  return w.finish();
}

std::size_t encode_write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                         std::span<std::uint8_t> out) {
  PacketWriter w(id, kWrite, out);
  w.put16(address);
  w.put(data);
  return w.finish();
}

std::size_t encode_sync_read(std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids, std::span<std::uint8_t> out) {
  PacketWriter w(kBroadcastId, kSyncRead, out);
  w.put16(address);
  w.put16(length);
  w.put(ids);
  return w.finish();
}

std::size_t encode_sync_write(std::uint16_t address, std::uint16_t length,
                              std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                              std::span<std::uint8_t> out) {
  if (data.size() != ids.size() * length) return 0;
  PacketWriter w(kBroadcastId, kSyncWrite, out);
  w.put16(address);
  w.put16(length);
  for (std::size_t i = 0; i < ids.size(); ++i) {
    w.put(ids[i]);
    w.put(data.subspan(i * length, length));
  }
  return w.finish();
}

namespace {

// parse_packet's work, the first `lead.size()` unstuffed bytes (a status
// packet's error byte) going to `lead` and the rest to `params`.
ParseResult parse_into(std::span<const std::uint8_t> in, Packet& packet,
                       std::span<std::uint8_t> lead, std::span<std::uint8_t> params) {
  packet = Packet{};
  for (std::size_t h = 0; h + 4 <= in.size(); ++h) {
    if (in[h] != 0xFF || in[h + 1] != 0xFF || in[h + 2] != 0xFD || in[h + 3] != 0x00) continue;
    if (h + kHeaderSize > in.size()) {
      packet.consumed = h;
      return ParseResult::kIncomplete;
    }
    const std::uint16_t length = get16(in, h + 5);
    if (!valid_id(in[h + 4]) || length < 3 || length > kMaxLength) {
      packet.consumed = h + 1;  // not a packet after all: look again from the next byte
      return ParseResult::kBadLength;
    }
    const std::size_t end = h + kHeaderSize + length;
    if (end > in.size()) {
      packet.consumed = h;
      return ParseResult::kIncomplete;
    }
    packet.consumed = end;
    packet.id = in[h + 4];
    if (crc16(in.subspan(h, end - 2 - h)) != get16(in, end - 2)) {
      packet.consumed = h + 1;  // a damaged length may hide good packets after it: resync
      return ParseResult::kBadCrc;
    }
    packet.instruction = in[h + kHeaderSize];
    // Unstuff: drop the 0xFD that follows each FF FF FD.
    std::size_t n = 0;
    int ff = 0;
    bool skip = false;
    for (std::size_t i = h + kHeaderSize + 1; i < end - 2; ++i) {
      const std::uint8_t b = in[i];
      if (skip) {
        skip = false;
        if (b == 0xFD) continue;
      }
      if (n < lead.size()) {
        lead[n] = b;
      } else if (n - lead.size() < params.size()) {
        params[n - lead.size()] = b;
      } else {
        return ParseResult::kBadLength;
      }
      ++n;
      if (b == 0xFD && ff >= 2) {
        skip = true;
        ff = 0;
      } else {
        ff = b == 0xFF ? ff + 1 : 0;
      }
    }
    if (n < lead.size()) return ParseResult::kBadLength;
    packet.param_count = n - lead.size();
    return ParseResult::kOk;
  }
  packet.consumed = in.size() > 3 ? in.size() - 3 : 0;  // a header may start in the last 3 bytes
  return ParseResult::kIncomplete;
}

}  // namespace

ParseResult parse_packet(std::span<const std::uint8_t> in, Packet& packet,
                         std::span<std::uint8_t> params) {
  return parse_into(in, packet, {}, params);
}

ParseResult parse_status(std::span<const std::uint8_t> in, Status& status,
                         std::span<std::uint8_t> params) {
  status = Status{};
  Packet p;
  std::uint8_t error = 0;
  ParseResult r = parse_into(in, p, {&error, 1}, params);
  if (r == ParseResult::kOk && p.instruction != kStatus) r = ParseResult::kNotStatus;
  // A short packet that is not a status packet is not ours to judge either.
  if (r == ParseResult::kBadLength && p.consumed > 0 && p.instruction != 0 &&
      p.instruction != kStatus) {
    r = ParseResult::kNotStatus;
  }
  status.id = p.id;
  status.consumed = p.consumed;
  if (r == ParseResult::kOk) {
    status.error = error;
    status.param_count = p.param_count;
  }
  return r;
}

std::size_t encode_status(std::uint8_t id, std::uint8_t error, std::span<const std::uint8_t> params,
                          std::span<std::uint8_t> out) {
  PacketWriter w(id, kStatus, out);
  w.put(error);
  w.put(params);
  return w.finish();
}

}  // namespace facectl::dxl2
