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
#include "drivers/i2c/i2c_transport.hpp"
#include "drivers/i2c/pca9685_options.hpp"
#include "drivers/protocol/pca9685_registers.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {

// ActuatorBus over NXP PCA9685 PWM boards on one I2C bus (docs/PROTOCOLS.md,
// "PCA9685"). Each actuator's encoding gives its pulse in µs (raw = µs); the
// I/O thread sets each board up (sleep, PRE_SCALE, wake, auto-increment,
// every output off, read back) and then, each cycle, writes the LEDn
// registers of the channels whose pulse changed and reads MODE1 back to
// notice a board that reset. The tick only touches a lock-free mailbox and
// atomics.
//
// The PCA9685 has no feedback: read() reports the last commanded position
// (the initial one until the first write). A channel switched off is held
// low (LED_FULL_OFF): the servo goes limp. Switched on again, it gets the
// last commanded position, which is what read() reported (bumpless as far
// as the controller can know; a servo moved by hand while limp snaps back).
class Pca9685Bus final : public ActuatorBus {
 public:
  static constexpr std::size_t kMaxActuators = 64;

  // `actuators` are this bus's slice, in the controller's order; their
  // addresses place them on boards (pca9685_place). Throws
  // std::invalid_argument naming the bus and actuator for a bad address,
  // a shared channel or an encoding that is not uint16. Starts the I/O thread.
  Pca9685Bus(std::string name, std::unique_ptr<I2cTransport> transport,
             const std::vector<ActuatorModel>& actuators,
             const std::vector<double>& initial_positions, Pca9685Options options = {});
  ~Pca9685Bus() override;
  Pca9685Bus(const Pca9685Bus&) = delete;
  Pca9685Bus& operator=(const Pca9685Bus&) = delete;

  std::string_view name() const override { return name_; }
  void read(const TickTime& time, std::span<double> positions) override;
  void write(const TickTime& time, std::span<const double> positions) override;
  void set_enabled(bool enabled) override;
  // Per channel: the PCA9685 switches each output on its own.
  void set_actuators_enabled(std::span<std::uint8_t> enabled) override;
  BusStatus status() const override;

  // Boards set up and verified.
  std::size_t boards_ready() const;
  std::uint64_t cycles() const { return cycles_.load(std::memory_order_relaxed); }
  double actual_pwm_hz() const { return actual_hz_; }
  int prescale() const { return prescale_; }

 private:
  struct Command {
    std::array<double, kMaxActuators> positions{};
    std::uint64_t sequence = 0;
  };
  struct Board {
    int address = 0x40;
    std::array<std::size_t, pca9685::kChannels> actuator{};  // channel -> actuator or SIZE_MAX
    // I/O thread only.
    bool ready = false;
    bool latched = false;  // wrong readback or lost set-up: never written again
    std::int64_t next_init_ns = 0;
    std::array<pca9685::LedRegisters, pca9685::kChannels> written{};  // what the chip holds
    // Static reasons, built before they are published and never changed after.
    std::string silent, mismatch, lost;
    // Shared with the tick.
    std::atomic<const char*> reason{nullptr};
    std::atomic<bool> ready_flag{false};
  };

  void io_loop();
  bool init_board(Board& board);
  void serve_board(Board& board, std::uint64_t on_mask);
  int count(int rc);
  const char* describe_mismatch(Board& board, int prescale, int mode1);

  std::string name_;
  std::unique_ptr<I2cTransport> transport_;
  Pca9685Options options_;
  int prescale_ = 0;
  double actual_hz_ = 0.0;
  std::size_t count_ = 0;
  std::vector<WireEncoding> encodings_;  // per actuator
  std::vector<std::unique_ptr<Board>> boards_;

  // Tick side.
  LatestValueMailbox<Command> commands_;
  Command staging_;
  // One bit per actuator: output on. The bus is on while any bit is.
  std::atomic<std::uint64_t> on_mask_{0};

  // I/O thread side.
  Command current_;

  std::atomic<std::uint64_t> transfers_{0}, failures_{0}, cycles_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl
