#include "drivers/can/custom_can_bus.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace facectl {

namespace {
constexpr int kMaxRxPerTick = 512;
}  // namespace

CustomCanBus::CustomCanBus(std::string name, CanTransport& transport,
                           const std::vector<ActuatorModel>& actuators,
                           const std::vector<double>& initial_positions, CanBusOptions options)
    : name_(std::move(name)),
      transport_(transport),
      options_(options),
      positions_(initial_positions),
      health_(name_) {
  if (initial_positions.size() != actuators.size()) {
    throw std::invalid_argument("bus " + name_ + ": one initial position per actuator");
  }
  if (options_.cycle_divider < 1)
    throw std::invalid_argument("bus " + name_ + ": cycle divider < 1");
  const int per_frame = custom_can::channels_per_frame(options_.fd, options_.width);
  for (std::size_t i = 0; i < actuators.size(); ++i) {
    const ActuatorModel& a = actuators[i];
    const int node = (a.address - 1) / per_frame + 1;
    if (a.address < 1 || node > 63) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + " has address " +
                                  std::to_string(a.address) + ", expected 1.." +
                                  std::to_string(63 * per_frame));
    }
    const auto ch = static_cast<std::size_t>((a.address - 1) % per_frame);
    addresses_.push_back(a.address);
    try {
      encodings_.push_back(custom_can::field_encoding(a.kind, a.encoding, options_.width));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("bus " + name_ + ": actuator " + a.name + ": " + e.what());
    }
    Board* board = nullptr;
    for (auto& b : boards_) {
      if (b->node == node) board = b.get();
    }
    if (board == nullptr) {
      boards_.push_back(std::make_unique<Board>());
      board = boards_.back().get();
      board->node = node;
      board->actuator.fill(SIZE_MAX);
      const std::string who = name_ + " board " + std::to_string(node);
      board->lost = who + ": heartbeat lost";
      board->reported = who + ": reports a fault";
      board->watchdog = who + ": watchdog tripped";
    }
    if (board->actuator[ch] != SIZE_MAX) {
      throw std::invalid_argument("bus " + name_ + ": two actuators on address " +
                                  std::to_string(a.address) + " (" + a.name + ")");
    }
    board->actuator[ch] = i;
    board->channels = std::max(board->channels, static_cast<int>(ch) + 1);
    board->targets[ch] = custom_can::to_field(encodings_[i], initial_positions[i]);
  }
}

void CustomCanBus::read(const TickTime& time, std::span<double> positions) {
  CanError err = CanError::kNone;
  for (int k = 0; k < kMaxRxPerTick && transport_.receive(frame_, err); ++k) {
    if (err != CanError::kNone) {
      health_.on_error(err, time.now_ns);
      continue;
    }
    if (frame_.id <= custom_can::kFeedbackBase || frame_.id > custom_can::kFeedbackBase + 63) {
      continue;  // someone else's traffic (our own commands are not looped back)
    }
    Board* board = nullptr;
    for (auto& b : boards_) {
      if (b->node == static_cast<int>(frame_.id - custom_can::kFeedbackBase)) board = b.get();
    }
    if (board == nullptr) continue;
    const auto fb = custom_can::decode_feedback(frame_, options_.width);
    if (!fb || fb->channels < board->channels) {
      bad_frames_.fetch_add(1, std::memory_order_relaxed);  // keep the last good values
      continue;
    }
    board->heard = true;
    board->last_heard_ns = time.now_ns;
    const char* lost = board->lost.c_str();
    board->fault.compare_exchange_strong(lost, nullptr, std::memory_order_acq_rel);
    for (int ch = 0; ch < board->channels; ++ch) {
      const std::size_t a = board->actuator[static_cast<std::size_t>(ch)];
      if (a != SIZE_MAX) {
        positions_[a] = custom_can::from_field(encodings_[a], options_.width,
                                               fb->positions[static_cast<std::size_t>(ch)]);
      }
    }
    if (board->awaiting_reset_echo &&
        static_cast<std::int8_t>(fb->sequence_echo - board->reset_sequence) >= 0) {
      board->awaiting_reset_echo = false;
    }
    if (enabled_ && !board->reset_pending && !board->awaiting_reset_echo) {
      if ((fb->status & custom_can::kStatusWatchdog) != 0) {
        set_first_reason(board->fault, board->watchdog);
      } else if ((fb->status & custom_can::kStatusFault) != 0) {
        set_first_reason(board->fault, board->reported);
      }
    }
  }
  const auto timeout_ns = static_cast<std::int64_t>(options_.heartbeat_timeout_s * 1e9);
  for (auto& b : boards_) {
    if ((b->heard || watching_) && time.now_ns - b->last_heard_ns > timeout_ns) {
      set_first_reason(b->fault, b->lost);
    }
  }
  for (std::size_t i = 0; i < positions_.size() && i < positions.size(); ++i) {
    positions[i] = positions_[i];
  }
  health_.end_cycle(time.now_ns);
}

