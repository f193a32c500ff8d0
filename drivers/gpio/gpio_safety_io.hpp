#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "control/actuator_bus.hpp"
#include "drivers/gpio/gpio_chip.hpp"

namespace facectl {

struct GpioSafetyConfig {
  unsigned estop_line = 0;
  // The default suits a normally-closed e-stop contact to ground with a
  // pull-up: pressed, or a cut wire, reads high = active. Fail-safe.
  bool estop_active_low = false;
  double release_debounce_s = 0.005;  // a press is never delayed; a release must hold this long
  unsigned power_line = 1;
  bool power_active_low = false;
  int led_line = -1;  // optional status LED; -1 = none
  bool led_active_low = false;
};

// SafetyIo on GPIO lines: an e-stop input read from edge events and the
// line's level, a power-enable output, and an optional status LED (on while
// power is enabled, blinking at 2 Hz while the e-stop is active). Every call
// is non-blocking; called from the tick.
//
// The e-stop is active from the first tick that reads an active edge or
// level, even for a pulse shorter than a tick (the edge is queued; an edge
// the levels read do not account for counts as a press). It is
// released only after the line has stayed inactive for release_debounce_s,
// so contact bounce cannot release it early. An unreadable line is a fault
// and reads as pressed.
class GpioSafetyIo final : public SafetyIo {
 public:
  using Clock = std::int64_t (*)();  // monotonic ns; tests pass a simulated one

  GpioSafetyIo(GpioChip& chip, const GpioSafetyConfig& config, Clock clock = nullptr);

  bool estop_active() override;
  void set_power_enable(bool on) override;
  bool fault() const override { return fault_.load(std::memory_order_acquire); }

 private:
  GpioChip& chip_;
  GpioSafetyConfig config_;
  Clock clock_;
  int estop_ = -1;
  int power_ = -1;
  int led_ = -1;
  bool pressed_ = true;            // until the first read says otherwise
  bool last_level_active_ = true;  // the level the last read saw
  std::int64_t last_active_ns_ = 0;
  bool power_on_ = false;
  std::int64_t led_phase_ns_ = 0;
  bool led_blinking_ = false;
  std::atomic<bool> fault_{false};
};

// The real safety I/O: a libgpiod chip ("gpiochip0", a number or a path) and
// the GpioSafetyIo on it. Throws std::runtime_error naming the chip or line.
struct GpioHardware {
  std::unique_ptr<GpioChip> chip;
  std::unique_ptr<GpioSafetyIo> io;  // declared last: released before the chip
};
GpioHardware make_gpio_safety_io(const std::string& chip, const GpioSafetyConfig& config);

}  // namespace facectl
