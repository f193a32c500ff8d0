#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"

namespace facectl {

// One sender's counters (FapUdpStream::peer_stats()).
struct FapUdpPeerStats {
  std::string peer;             // "address:port"
  std::uint64_t datagrams = 0;  // received from it
  std::uint64_t frames = 0;     // played
  std::uint64_t held_back = 0;  // good frames not played: another sender was playing
  std::uint64_t malformed = 0;
  std::uint64_t out_of_bounds = 0;
  std::string last_error;
};

// A sender: address and port, host byte order.
struct FapUdpSender {
  std::uint32_t address = 0;
  std::uint16_t port = 0;
  bool operator==(const FapUdpSender&) const = default;
};

// A sender and what the stream keeps of it: its own numbering (a header
// from one sender restarts only its own) and the FAPs in force.
struct FapUdpPeer {
  FapUdpSender sender;
  std::int64_t last_seen_ns = 0;  // its last datagram
  std::int64_t accepted_ns = 0;   // its last datagram with frames taken
  FapReader reader{""};
  FapState state;
  FapUdpPeerStats stats;
};

// At most `capacity` senders, at least 2. When full, a new one takes the
// slot of the sender heard least recently, never that of the one playing:
// a flood from new ports can churn the other slots but cannot push out the
// sender that plays, and a real sender that restarts on a new port always
// gets a slot (nobody is refused for want of room).
class FapUdpPeerTable {
 public:
  explicit FapUdpPeerTable(std::size_t capacity);

  // The sender's entry, new ones with a reader that allows new headers;
  // marks it heard at now_ns. `playing` is never evicted.
  FapUdpPeer& find_or_add(const FapUdpSender& sender, std::int64_t now_ns,
                          const std::optional<FapUdpSender>& playing);
  std::size_t size() const { return peers_.size(); }
  std::uint64_t evicted() const { return evicted_; }
  std::vector<FapUdpPeerStats> stats() const;

 private:
  std::size_t capacity_;
  std::uint64_t evicted_ = 0;
  std::vector<FapUdpPeer> peers_;  // never above capacity_: entries stay put
};

}  // namespace facectl