void CustomCanBus::write(const TickTime& time, std::span<const double> positions) {
  if (!enabled_) return;
  if (!watching_) {
    watching_ = true;
    for (auto& b : boards_) {
      if (!b->heard) b->last_heard_ns = time.now_ns;
    }
  }
  if (cycle_++ % static_cast<std::uint64_t>(options_.cycle_divider) != 0) return;
  for (auto& bp : boards_) {
    Board& b = *bp;
    for (int ch = 0; ch < b.channels; ++ch) {
      const std::size_t a = b.actuator[static_cast<std::size_t>(ch)];
      if (a != SIZE_MAX && a < positions.size()) {
        b.targets[static_cast<std::size_t>(ch)] =
            custom_can::to_field(encodings_[a], b.wanted ? positions[a] : positions_[a]);
      }
    }
    custom_can::Command c{b.node, ++b.sequence,
                          b.wanted ? custom_can::kFlagEnable : std::uint8_t{0}};
    if (b.reset_pending) c.flags |= custom_can::kFlagFaultReset;
    custom_can::encode_command(
        c, options_.width,
        std::span<const std::int32_t>(b.targets.data(), static_cast<std::size_t>(b.channels)),
        options_.fd, frame_);
    const bool sent = transport_.send(frame_);
    health_.on_send(sent);
    if (sent && b.reset_pending) {
      b.reset_pending = false;
      b.awaiting_reset_echo = true;
      b.reset_sequence = c.sequence;
    }
  }
}

void CustomCanBus::set_enabled(bool enabled) {
  if (enabled == enabled_) return;
  enabled_ = enabled;
  cycle_ = 0;
  for (auto& b : boards_) {
    b->wanted = enabled;
    b->reset_pending = enabled;  // the first command after enabling clears a latched fault
    const char* f = b->fault.load(std::memory_order_relaxed);
    if (f != b->lost.c_str()) b->fault.store(nullptr, std::memory_order_release);
  }
}

void CustomCanBus::set_actuators_enabled(std::span<std::uint8_t> enabled) {
  const bool any = std::any_of(enabled.begin(), enabled.end(), [](auto on) { return on != 0; });
  if (!any || !enabled_) {
    set_enabled(any);
    if (!any) return;
  }
  for (auto& b : boards_) {
    bool on = true;
    for (int ch = 0; ch < b->channels; ++ch) {
      const std::size_t a = b->actuator[static_cast<std::size_t>(ch)];
      if (a != SIZE_MAX) on = on && a < enabled.size() && enabled[a] != 0;
    }
    if (on && !b->wanted) b->reset_pending = true;  // as on a bus enable
    b->wanted = on;
    for (int ch = 0; ch < b->channels && !on; ++ch) {
      const std::size_t a = b->actuator[static_cast<std::size_t>(ch)];
      if (a < enabled.size()) enabled[a] = 0;  // switched off with its board
    }
  }
}

BusStatus CustomCanBus::status() const {
  const char* device = nullptr;
  for (std::size_t i = 0; device == nullptr && i < boards_.size(); ++i) {
    device = boards_[i]->fault.load(std::memory_order_acquire);
  }
  return health_.status(device, bad_frames());
}

CanBusBudget CustomCanBus::budget(double tick_hz, long bitrate) const {
  return custom_can_budget(addresses_, options_, tick_hz, bitrate);
}

}  // namespace facectl
