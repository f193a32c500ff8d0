#include "firmware-host/fap/fap_udp_stream.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>

#include "control/clock.hpp"

namespace facectl {
namespace {

constexpr std::size_t kMaxDatagram = 65536;
constexpr std::size_t kMaxKeptClamps = 1024;

}  // namespace

FapUdpStream::FapUdpStream(const FapMapping& mapping, const FapUdpOptions& options,
                           LatestValueMailbox<FaceCommand>* mailbox)
    : mapping_(mapping), mailbox_(mailbox), reader_("udp"), buffer_(kMaxDatagram) {
  const std::string where =
      "FAP stream " + options.bind_address + ":" + std::to_string(options.port);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(options.port);
  if (inet_pton(AF_INET, options.bind_address.c_str(), &addr.sin_addr) != 1) {
    throw ConfigError(where + ": expected an IPv4 address to bind to, found '" +
                      options.bind_address + "'");
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw ConfigError(where + ": socket: " + std::strerror(errno));
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string err = std::strerror(errno);
    ::close(fd_);
    throw ConfigError(where + ": cannot bind: " + err);
  }
  socklen_t len = sizeof addr;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = ntohs(addr.sin_port);
  bound_ = options.bind_address + ":" + std::to_string(port_);
  reader_ = FapReader("udp " + bound_);
  reader_.allow_new_header(true);
}

FapUdpStream::~FapUdpStream() {
  stop();
  if (fd_ >= 0) ::close(fd_);
}

std::size_t FapUdpStream::poll() {
  std::size_t accepted_before = 0;
  {
    std::lock_guard lock(mutex_);
    accepted_before = stats_.frames;
  }
  for (;;) {
    sockaddr_in peer{};
    socklen_t len = sizeof peer;
    const ssize_t n = ::recvfrom(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&peer), &len);
    if (n < 0) break;  // EAGAIN: nothing more queued (other errors: try again next poll)
    char ip[INET_ADDRSTRLEN] = "?";
    inet_ntop(AF_INET, &peer.sin_addr, ip, sizeof ip);
    handle(std::string_view(buffer_.data(), static_cast<std::size_t>(n)),
           std::string(ip) + ":" + std::to_string(ntohs(peer.sin_port)));
  }
  std::lock_guard lock(mutex_);
  return stats_.frames - accepted_before;
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

void FapUdpStream::handle(std::string_view datagram, const std::string& peer) {
  std::uint64_t number = 0;
  {
    std::lock_guard lock(mutex_);
    number = ++stats_.datagrams;
  }
  // Parsed on a copy of the reader, committed only if the whole datagram is
  // good; line numbers count within the datagram, which the source names.
  FapReader trial = reader_;
  trial.set_source("udp " + bound_ + " datagram " + std::to_string(number) + " from " + peer);
  std::vector<FapFrame> frames;
  std::string error;
  try {
    int line = 0;
    std::size_t pos = 0;
    while (pos < datagram.size()) {
      const std::size_t end = std::min(datagram.find('\n', pos), datagram.size());
      ++line;
      if (auto f = trial.feed(datagram.substr(pos, end - pos), line)) frames.push_back(*f);
      pos = end + 1;
    }
    if (trial.mid_frame()) {
      trial.fail(line + 1, 0,
                 "the values line of the frame whose mask is at line " +
                     std::to_string(trial.mask_line()) + ", in the same datagram",
                 "the end of the datagram");
    }
    if (!trial.has_header()) {
      trial.fail(1, 0, "a header 'version name frame_rate frame_count' before any frame",
                 "a datagram without one");
    }
  } catch (const FapFormatError& e) {
    error = e.what();
  }
  if (!error.empty()) {
    std::lock_guard lock(mutex_);
    ++stats_.malformed;
    stats_.last_error = error;
    return;
  }
  reader_ = trial;
  if (frames.empty()) return;  // a header alone
  std::vector<FapClamp> clamps;
  std::array<double, kMaxFaceSignals> pose{};
  for (const FapFrame& f : frames) {
    state_.apply(f);
    mapping_.map(state_, f.number, pose, &clamps);
  }
  if (mailbox_ != nullptr) {
    FaceCommand cmd;
    cmd.values = pose;
    cmd.sequence = ++sequence_;
    cmd.stamp_ns = monotonic_ns();
    mailbox_->publish(cmd);
  }
  std::lock_guard lock(mutex_);
  pose_ = pose;
  has_pose_ = true;
  stats_.frames += frames.size();
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

std::vector<FapClamp> FapUdpStream::take_clamps() {
  std::lock_guard lock(mutex_);
  std::vector<FapClamp> out;
  out.swap(clamps_);
  return out;
}

}  // namespace facectl
