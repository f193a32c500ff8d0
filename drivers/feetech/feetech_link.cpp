#include "drivers/feetech/feetech_link.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace facectl {
namespace {

std::int64_t seconds_ns(double s) {
  return static_cast<std::int64_t>(std::llround(s * 1e9));
}

}  // namespace

FeetechLink::FeetechLink(const std::string& device, long baud)
    : port_(device, baud), rx_(4096), params_(scs::kMaxParams), sent_(scs::kOverhead + 256) {}

bool FeetechLink::send(std::span<const std::uint8_t> packet, std::int64_t timeout_ns) {
  rx_len_ = 0;
  port_.discard_input();  // a late reply must not answer this request
  sent_len_ = std::min(packet.size(), sent_.size());
  std::copy_n(packet.begin(), sent_len_, sent_.begin());
  echo_pending_ = true;
  return port_.write_all(packet, timeout_ns + seconds_ns(wire_s(packet.size())));
}

FeetechLink::Reply FeetechLink::request(std::uint8_t id, std::span<const std::uint8_t> packet,
                                        std::span<std::uint8_t> data, double response_s,
                                        double return_delay_s, std::uint8_t* error) {
  if (!send(packet, seconds_ns(response_s))) return Reply::kLost;
  const std::size_t reply_bytes = scs::kOverhead + data.size();
  const double wait_s = wire_s(packet.size() + reply_bytes) + return_delay_s + response_s;
  Reply reply = Reply::kNoReply;
  const int got =
      receive(1, monotonic_ns() + seconds_ns(wait_s),
              [&](std::uint8_t from, std::uint8_t err, std::span<const std::uint8_t> p) {
                if (error != nullptr) *error = err;
                if (from != id || p.size() != data.size()) {
                  ++counters_.bad_packets;
                  reply = Reply::kBad;
                  return;
                }
                std::copy(p.begin(), p.end(), data.begin());
                reply = Reply::kOk;
              });
  if (got == 0) {
    // A reply may still be on its way: let it arrive and drop it, so that it
    // is not taken for the answer to the next request.
    const double guard_s = wire_s(reply_bytes) + return_delay_s + 0.001;
    const timespec t{0, static_cast<long>(guard_s * 1e9)};
    nanosleep(&t, nullptr);
    rx_len_ = 0;
    port_.discard_input();
  }
  return got < 0 ? Reply::kLost : reply;
}

}  // namespace facectl
