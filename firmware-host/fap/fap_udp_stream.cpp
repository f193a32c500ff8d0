#include "firmware-host/fap/fap_udp_stream.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>

#include "control/clock.hpp"
#include "firmware-host/fap/fap_udp_bounds.hpp"
#include "firmware-host/fap/udp_receive.hpp"

namespace facectl {
namespace {

constexpr std::size_t kMaxDatagram = 65536;
constexpr std::size_t kMaxKeptClamps = 1024;

std::int64_t to_ns(double s) {
  return static_cast<std::int64_t>(s * 1e9);
}

// The frames of one datagram, read on `reader` with every field bounded.
// Line numbers count within the datagram (the reader's source names it).
// Throws FapFormatError, or FapBoundError for a field past `limits`.
std::vector<FapFrame> read_datagram(FapReader& reader, std::string_view datagram,
                                    const FapUdpLimits& limits) {
  std::vector<FapFrame> frames;
  int line = 0;
  std::size_t pos = 0;
  while (pos < datagram.size()) {
    const std::size_t end = std::min(datagram.find('\n', pos), datagram.size());
    ++line;
    const std::optional<long> previous = reader.last_frame_number();
    const auto f = reader.feed(datagram.substr(pos, end - pos), line);
    check_header_bounds(reader, limits, line);
    if (f) {
      check_frame_bounds(reader, *f, previous, limits);
      frames.push_back(*f);
      check_frame_count(reader, frames.size(), limits, line);
    }
    pos = end + 1;
  }
  if (reader.mid_frame()) {
    reader.fail(line + 1, 0,
                "the values line of the frame whose mask is at line " +
                    std::to_string(reader.mask_line()) + ", in the same datagram",
                "the end of the datagram");
  }
  if (!reader.has_header()) {
    reader.fail(1, 0, "a header 'version name frame_rate frame_count' before any frame",
                "a datagram without one");
  }
  return frames;
}

}  // namespace

FapUdpStream::FapUdpStream(const FapMapping& mapping, const FapUdpOptions& options,
                           LatestValueMailbox<FaceCommand>* mailbox)
    : mapping_(mapping),
      options_(options),
      mailbox_(mailbox),
      buffer_(kMaxDatagram),
      peers_(options.max_peers, to_ns(options.peer_idle_s)) {
  const std::string where =
      "FAP stream " + options.bind_address + ":" + std::to_string(options.port);
  const auto address = parse_ipv4_address(options.bind_address);
  if (!address) {
    throw ConfigError(where + ": expected an IPv4 address to bind to, found '" +
                      options.bind_address + "'");
  }
  if (!kIpv4Loopback.contains(*address) && !options.allow_remote) {
    throw ConfigError(where +
                      ": expected a loopback address (127.0.0.0/8), found one beyond loopback: "
                      "binding it needs allow_remote (fap_stream.allow_remote: true)");
  }
  if (options.allow.empty() || options.max_peers == 0) {
    throw ConfigError(where + ": expected at least one allowed sender and one peer slot");
  }
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(options.port);
  addr.sin_addr.s_addr = htonl(*address);
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw ConfigError(where + ": socket: " + std::strerror(errno));
  if (!enable_kernel_drop_count(fd_) ||
      ::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string err = std::strerror(errno);
    ::close(fd_);
    throw ConfigError(where + ": cannot bind: " + err);
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  bound_ = options.bind_address + ":" + std::to_string(port_);
}

FapUdpStream::~FapUdpStream() {
  stop();
  if (fd_ >= 0) ::close(fd_);
}

std::size_t FapUdpStream::poll() {
  std::size_t played_before = 0;
  {
    std::lock_guard lock(mutex_);
    played_before = stats_.frames;
  }
  while (const auto d = receive_datagram(fd_, buffer_)) {
    std::lock_guard lock(mutex_);
    if (d->kernel_drops) count_kernel_drops(*d->kernel_drops);
    handle(std::string_view(buffer_.data(), d->size), d->address, d->port);
  }
  std::lock_guard lock(mutex_);
  return stats_.frames - played_before;
}

std::size_t FapUdpStream::wait_and_poll(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  ::poll(&p, 1, timeout_ms);
  return poll();
}

void FapUdpStream::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] {
    while (running_.load(std::memory_order_relaxed)) wait_and_poll(20);
  });
}

void FapUdpStream::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

