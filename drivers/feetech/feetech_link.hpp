#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "control/clock.hpp"
#include "drivers/protocol/feetech_packet.hpp"
#include "drivers/serial/serial_port.hpp"

namespace facectl {

// Request and status packets over one serial port (Feetech SCS/STS): what
// the bus's I/O thread and `facectl bus doctor` share. Not thread-safe.
class FeetechLink {
 public:
  struct Counters {
    std::uint64_t status_packets = 0;
    std::uint64_t timeouts = 0;  // status packets that did not come
    std::uint64_t bad_checksum = 0;
    std::uint64_t bad_packets = 0;  // wrong length, id or parameter count
  };
  enum class Reply { kOk, kNoReply, kBad, kLost };

  // Throws std::runtime_error naming the device (SerialPort).
  FeetechLink(const std::string& device, long baud);

  // Drops what is pending and sends `packet`. False: the port is lost.
  bool send(std::span<const std::uint8_t> packet, std::int64_t timeout_ns);
  // Reads status packets until `want` arrived or the deadline passed, calling
  // on_status(id, error, params) for each good one; skips our own request
  // echoed (half-duplex adapters). Returns how many came, -1: port lost.
  template <typename OnStatus>
  int receive(int want, std::int64_t deadline_ns, OnStatus&& on_status);
  // One instruction to servo `id` and its status packet, whose parameters
  // must fill `data` exactly. `error` gets the status's error byte, which
  // does not make the reply bad: the servo did what it was asked.
  Reply request(std::uint8_t id, std::span<const std::uint8_t> packet, std::span<std::uint8_t> data,
                double response_s, double return_delay_s, std::uint8_t* error = nullptr);

  double wire_s(std::size_t bytes) const {
    return serial_byte_s(port_.baud()) * static_cast<double>(bytes);
  }
  const Counters& counters() const { return counters_; }

 private:
  SerialPort port_;
  std::vector<std::uint8_t> rx_, params_, sent_;
  std::size_t rx_len_ = 0;
  std::size_t sent_len_ = 0;
  bool echo_pending_ = false;
  Counters counters_;
};

template <typename OnStatus>
int FeetechLink::receive(int want, std::int64_t deadline_ns, OnStatus&& on_status) {
  int got = 0;
  while (got < want) {
    scs::Packet pk;
    const scs::ParseResult r = scs::parse_packet({rx_.data(), rx_len_}, pk, params_);
    const bool echo =
        r == scs::ParseResult::kOk && echo_pending_ && pk.consumed >= sent_len_ &&
        std::memcmp(rx_.data() + pk.consumed - sent_len_, sent_.data(), sent_len_) == 0;
    if (pk.consumed > 0) {
      std::memmove(rx_.data(), rx_.data() + pk.consumed, rx_len_ - pk.consumed);
      rx_len_ -= pk.consumed;
    }
    if (echo) {
      echo_pending_ = false;
      continue;
    }
    // No servo answers from the broadcast ID: an echo of an earlier
    // broadcast (a sync write) that came late.
    if (r == scs::ParseResult::kOk && pk.id == scs::kBroadcastId) continue;
    if (r == scs::ParseResult::kOk) {
      ++got;
      ++counters_.status_packets;
      on_status(pk.id, pk.code, std::span<const std::uint8_t>(params_.data(), pk.param_count));
      continue;
    }
    if (r == scs::ParseResult::kBadChecksum) ++counters_.bad_checksum;
    if (r == scs::ParseResult::kBadLength) ++counters_.bad_packets;
    if (r != scs::ParseResult::kIncomplete) continue;
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
