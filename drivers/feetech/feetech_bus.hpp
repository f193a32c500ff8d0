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
#include "drivers/feetech/feetech_link.hpp"
#include "drivers/feetech/feetech_options.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {

// Counters of the I/O thread, readable from any thread.
struct FeetechStats {
  std::uint64_t cycles = 0;
  std::uint64_t status_packets = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t bad_packets = 0;
  std::uint64_t reopens = 0;
  std::uint64_t max_cycle_ns = 0;
};

// ActuatorBus over the Feetech SCS/STS protocol on one serial port
// (docs/PROTOCOLS.md, "Feetech"). An actuator's `address` is its servo ID.
// The tick touches only lock-free mailboxes and atomics; an I/O thread owns
// the port and, each cycle, sends the goal positions of the servos with
// torque on in one Sync Write and reads every servo's position, speed,
// load, voltage and temperature: one Sync Read on STS, one Read per servo
// on SCS (which has no Sync Read).
//
// At start-up each servo is pinged and set up with its torque off: Response
// Level 1 (every write answered), Return Delay and its Min/Max Angle Limit
// from the rig's hard limits, each written only when it differs, with the
// EEPROM unlocked for the write and locked again. Torque goes on per servo,
// after its goal has been set to where it is (bumpless). A Feetech servo has
// no bus watchdog: if this program stops talking it holds its last goal
// (docs/SAFETY.md).
class FeetechBus final : public ActuatorBus {
 public:
  static constexpr std::size_t kMaxActuators = 32;

  // Throws std::invalid_argument for a bad ID, a duplicate, or hard limits
  // outside the series' position range. Starts the I/O thread.
  FeetechBus(std::string name, std::string device, long baud,
             const std::vector<ActuatorModel>& actuators,
             const std::vector<double>& initial_positions, FeetechOptions options = {});
  ~FeetechBus() override;
  FeetechBus(const FeetechBus&) = delete;
  FeetechBus& operator=(const FeetechBus&) = delete;

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;
  void read_health(std::span<ActuatorHealth> health) override;

  // True once every servo has been set up and answered.
  bool ready() const;
  // True while the servo's torque is on (its write confirmed).
  bool torque_on(std::size_t actuator) const;
  FeetechStats stats() const;

 private:
  struct Command {
    std::array<double, kMaxActuators> positions{};
    std::uint32_t epoch = 0;
  };
  struct Feedback {
    std::array<double, kMaxActuators> positions{};
    std::array<ActuatorHealth, kMaxActuators> health{};
  };
  enum class Stage { kSetUp, kReady, kOn };
  struct Servo;

  void io_loop();
  bool open_port(std::int64_t now_ns);
  void run_cycle(std::int64_t now_ns);
  bool set_up(Servo& s);
  bool write_eeprom(Servo& s, std::uint8_t address, std::span<const std::uint8_t> data);
  bool switch_torque(Servo& s, bool on);
  void sync_write_goals();
  void read_feedback(std::int64_t now_ns);
  void take_feedback(Servo& s, std::uint8_t error, std::span<const std::uint8_t> p,
                     std::int64_t now_ns);
  void check_error(Servo& s, std::uint8_t error);
  bool transact(Servo& s, std::span<const std::uint8_t> packet, std::span<std::uint8_t> data);
  bool read_register(Servo& s, std::uint8_t address, std::span<std::uint8_t> data);
  bool write_register(Servo& s, std::uint8_t address, std::span<const std::uint8_t> data);
  void publish_counters();
  void latch_off(Servo& s);
  void fail(Servo& s, const char* reason);
  void lose_port(const char* reason);
  void broadcast_torque_off(std::span<const std::uint8_t> ids);

  std::string name_;
  std::string device_;
  long baud_ = 0;
  FeetechOptions options_;
  ft::Series series_;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Servo>> servos_;

  // Tick side.
  LatestValueMailbox<Command> commands_;
  LatestValueMailbox<Feedback> feedback_;
  Command staging_;
  Feedback last_feedback_;
  std::atomic<bool> enabled_{false};
  std::atomic<std::uint32_t> epoch_{0};

  // I/O thread side.
  std::unique_ptr<FeetechLink> link_;
  FeetechLink::Counters counted_;
  std::int64_t last_open_attempt_ns_ = -1'000'000'000'000;
  Command current_;
  Feedback measured_;
  std::vector<std::uint8_t> tx_;
  std::string port_lost_;
  std::atomic<const char*> port_reason_{nullptr};

  struct AtomicStats {
    std::atomic<std::uint64_t> cycles{0}, status_packets{0}, timeouts{0}, bad_checksum{0},
        bad_packets{0}, reopens{0}, max_cycle_ns{0};
  } stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
