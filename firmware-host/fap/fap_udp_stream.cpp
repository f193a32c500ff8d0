#include "firmware-host/fap/fap_udp_stream.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/clock.hpp"
#include "firmware-host/fap/fap_udp_bounds.hpp"

namespace facectl {
namespace {

constexpr std::size_t kMaxDatagram = 65536;  // above UDP's 65507: never cut
constexpr std::size_t kMaxKeptClamps = 1024;

std::int64_t to_ns(double s) {
  return static_cast<std::int64_t>(s * 1e9);
}

// The frames of one datagram, read on `reader` with every field bounded;
// `skipped` frames of silence widen the datagram's jump. Line numbers
// count within the datagram (the reader's source names it). Throws
// FapFormatError, or FapBoundError for a field past `limits`.
std::vector<FapFrame> read_datagram(FapReader& reader, std::string_view datagram, long skipped,
                                    const FapUdpLimits& limits) {
  std::vector<FapFrame> frames;
  int line = 0;
  std::size_t pos = 0;
  // One bound for the whole datagram: 64 frames each 1000 ahead of the one
  // before would otherwise move the numbering 64,000 frames at once.
  std::optional<long> before = reader.last_frame_number();
  while (pos < datagram.size()) {
    const std::size_t end = std::min(datagram.find('\n', pos), datagram.size());
    ++line;
    if (!reader.last_frame_number()) before.reset();  // a header restarted the numbering
    const auto f = reader.feed(datagram.substr(pos, end - pos), line);
    check_header_bounds(reader, limits, line);
    if (f) {
      check_frame_bounds(reader, *f, before, skipped, limits);
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

// The frames a sender's clock ran on since its last frame was taken, at
// its header's frame rate (bounded by FapUdpLimits).
long skipped_frames(const FapUdpPeer& peer, std::int64_t now_ns) {
  if (!peer.reader.has_header() || !peer.reader.last_frame_number()) return 0;
  const double silent_s = static_cast<double>(now_ns - peer.accepted_ns) * 1e-9;
  return static_cast<long>(std::min(silent_s * peer.reader.header().frame_rate, 1e12));
}

const FapUdpOptions& checked(const FapUdpOptions& o) {
  if (o.allow.empty() || o.max_peers < 2) {
    throw ConfigError("FAP stream " + o.bind_address + ":" + std::to_string(o.port) +
                      ": expected at least one allowed sender and two peer slots");
  }
  return o;
}

}  // namespace

FapUdpStream::FapUdpStream(const FapMapping& mapping, const FapUdpOptions& options,
                           LatestValueMailbox<FaceCommand>* mailbox, ShowRecorder* recorder)
    : mapping_(mapping),
      options_(options),
      mailbox_(mailbox),
      recorder_(recorder),
      // Too few slots is a ConfigError in checked(), with the address.
      peers_(std::max<std::size_t>(options.max_peers, 2)),
      listener_(checked(options), "FAP stream", "fap_stream", kMaxDatagram,
                [this](const UdpDatagram& d, std::string_view text) { return handle(d, text); }) {}

// Called with mutex_ held.
void FapUdpStream::count_arrival(const UdpDatagram& d) {
  ++stats_.datagrams;
  stats_.kernel_drops += listener_.new_kernel_drops(d);
}

// Called with mutex_ held.
void FapUdpStream::reject(FapUdpPeer& peer, const std::string& error, bool out_of_bounds) {
  ++(out_of_bounds ? stats_.out_of_bounds : stats_.malformed);
  ++(out_of_bounds ? peer.stats.out_of_bounds : peer.stats.malformed);
  stats_.last_error = error;
  peer.stats.last_error = error;
}

std::size_t FapUdpStream::handle(const UdpDatagram& d, std::string_view text) {
  // A sender off the allow list is counted before anything of its datagram
  // is parsed or anything allocated for it.
  if (!listener_.allowed(d)) {
    std::lock_guard lock(mutex_);
    count_arrival(d);
    ++stats_.refused_senders;
    last_refused_ = FapUdpSender{d.address, d.port};
    return 0;
  }
  const std::int64_t now = monotonic_ns();
  const FapUdpSender sender{d.address, d.port};
  FapUdpPeer* peer = nullptr;
  std::uint64_t number = 0;
  {
    std::lock_guard lock(mutex_);
    count_arrival(d);
    number = stats_.datagrams;
    peer = &peers_.find_or_add(sender, now, playing_);
    ++peer->stats.datagrams;
    stats_.peers = peers_.size();
    stats_.evicted = peers_.evicted();
  }
  // Parsed without the lock (only this thread touches readers) on a copy of
  // the sender's reader, committed only if the whole datagram is good.
  FapReader trial = peer->reader;
  trial.set_source("udp " + listener_.bound() + " datagram " + std::to_string(number) + " from " +
                   peer->stats.peer);
  std::vector<FapFrame> frames;
  try {
    frames = read_datagram(trial, text, skipped_frames(*peer, now), options_.limits);
  } catch (const FapFormatError& e) {
    std::lock_guard lock(mutex_);
    reject(*peer, e.what(), dynamic_cast<const FapBoundError*>(&e) != nullptr);
    return 0;
  }
  peer->reader = std::move(trial);
  if (frames.empty()) return 0;  // a header alone
  peer->accepted_ns = now;
  return take(*peer, frames, now);
}

// The good frames of an allowed sender: played, or kept in its own state
// while another sender plays (so that it plays on from there once it takes
// over). Returns the number played.
std::size_t FapUdpStream::take(FapUdpPeer& peer, const std::vector<FapFrame>& frames,
                               std::int64_t now_ns) {
  const bool plays =
      !playing_ || *playing_ == peer.sender || now_ns - played_ns_ > to_ns(options_.takeover_s);
  std::vector<FapClamp> clamps;
  std::array<double, kMaxFaceSignals> pose{};
  for (const FapFrame& f : frames) {
    peer.state.apply(f);
    if (plays) mapping_.map(peer.state, f.number, pose, &clamps);
  }
  if (!plays) {
    std::lock_guard lock(mutex_);
    stats_.held_back += frames.size();
    peer.stats.held_back += frames.size();
    return 0;
  }
  playing_ = peer.sender;
  played_ns_ = now_ns;
  if (first_played_ns_ < 0) first_played_ns_ = now_ns;
  if (recorder_ != nullptr) {
    recorder_->add(static_cast<double>(now_ns - first_played_ns_) * 1e-9, pose);
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
  peer.stats.frames += frames.size();
  stats_.clamps += clamps.size();
  for (const FapClamp& c : clamps) {
    if (clamps_.size() < kMaxKeptClamps) clamps_.push_back(c);
  }
  return frames.size();
}

bool FapUdpStream::latest(std::array<double, kMaxFaceSignals>& out) const {
  std::lock_guard lock(mutex_);
  if (!has_pose_) return false;
  out = pose_;
  return true;
}

FapUdpStats FapUdpStream::stats() const {
  std::lock_guard lock(mutex_);
  FapUdpStats st = stats_;
  if (last_refused_) {
    st.last_refused = ipv4_text(last_refused_->address) + ":" + std::to_string(last_refused_->port);
  }
  return st;
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
