#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace facectl::sim {

// A Pololu Maestro as its user's guide describes it (https://www.pololu.com/
// docs/0J40): the serial command parser of section 5 (compact and Pololu
// protocols on the same line, a Pololu packet for another device number
// ignored, a command byte interrupting a packet a protocol error), the
// servo commands of 5.e (Set Target with 0 = no pulses, clamped to the
// channel's range; Set Speed in 0.25 µs per 10 ms; Set Multiple Targets on
// the Mini Maestros only; Get Position; Get Errors, which clears the
// register), the error register of 4.e with "outputs go home" on an error,
// and the serial timeout of 4.b. Not thread-safe: MaestroPtyWire serialises
// every call. Acceleration is stored but not applied.
class MaestroSim {
 public:
  // `channels`: 6 (Micro Maestro), 12, 18 or 24 (Mini Maestro).
  explicit MaestroSim(int channels = 12, int device_number = 12);

  // One byte from the line at `now_ns`; replies are appended to `reply`.
  void feed(std::uint8_t byte, std::int64_t now_ns, std::vector<std::uint8_t>& reply);
  // Time passes: speed limits and the serial timeout.
  void advance(std::int64_t now_ns);

  // The range Set Target clamps to (Control Center's Min/Max), quarter-µs;
  // the factory's is 992..2000 µs.
  void set_range(int channel, int min_q, int max_q);
  // Control Center's serial timeout (0 = off).
  void set_serial_timeout_ms(int ms) { serial_timeout_ms_ = ms; }
  // As if the Maestro had detected these errors (4.e): the bits are set and
  // every output goes home (here: off).
  void raise_error(std::uint16_t bits);
  // Power lost and back: no pulses, no errors, no packet half received.
  void power_cycle();

  int channels() const { return channels_; }
  int target(int channel) const { return targets_.at(static_cast<std::size_t>(channel)); }
  int position(int channel) const;  // quarter-µs being sent, 0: no pulses
  int speed(int channel) const { return speeds_.at(static_cast<std::size_t>(channel)); }
  std::uint16_t errors() const { return errors_; }
  std::uint64_t commands(std::uint8_t command) const { return counts_[command]; }

 private:
  void execute(std::int64_t now_ns, std::vector<std::uint8_t>& reply);
  int data_bytes_needed() const;
  void go_home();

  int channels_;
  int device_number_;
  std::array<int, 24> targets_{};
  std::array<double, 24> positions_{};
  std::array<int, 24> speeds_{}, accelerations_{}, min_q_{}, max_q_{};
  std::uint16_t errors_ = 0;
  int serial_timeout_ms_ = 0;
  std::int64_t last_command_ns_ = 0;
  std::int64_t last_ns_ = -1;
  // The packet being received.
  enum class Stage { kIdle, kDevice, kCommand, kData, kIgnore } stage_ = Stage::kIdle;
  std::uint8_t command_ = 0;
  std::vector<std::uint8_t> data_;
  std::array<std::uint64_t, 256> counts_{};
};

}  // namespace facectl::sim
