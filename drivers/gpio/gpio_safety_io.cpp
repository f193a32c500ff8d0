#include "drivers/gpio/gpio_safety_io.hpp"

#include <array>
#include <ctime>

#include "control/clock.hpp"
#include "drivers/gpio/gpiod_chip.hpp"

namespace facectl {

namespace {
constexpr std::int64_t kBlinkHalfPeriodNs = 250'000'000;  // 2 Hz
}  // namespace

GpioSafetyIo::GpioSafetyIo(GpioChip& chip, const GpioSafetyConfig& config, Clock clock)
    : chip_(chip), config_(config), clock_(clock != nullptr ? clock : &monotonic_ns) {
  // Outputs first, both off: nothing is powered before the e-stop is read.
  power_ = chip_.request_output(config_.power_line, config_.power_active_low, false,
                                "facectl power-enable");
  if (config_.led_line >= 0) {
    led_ = chip_.request_output(static_cast<unsigned>(config_.led_line), config_.led_active_low,
                                false, "facectl status");
  }
  estop_ = chip_.request_input(config_.estop_line, config_.estop_active_low, "facectl e-stop");
  last_active_ns_ = clock_();
}

bool GpioSafetyIo::estop_active() {
  const std::int64_t now = clock_();
  std::array<GpioEdge, 16> edges;
  const int n = chip_.read_edges(estop_, edges);
  const int level = chip_.get_value(estop_);
  if (n < 0 || level < 0) {
    fault_.store(true, std::memory_order_release);
    pressed_ = true;
  } else {
    // The v1 uAPI names each edge of a both-edges request by the level its
    // interrupt thread reads (Linux 6.1 gpiolib-cdev.c, lineevent_irq_thread),
    // and an interrupt can stand for several edges (irq_sim keeps a pending
    // bit): a press shorter than that latency arrives as falling edges, or
    // one. So more edges than the change between two reads' levels mean the
    // line was active in between (tests/drivers/qemu/gpio_guest_test.cpp).
    const bool level_active = level == 1;
    bool active = level_active || n > (level_active != last_level_active_ ? 1 : 0);
    last_level_active_ = level_active;
    for (int i = 0; i < n; ++i) active = active || edges[static_cast<std::size_t>(i)].active;
    if (active) {
      pressed_ = true;
      last_active_ns_ = now;
    } else if (pressed_ &&
               static_cast<double>(now - last_active_ns_) * 1e-9 >= config_.release_debounce_s) {
      pressed_ = false;
    }
  }
  if (led_ >= 0) {
    if (pressed_) {
      // The blink starts on the press, so the LED answers it at once.
      if (!led_blinking_ || now - led_phase_ns_ >= 2 * kBlinkHalfPeriodNs) led_phase_ns_ = now;
      led_blinking_ = true;
      chip_.set_value(led_, now - led_phase_ns_ < kBlinkHalfPeriodNs);
    } else {
      led_blinking_ = false;
      chip_.set_value(led_, power_on_);
    }
  }
  return pressed_;
}

void GpioSafetyIo::set_power_enable(bool on) {
  power_on_ = on;
  if (!chip_.set_value(power_, on)) fault_.store(true, std::memory_order_release);
}

GpioHardware make_gpio_safety_io(const std::string& chip, const GpioSafetyConfig& config) {
  GpioHardware hw;
  hw.chip = std::make_unique<GpiodChip>(chip);
  hw.io = std::make_unique<GpioSafetyIo>(*hw.chip, config);
  return hw;
}

}  // namespace facectl
