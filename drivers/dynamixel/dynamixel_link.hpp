#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "control/clock.hpp"
#include "drivers/protocol/dynamixel2_packet.hpp"
#include "drivers/serial/serial_port.hpp"

namespace facectl {

// Request and status packets over one serial port (DYNAMIXEL Protocol 2.0):
// what the bus's I/O thread and `facectl bus doctor` share. Not thread-safe.
class DynamixelLink {
 public:
  struct Counters {
    std::uint64_t status_packets = 0;
    std::uint64_t timeouts = 0;  // status packets that did not come
    std::uint64_t bad_crc = 0;
    std::uint64_t bad_packets = 0;  // wrong length, id or parameter count; an error status
  };
  enum class Reply { kOk, kNoReply, kBad, kLost };

  // Throws std::runtime_error naming the device (SerialPort).
  DynamixelLink(const std::string& device, long baud);

  // Drops what is pending and sends `packet`. False: the port is lost.
  bool send(std::span<const std::uint8_t> packet, std::int64_t timeout_ns);
  // Reads status packets until `want` arrived or the deadline passed, calling
  // on_status(id, error, params) for each good one; skips our own echoed
  // request (half-duplex adapters). Returns how many came, -1: port lost.
  template <typename OnStatus>
  int receive(int want, std::int64_t deadline_ns, OnStatus&& on_status);
  // One instruction to servo `id` and its status packet, whose parameters
  // must fill `data` exactly. `response_s`: the wait beyond the wire time.
  Reply request(std::uint8_t id, std::span<const std::uint8_t> packet, std::span<std::uint8_t> data,
                double response_s, double return_delay_s, std::uint8_t* error = nullptr);

  // Seconds `bytes` take on the wire.
  double wire_s(std::size_t bytes) const {
    return serial_byte_s(port_.baud()) * static_cast<double>(bytes);
  }
  const Counters& counters() const { return counters_; }

 private:
  SerialPort port_;
  std::vector<std::uint8_t> rx_, params_;
  std::size_t rx_len_ = 0;
  Counters counters_;
};

template <typename OnStatus>
int DynamixelLink::receive(int want, std::int64_t deadline_ns, OnStatus&& on_status) {
  int got = 0;
  while (got < want) {
    dxl2::Status st;
    const dxl2::ParseResult r = dxl2::parse_status({rx_.data(), rx_len_}, st, params_);
    if (st.consumed > 0) {
      std::memmove(rx_.data(), rx_.data() + st.consumed, rx_len_ - st.consumed);
      rx_len_ -= st.consumed;
    }
    if (r == dxl2::ParseResult::kOk) {
      ++got;
      ++counters_.status_packets;
      on_status(st.id, st.error, std::span<const std::uint8_t>(params_.data(), st.param_count));
      continue;
    }
    if (r == dxl2::ParseResult::kBadCrc) ++counters_.bad_crc;
    if (r == dxl2::ParseResult::kBadLength) ++counters_.bad_packets;
    // kNotStatus: our own request, echoed.
    if (r != dxl2::ParseResult::kIncomplete) continue;
    if (rx_len_ == rx_.size()) rx_len_ = 0;  // longer than any reply: noise
    const std::int64_t left = deadline_ns - monotonic_ns();
    if (left <= 0) break;
    const long n = port_.read_some({rx_.data() + rx_len_, rx_.size() - rx_len_}, left);
    if (n < 0) return -1;
    rx_len_ += static_cast<std::size_t>(n);
  }
  counters_.timeouts += static_cast<std::uint64_t>(want - got);
  return got;
}

}  // namespace facectl
