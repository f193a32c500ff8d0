#pragma once

#include <atomic>
#include <mutex>
#include <vector>

#include "drivers/protocol/custom_can_frames.hpp"
#include "sim/devices/can_device.hpp"
#include "sim/devices/modbus_actuator_board.hpp"

namespace facectl::sim {

// A simulated custom actuator board on CAN (custom_can_frames.hpp): answers
// each command frame with a feedback frame, sends one every heartbeat period
// anyway, and latches a watchdog fault when enabled without commands.
class CustomCanBoardSim final : public CanDevice {
 public:
  CustomCanBoardSim(int node, std::vector<BoardChannel> channels, custom_can::Width width,
                    bool fd = false, int heartbeat_ms = 10, int watchdog_ms = 50);

  void on_frame(const CanFrame& f, std::int64_t now_ns) override;
  void step(std::int64_t now_ns) override;

  void inject_fault() { inject_.store(true); }
  bool enabled() const;
  bool watchdog_tripped() const;
  double position(std::size_t channel) const;
  std::uint64_t commands() const { return commands_.load(); }
  std::uint64_t sequence_gaps() const { return gaps_.load(); }  // lost command frames

 private:
  void send_feedback(std::int64_t now_ns);

  const int node_;
  const custom_can::Width width_;
  const bool fd_;
  const int heartbeat_ms_;
  const int watchdog_ms_;
  std::vector<BoardChannel> spec_;
  std::vector<WireEncoding> encodings_;  // per channel, from its rig actuator
  mutable std::mutex mutex_;
  std::vector<ServoPlant> plants_;
  bool enabled_ = false;
  bool fault_ = false;
  bool watchdog_ = false;
  bool any_command_ = false;
  std::uint8_t sequence_ = 0;
  std::int64_t last_command_ns_ = 0;
  std::int64_t last_sent_ns_ = 0;
  std::atomic<bool> inject_{false};
  std::atomic<std::uint64_t> commands_{0}, gaps_{0};
};

}  // namespace facectl::sim
