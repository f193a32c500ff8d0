#pragma once

#include <cstddef>
#include <cstdint>
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

// A sender address:port and what the stream keeps of it: its own numbering
// (a header from one sender restarts only its own) and the FAPs in force.
struct FapUdpPeer {
  std::uint32_t address = 0;  // host byte order
  std::uint16_t port = 0;
  std::int64_t last_seen_ns = 0;
  FapReader reader{""};
  FapState state;
  FapUdpPeerStats stats;
};

// At most `capacity` senders. A new one takes the slot of the sender heard
// least recently if that one has been silent for `idle_ns`; otherwise it
// gets none (the caller counts and drops its datagram), so a flood of new
// ports cannot push out a sender that is still talking.
class FapUdpPeerTable {
 public:
  FapUdpPeerTable(std::size_t capacity, std::int64_t idle_ns);

  // The sender's entry (new ones with a reader that allows new headers), or
  // nullptr when the table is full of senders heard within idle_ns.
  FapUdpPeer* find_or_add(std::uint32_t address, std::uint16_t port, std::int64_t now_ns);
  std::size_t size() const { return peers_.size(); }
  std::vector<FapUdpPeerStats> stats() const;

 private:
  std::size_t capacity_;
  std::int64_t idle_ns_;
  std::vector<FapUdpPeer> peers_;  // never above capacity_: entries stay put
};

}  // namespace facectl
