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
#include "drivers/dynamixel/dynamixel_link.hpp"
#include "drivers/dynamixel/dynamixel_options.hpp"
#include "drivers/protocol/dynamixel_x_table.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {

// Counters of the I/O thread, readable from any thread.
struct DynamixelStats {
  std::uint64_t cycles = 0;
  std::uint64_t status_packets = 0;  // good status packets received
  std::uint64_t timeouts = 0;        // status packets that did not come
  std::uint64_t bad_crc = 0;
  std::uint64_t bad_packets = 0;  // wrong length, wrong id, an error in the status
  std::uint64_t reopens = 0;      // the port reopened after it was lost
  std::uint64_t max_cycle_ns = 0;
};

// ActuatorBus over DYNAMIXEL Protocol 2.0 to X-series servos on one serial
// port (docs/PROTOCOLS.md, "Dynamixel"). An actuator's `address` is its
// servo ID. The tick touches only lock-free mailboxes and atomics; an I/O
// thread owns the port and, each cycle, sends the goal positions of the
// servos with torque on in one Sync Write and reads every servo's load,
// position, voltage and temperature with one Sync Read.
//
// At start-up each servo is checked (an X-series model, answering) and set
// up with its torque off: Status Return Level 2, Return Delay Time, position
// control mode and its Min/Max Position Limit from the rig's hard limits,
// each written only when it differs (EEPROM wears). Torque goes on per servo,
// after its goal has been set to where it is (bumpless), and with it the
// servo's own Bus Watchdog, which stops it if this program stops talking.
class DynamixelBus final : public ActuatorBus {
 public:
  static constexpr std::size_t kMaxActuators = 32;

  // Throws std::invalid_argument for a bad ID, a duplicate, or hard limits
  // that fall outside the servo's 0..4095 pulses. Starts the I/O thread; the
  // port is opened there (and reopened if lost).
  DynamixelBus(std::string name, std::string device, long baud,
               const std::vector<ActuatorModel>& actuators,
               const std::vector<double>& initial_positions, DynamixelOptions options = {});
  ~DynamixelBus() override;
  DynamixelBus(const DynamixelBus&) = delete;
  DynamixelBus& operator=(const DynamixelBus&) = delete;

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;
  void read_health(std::span<ActuatorHealth> health) override;

  // True once every servo has been set up and answered.
  bool ready() const;
  // True while the servo's torque is on (confirmed by its status packet).
  bool torque_on(std::size_t actuator) const;
  DynamixelStats stats() const;

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
  bool switch_torque(Servo& s, bool on);
  void sync_write_goals();
  void sync_read_feedback(std::int64_t now_ns);
  void check_hardware_error(Servo& s);
  // One instruction to one servo and its status packet; `data` gets the
  // parameters. False on no reply, a bad one, or an error in the status.
  bool transact(Servo& s, std::span<const std::uint8_t> packet, std::span<std::uint8_t> data);
  bool read_register(Servo& s, std::uint16_t address, std::span<std::uint8_t> data);
  bool write_register(Servo& s, std::uint16_t address, std::span<const std::uint8_t> data);
  void publish_counters();
  void latch_off(Servo& s);
  void check_bus_watchdog();
  void fail(Servo& s, const char* reason);
  void lose_port(const char* reason);

  std::string name_;
  std::string device_;
  long baud_ = 0;
  DynamixelOptions options_;
  std::size_t count_ = 0;
  std::vector<std::unique_ptr<Servo>> servos_;  // one per actuator, in order

  // Tick side.
  LatestValueMailbox<Command> commands_;
  LatestValueMailbox<Feedback> feedback_;
  Command staging_;
  Feedback last_feedback_;
  std::atomic<bool> enabled_{false};
  std::atomic<std::uint32_t> epoch_{0};  // +1 on every enable: older commands are never sent

  // I/O thread side.
  std::unique_ptr<DynamixelLink> link_;
  DynamixelLink::Counters counted_;  // of the links lost before this one
  std::int64_t last_open_attempt_ns_ = -1'000'000'000'000;
  Command current_;
  Feedback measured_;
  std::vector<std::uint8_t> tx_;
  std::size_t watchdog_turn_ = 0;
  std::string port_lost_;  // static reason
  std::atomic<const char*> port_reason_{nullptr};

  struct AtomicStats {
    std::atomic<std::uint64_t> cycles{0}, status_packets{0}, timeouts{0}, bad_crc{0},
        bad_packets{0}, reopens{0}, max_cycle_ns{0};
  } stats_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