void FapUdpStream::count_kernel_drops(std::uint32_t running_count) {
  // A running count since the socket opened, 32 bits wide: add what it grew.
  stats_.kernel_drops += static_cast<std::uint32_t>(running_count - last_drop_count_);
  last_drop_count_ = running_count;
}

bool FapUdpStream::allowed(std::uint32_t address) const {
  return std::any_of(options_.allow.begin(), options_.allow.end(),
                     [&](const Ipv4Cidr& c) { return c.contains(address); });
}

void FapUdpStream::reject(FapUdpPeer* peer, const std::string& error, bool out_of_bounds) {
  ++(out_of_bounds ? stats_.out_of_bounds : stats_.malformed);
  stats_.last_error = error;
  if (peer == nullptr) return;
  ++(out_of_bounds ? peer->stats.out_of_bounds : peer->stats.malformed);
  peer->stats.last_error = error;
}

// Called with mutex_ held.
void FapUdpStream::handle(std::string_view datagram, std::uint32_t address, std::uint16_t port) {
  const std::uint64_t number = ++stats_.datagrams;
  const std::string source = "udp " + bound_ + " datagram " + std::to_string(number) + " from " +
                             ipv4_text(address) + ":" + std::to_string(port);
  if (!allowed(address)) {
    ++stats_.refused_senders;
    stats_.last_error = source + ": sender not on the allow list (fap_stream.allow)";
    return;
  }
  const std::int64_t now = monotonic_ns();
  FapUdpPeer* peer = peers_.find_or_add(address, port, now);
  stats_.peers = peers_.size();
  if (peer == nullptr) {
    ++stats_.peers_full;
    stats_.last_error = source + ": no room for another sender (" +
                        std::to_string(options_.max_peers) + " heard within the last " +
                        std::to_string(std::llround(options_.peer_idle_s * 1000)) + " ms)";
    return;
  }
  peer->last_seen_ns = now;
  ++peer->stats.datagrams;
  // Parsed on a copy of the sender's reader, committed only if the whole
  // datagram is good.
  FapReader trial = peer->reader;
  trial.set_source(source);
  std::vector<FapFrame> frames;
  try {
    frames = read_datagram(trial, datagram, options_.limits);
  } catch (const FapBoundError& e) {
    reject(peer, e.what(), true);
    return;
  } catch (const FapFormatError& e) {
    reject(peer, e.what(), false);
    return;
  }
  peer->reader = trial;
  if (frames.empty()) return;  // a header alone
  const auto who = std::make_pair(address, port);
  if (playing_ && *playing_ != who && now - played_ns_ <= to_ns(options_.takeover_s)) {
    // Kept in the sender's own state, so that it plays on from there once
    // it takes over.
    for (const FapFrame& f : frames) peer->state.apply(f);
    stats_.held_back += frames.size();
    peer->stats.held_back += frames.size();
    return;
  }
  playing_ = who;
  play(*peer, frames, now);
}

// Called with mutex_ held.
void FapUdpStream::play(FapUdpPeer& peer, const std::vector<FapFrame>& frames,
                        std::int64_t now_ns) {
  std::vector<FapClamp> clamps;
  std::array<double, kMaxFaceSignals> pose{};
  for (const FapFrame& f : frames) {
    peer.state.apply(f);
    mapping_.map(peer.state, f.number, pose, &clamps);
  }
  if (mailbox_ != nullptr) {
    FaceCommand cmd;
    cmd.values = pose;
    cmd.sequence = ++sequence_;
    cmd.stamp_ns = monotonic_ns();
    mailbox_->publish(cmd);
  }
  played_ns_ = now_ns;
  pose_ = pose;
  has_pose_ = true;
  stats_.frames += frames.size();
  peer.stats.frames += frames.size();
  stats_.clamps += clamps.size();
  for (const FapClamp& c : clamps) {
    if (clamps_.size() < kMaxKeptClamps) clamps_.push_back(c);
  }
}

bool FapUdpStream::latest(std::array<double, kMaxFaceSignals>& out) const {
  std::lock_guard lock(mutex_);
  if (!has_pose_) return false;
  out = pose_;
  return true;
}

FapUdpStats FapUdpStream::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::vector<FapUdpPeerStats> FapUdpStream::peer_stats() const {
  std::lock_guard lock(mutex_);
  return peers_.stats();
}

std::vector<FapClamp> FapUdpStream::take_clamps() {
  std::lock_guard lock(mutex_);
  std::vector<FapClamp> out;
  out.swap(clamps_);
  return out;
}

}  // namespace facectl
