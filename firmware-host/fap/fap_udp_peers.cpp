#include "firmware-host/fap/fap_udp_peers.hpp"

#include <stdexcept>

#include "firmware-host/config/ipv4_cidr.hpp"

namespace facectl {

FapUdpPeerTable::FapUdpPeerTable(std::size_t capacity) : capacity_(capacity) {
  // One slot for the sender playing and at least one for everyone else.
  if (capacity_ < 2) throw std::invalid_argument("FapUdpPeerTable: capacity below 2");
  peers_.reserve(capacity_);
}

FapUdpPeer& FapUdpPeerTable::find_or_add(const FapUdpSender& sender, std::int64_t now_ns,
                                         const std::optional<FapUdpSender>& playing) {
  FapUdpPeer* oldest = nullptr;
  for (FapUdpPeer& p : peers_) {
    if (p.sender == sender) {
      p.last_seen_ns = now_ns;
      return p;
    }
    if (p.sender != playing && (oldest == nullptr || p.last_seen_ns < oldest->last_seen_ns)) {
      oldest = &p;
    }
  }
  FapUdpPeer fresh;
  fresh.sender = sender;
  fresh.last_seen_ns = now_ns;
  fresh.stats.peer = ipv4_text(sender.address) + ":" + std::to_string(sender.port);
  fresh.reader.allow_new_header(true);
  if (peers_.size() < capacity_) return peers_.emplace_back(std::move(fresh));
  // Full, and at most one entry is the one playing: capacity >= 2 leaves one.
  ++evicted_;
  *oldest = std::move(fresh);
  return *oldest;
}

std::vector<FapUdpPeerStats> FapUdpPeerTable::stats() const {
  std::vector<FapUdpPeerStats> out;
  out.reserve(peers_.size());
  for (const FapUdpPeer& p : peers_) out.push_back(p.stats);
  return out;
}

}  // namespace facectl
