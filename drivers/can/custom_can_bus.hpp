#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"
#include "drivers/can/can_bus_health.hpp"
#include "drivers/can/can_bus_options.hpp"
#include "drivers/can/can_transport.hpp"
#include "drivers/protocol/can_bus_budget.hpp"
#include "drivers/protocol/custom_can_frames.hpp"

namespace facectl {

// ActuatorBus for custom actuator boards speaking facectl's frame layout
// (custom_can_frames.hpp): per board and cycle one command frame with a
// sequence counter and the packed targets; each board answers with a
// feedback frame, which is also its heartbeat. Runs in the tick: every call
// is non-blocking and allocation-free. Disabled, it transmits nothing.
class CustomCanBus final : public ActuatorBus {
 public:
  // Actuator addresses number channels across boards: node = (address-1)/k + 1,
  // channel = (address-1) % k, with k = channels per frame (3 for classic int16).
  CustomCanBus(std::string name, CanTransport& transport,
               const std::vector<ActuatorModel>& actuators,
               const std::vector<double>& initial_positions, CanBusOptions options = {});

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  // The enable flag is per board: a board is on only while every actuator on
  // it is; a board switched off gets frames without the enable flag (torque
  // off, its heartbeat kept) carrying its measured positions.
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;

  // One command and one feedback frame per board per bus cycle.
  CanBusBudget budget(double tick_hz, long bitrate) const;
  std::size_t board_count() const { return boards_.size(); }
  std::uint64_t bad_frames() const { return bad_frames_.load(std::memory_order_relaxed); }

 private:
  struct Board {
    int node = 0;
    int channels = 0;
    std::array<std::size_t, 31> actuator{};  // channel -> actuator index
    std::array<std::int32_t, 31> targets{};
    std::uint8_t sequence = 0;
    bool reset_pending = false;
    bool wanted = false;               // enabled by the controller (every channel on)
    bool awaiting_reset_echo = false;  // status is stale until the board echoes the reset
    std::uint8_t reset_sequence = 0;
    bool heard = false;
    std::int64_t last_heard_ns = 0;
    std::atomic<const char*> fault{nullptr};
    std::string lost, reported, watchdog;
  };

  std::string name_;
  CanTransport& transport_;
  CanBusOptions options_;
  std::vector<std::unique_ptr<Board>> boards_;
  std::vector<WireEncoding> encodings_;  // per actuator
  std::vector<double> positions_;
  std::vector<int> addresses_;  // for the budget
  CanBusHealth health_;
  bool enabled_ = false;
  bool watching_ = false;  // enabled at least once since the boards were last heard
  std::uint64_t cycle_ = 0;
  std::atomic<std::uint64_t> bad_frames_{0};
  CanFrame frame_;
};

}  // namespace facectl
