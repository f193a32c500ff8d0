#include "firmware-host/inputs/live_link_face_stream.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>

#include "control/clock.hpp"
#include "firmware-host/inputs/arkit_capture.hpp"
#include "firmware-host/inputs/live_link_face_packet.hpp"

namespace facectl {
namespace {

// A version 6 packet is 318 bytes with a 36-character device id and a
// 12-character name, at most 782 with both names at their bound of 256;
// anything longer is refused for its length.
constexpr std::size_t kMaxDatagram = 2047;

// The retargeting table's view of one packet; `clamped` counts the weights
// ARKit's solver overshot past 0..1 (the parser refused any beyond -0.5..1.5).
ArkitFrame arkit_frame(const LiveLinkFacePacket& p, int& clamped) {
  ArkitFrame f;
  for (std::size_t i = 0; i < kArkitCount; ++i) {
    clamped += (p.values[i] < 0.0F || p.values[i] > 1.0F);
    f.weights[live_link_face_arkit_index(i)] = std::clamp<double>(p.values[i], 0.0, 1.0);
  }
  f.has_head = true;
  f.head_yaw = p.values[kLiveLinkFaceHeadYaw];
  f.head_pitch = p.values[kLiveLinkFaceHeadYaw + 1];
  f.head_roll = p.values[kLiveLinkFaceHeadYaw + 2];
  return f;
}

const LiveLinkFaceOptions& checked(const LiveLinkFaceOptions& o) {
  if (o.allow.empty()) {
    throw ConfigError("Live Link Face stream: expected at least one allowed sender");
  }
  return o;
}

}  // namespace

LiveLinkFaceStream::LiveLinkFaceStream(const RetargetTable& table, const FaceLayout& layout,
                                       const std::array<double, kMaxFaceSignals>& neutral,
                                       const LiveLinkFaceOptions& options,
                                       LatestValueMailbox<FaceCommand>* mailbox,
                                       ShowRecorder* recorder)
    : table_(table),
      layout_(layout),
      neutral_(neutral),
      options_(options),
      mailbox_(mailbox),
      recorder_(recorder),
      listener_(checked(options), "Live Link Face stream", "live_link_face", kMaxDatagram,
                [this](const UdpDatagram& d, std::string_view bytes) { return handle(d, bytes); }) {
}

std::size_t LiveLinkFaceStream::handle(const UdpDatagram& d, std::string_view bytes) {
  const std::uint64_t drops = listener_.new_kernel_drops(d);
  if (!listener_.allowed(d)) {
    std::lock_guard lock(mutex_);
    ++stats_.datagrams;
    stats_.kernel_drops += drops;
    ++stats_.refused_senders;
    return 0;
  }
  LiveLinkFacePacket packet;
  std::string error;
  try {
    // The listener cuts longer datagrams to kMaxDatagram + 1 bytes.
    if (bytes.size() > kMaxDatagram) {
      throw LiveLinkFacePacketError("expected a packet of at most " + std::to_string(kMaxDatagram) +
                                    " bytes, found a longer datagram");
    }
    packet = parse_live_link_face_packet(
        std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
  } catch (const LiveLinkFacePacketError& e) {
    error = e.what();
  }
  const std::int64_t now = monotonic_ns();
  const Sender sender{d.address, d.port};
  const bool plays = error.empty() && packet.has_face &&
                     (!playing_ || *playing_ == sender ||
                      now - played_ns_ > static_cast<std::int64_t>(options_.takeover_s * 1e9));
  std::array<double, kMaxFaceSignals> pose{};
  int clamped = 0;
  if (plays) {
    const ArkitFrame frame = arkit_frame(packet, clamped);
    clamped += arkit_frame_pose(frame, table_, layout_, neutral_, pose);
    playing_ = sender;
    played_ns_ = now;
    if (mailbox_ != nullptr) {
      FaceCommand cmd;
      cmd.values = pose;
      cmd.sequence = ++sequence_;
      cmd.stamp_ns = monotonic_ns();
      mailbox_->publish(cmd);
    }
    if (first_played_ns_ < 0) first_played_ns_ = now;
    if (recorder_ != nullptr)
      recorder_->add(static_cast<double>(now - first_played_ns_) * 1e-9, pose);
  }
  std::lock_guard lock(mutex_);
  ++stats_.datagrams;
  stats_.kernel_drops += drops;
  if (!error.empty()) {
    ++stats_.malformed;
    stats_.last_error = "udp datagram " + std::to_string(stats_.datagrams) + " from " +
                        ipv4_text(d.address) + ":" + std::to_string(d.port) + ": " + error;
    return 0;
  }
  if (!packet.has_face) {
    ++stats_.no_face;
    return 0;
  }
  if (!plays) {
    ++stats_.held_back;
    return 0;
  }
  ++stats_.frames;
  stats_.clamps += static_cast<std::uint64_t>(clamped);
  stats_.subject.assign(packet.subject);
  stats_.device_id.assign(packet.device_id);
  pose_ = pose;
  has_pose_ = true;
  return 1;
}

bool LiveLinkFaceStream::latest(std::array<double, kMaxFaceSignals>& out) const {
  std::lock_guard lock(mutex_);
  if (!has_pose_) return false;
  out = pose_;
  return true;
}

LiveLinkFaceStats LiveLinkFaceStream::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

}  // namespace facectl
