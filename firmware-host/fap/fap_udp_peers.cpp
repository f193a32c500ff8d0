#include "firmware-host/fap/fap_udp_peers.hpp"

#include "firmware-host/config/ipv4_cidr.hpp"

namespace facectl {

FapUdpPeerTable::FapUdpPeerTable(std::size_t capacity, std::int64_t idle_ns)
    : capacity_(capacity), idle_ns_(idle_ns) {
  peers_.reserve(capacity_);
}

FapUdpPeer* FapUdpPeerTable::find_or_add(std::uint32_t address, std::uint16_t port,
                                         std::int64_t now_ns) {
  FapUdpPeer* oldest = nullptr;
  for (FapUdpPeer& p : peers_) {
    if (p.address == address && p.port == port) return &p;
    if (oldest == nullptr || p.last_seen_ns < oldest->last_seen_ns) oldest = &p;
  }
  FapUdpPeer fresh;
  fresh.address = address;
  fresh.port = port;
  fresh.last_seen_ns = now_ns;
  fresh.stats.peer = ipv4_text(address) + ":" + std::to_string(port);
  fresh.reader.allow_new_header(true);
  if (peers_.size() < capacity_) return &peers_.emplace_back(std::move(fresh));
  if (oldest != nullptr && now_ns - oldest->last_seen_ns > idle_ns_) {
    *oldest = std::move(fresh);
    return oldest;
  }
  return nullptr;
}

std::vector<FapUdpPeerStats> FapUdpPeerTable::stats() const {
  std::vector<FapUdpPeerStats> out;
  out.reserve(peers_.size());
  for (const FapUdpPeer& p : peers_) out.push_back(p.stats);
  return out;
}

}  // namespace facectl
