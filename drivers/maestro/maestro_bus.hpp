#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "control/actuator_bus.hpp"
#include "control/actuator_model.hpp"
#include "control/realtime/latest_value_mailbox.hpp"
#include "drivers/maestro/maestro_options.hpp"
#include "drivers/protocol/wire_encoding.hpp"
#include "drivers/serial/serial_port.hpp"

namespace facectl {

// Counters of the I/O thread, readable from any thread.
struct MaestroStats {
  std::uint64_t cycles = 0;
  std::uint64_t replies = 0;        // cycles whose every reply came
  std::uint64_t timeouts = 0;       // cycles with no reply at all
  std::uint64_t short_replies = 0;  // cycles with part of the replies
  std::uint64_t error_reports = 0;  // Get Errors answers with a bit set
  std::uint64_t reopens = 0;        // the port reopened after it was lost
  std::uint64_t max_cycle_ns = 0;
};

// ActuatorBus over a Pololu Maestro servo controller's serial commands
// (docs/PROTOCOLS.md, "Maestro"), compact or Pololu protocol. An actuator's
// `address` is its channel; its encoding gives the pulse in µs. The tick
// touches only lock-free mailboxes and atomics; an I/O thread owns the port
// and, each cycle, sends every channel's target (0 = no pulses: a hobby
// servo's "torque off") and reads back every channel's position and the
// error register.
//
// The position read back is the pulse the Maestro is sending (after its own
// speed and acceleration limits), not a measurement: a hobby servo reports
// nothing. A channel is switched on per actuator, bumplessly (at the pulse it
// last had), and off by any fault: silence, error bits, a lost port. It stays
// off until the controller has disabled it.
class MaestroBus final : public ActuatorBus {
 public:
  // Throws std::invalid_argument for a bad channel, a duplicate, hard limits
  // whose pulses fall outside the Maestro's 14-bit target, or
  // multiple_targets over channels that are not one block. Starts the I/O
  // thread; the port is opened there (and reopened if lost).
  MaestroBus(std::string name, std::string device, long baud,
             const std::vector<ActuatorModel>& actuators,
             const std::vector<double>& initial_positions, MaestroOptions options = {});
  ~MaestroBus() override;
  MaestroBus(const MaestroBus&) = delete;
  MaestroBus& operator=(const MaestroBus&) = delete;

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;
  void read_health(std::span<ActuatorHealth> health) override;

  // True once the Maestro has answered a whole cycle with no error bits.
  bool ready() const { return ready_.load(std::memory_order_acquire); }
  // True while the channel is sending pulses.
  bool output_on(std::size_t actuator) const;
  MaestroStats stats() const;

 private:
  static constexpr std::size_t kMax = maestro::kMaxChannels;
  struct Command {
    std::array<double, kMax> positions{};
    std::uint32_t epoch = 0;
  };
  struct Feedback {
    std::array<double, kMax> positions{};
    std::array<ActuatorHealth, kMax> health{};
  };
  struct Channel;

  void io_loop();
  bool open_port(std::int64_t now_ns);
  void run_cycle(std::int64_t now_ns);
  void update_outputs();
  bool send_targets();
  void read_back(std::int64_t now_ns);
  void take_errors(std::uint16_t bits);
  void latch_all();
  void lose_port();

  std::string name_;
  std::string device_;
  long baud_ = 0;
  MaestroOptions options_;
  maestro::Addressing to_;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Channel>> channels_;  // one per actuator, in order
  int first_channel_ = 0;                           // of the Set Multiple Targets block

  // Tick side.
  LatestValueMailbox<Command> commands_;
  LatestValueMailbox<Feedback> feedback_;
  Command staging_;
  Feedback last_feedback_;
  std::atomic<bool> enabled_{false};
  std::atomic<std::uint32_t> epoch_{0};  // +1 on every enable: older commands are never sent

  // I/O thread side.
  std::unique_ptr<SerialPort> port_;
  std::int64_t last_open_attempt_ns_ = -1'000'000'000'000;
  std::int64_t last_ok_ns_ = 0;
  std::uint16_t error_bits_ = 0;  // latched until every channel has been disabled
  Command current_;
  Feedback measured_;
  std::vector<std::uint8_t> tx_, rx_;
  // Static reasons (BusStatus::reason must outlive the call).
  std::string port_lost_, silent_, multiple_refused_, error_reasons_[16];
  std::atomic<const char*> port_reason_{nullptr};
  std::atomic<const char*> reason_{nullptr};
  std::atomic<bool> ready_{false};

  struct AtomicStats {
    std::atomic<std::uint64_t> cycles{0}, replies{0}, timeouts{0}, short_replies{0},
        error_reports{0}, reopens{0}, max_cycle_ns{0};
  } stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
