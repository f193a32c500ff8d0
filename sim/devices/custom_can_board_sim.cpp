#include "sim/devices/custom_can_board_sim.hpp"

#include <stdexcept>

namespace facectl::sim {

using namespace custom_can;

CustomCanBoardSim::CustomCanBoardSim(int node, std::vector<BoardChannel> channels, Width width,
                                     bool fd, int heartbeat_ms, int watchdog_ms)
    : node_(node),
      width_(width),
      fd_(fd),
      heartbeat_ms_(heartbeat_ms),
      watchdog_ms_(watchdog_ms),
      spec_(std::move(channels)) {
  if (spec_.empty() || static_cast<int>(spec_.size()) > channels_per_frame(fd, width)) {
    throw std::invalid_argument("simulated CAN board: too many channels for one frame");
  }
  for (const auto& c : spec_) {
    const ActuatorKind kind =
        c.unit == modbus_map::Unit::kRotary ? ActuatorKind::kRotary : ActuatorKind::kLinear;
    encodings_.push_back(field_encoding(kind, c.encoding, width));  // refuses int32 in int16
    plants_.emplace_back(c.plant, c.initial);
  }
}

void CustomCanBoardSim::send_feedback(std::int64_t now_ns) {
  std::int32_t counts[31];
  for (std::size_t i = 0; i < plants_.size(); ++i) {
    counts[i] = to_field(encodings_[i], plants_[i].measured());
  }
  CanFrame f;
  encode_command({node_, sequence_, 0}, width_,
                 std::span<const std::int32_t>(counts, plants_.size()), fd_, f);
  f.id = kFeedbackBase + static_cast<std::uint32_t>(node_);
  f.data[1] = static_cast<std::uint8_t>((enabled_ ? kStatusEnabled : 0) |
                                        (fault_ || watchdog_ ? kStatusFault : 0) |
                                        (watchdog_ ? kStatusWatchdog : 0));
  emit(f, now_ns);
  last_sent_ns_ = now_ns;
}

void CustomCanBoardSim::on_frame(const CanFrame& f, std::int64_t now_ns) {
  if (f.id != kCommandBase + static_cast<std::uint32_t>(node_)) return;
  std::lock_guard lock(mutex_);
  const auto w = static_cast<std::size_t>(width_);
  const std::size_t need = 2 + plants_.size() * w;
  if (fd_ ? f.len < need : f.len != need) return;  // not for our channel count: ignore
  commands_.fetch_add(1);
  if (any_command_ && f.data[0] != static_cast<std::uint8_t>(sequence_ + 1)) gaps_.fetch_add(1);
  any_command_ = true;
  sequence_ = f.data[0];
  last_command_ns_ = now_ns;
  if ((f.data[1] & kFlagFaultReset) != 0) fault_ = watchdog_ = false;
  enabled_ = (f.data[1] & kFlagEnable) != 0 && !fault_ && !watchdog_;
  for (std::size_t i = 0; i < plants_.size(); ++i) {
    plants_[i].advance(now_ns);
    plants_[i].set_enabled(enabled_);
    const std::uint8_t* p = &f.data[2 + i * w];
    const std::int32_t c = width_ == Width::kInt16 ? static_cast<std::int16_t>(get_u16(p))
                                                   : static_cast<std::int32_t>(get_u32(p));
    if (enabled_) plants_[i].command(now_ns, from_field(encodings_[i], width_, c));
  }
  send_feedback(now_ns);
}

void CustomCanBoardSim::step(std::int64_t now_ns) {
  std::lock_guard lock(mutex_);
  for (auto& p : plants_) p.advance(now_ns);
  if (inject_.exchange(false)) fault_ = true;
  if (enabled_ && now_ns - last_command_ns_ > static_cast<std::int64_t>(watchdog_ms_) * 1'000'000) {
    watchdog_ = true;
  }
  if (fault_ || watchdog_) {
    enabled_ = false;
    for (auto& p : plants_) p.set_enabled(false);
  }
  if (now_ns - last_sent_ns_ >= static_cast<std::int64_t>(heartbeat_ms_) * 1'000'000) {
    send_feedback(now_ns);
  }
}

bool CustomCanBoardSim::enabled() const {
  std::lock_guard lock(mutex_);
  return enabled_;
}
bool CustomCanBoardSim::watchdog_tripped() const {
  std::lock_guard lock(mutex_);
  return watchdog_;
}
double CustomCanBoardSim::position(std::size_t channel) const {
  std::lock_guard lock(mutex_);
  return plants_.at(channel).position();
}

}  // namespace facectl::sim
