// Runs inside the QEMU guest, whose kernel has the GPIO simulator gpio-sim
// (built out of tree by build_gpio_sim.sh and loaded by run_in_qemu.sh):
// GpioSafetyIo over the real libgpiod chip, on a gpio-sim chip made through
// configfs. The e-stop line is driven from the simulator's side (its `pull`
// attribute, which raises the line's interrupt as a wired switch would) and
// the power-enable output is read there (its `value` attribute).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>

#include "drivers/gpio/gpio_safety_io.hpp"
#include "drivers/gpio/gpiod_chip.hpp"
#include "tests/drivers/qemu/gpio_sim_configfs.hpp"

namespace facectl {
namespace {

using Clock = std::chrono::steady_clock;
using testing::GpioSimDevice;

constexpr unsigned kEstop = 0;
constexpr unsigned kPower = 1;

class GpioInGuest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (access(testing::kGpioSimModule, F_OK) != 0) {
      GTEST_SKIP() << "gpio-sim not built (packages linux-source-6.1, linux-headers-amd64)";
    }
    ASSERT_EQ(access(testing::kGpioSimConfigfs, F_OK), 0)
        << "gpio-sim.ko is here but " << testing::kGpioSimConfigfs << " is not: it did not load";
    cfg_.estop_line = kEstop;  // active high: pressed pulls the line up
    cfg_.power_line = kPower;
    cfg_.release_debounce_s = 0.1;  // long against the emulated guest's scheduling
  }
  // Ticks at about 1 kHz until the e-stop reads released; false after `limit`.
  static bool released_within(GpioSafetyIo& io, std::chrono::milliseconds limit) {
    const auto end = Clock::now() + limit;
    while (Clock::now() < end) {
      if (!io.estop_active()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
  }
  // The e-stop released and power-enable on, as in RUNNING.
  static void power_up(GpioSafetyIo& io, GpioSimDevice& sim) {
    ASSERT_TRUE(released_within(io, std::chrono::seconds(2)));
    io.set_power_enable(true);
    ASSERT_EQ(sim.level(kPower), 1);
    ASSERT_FALSE(io.fault());
  }
  GpioSafetyConfig cfg_;
};

TEST_F(GpioInGuest, RequestsItsLinesAndDrivesPowerEnable) {
  GpioSimDevice sim("facectl-lines");
  GpiodChip chip(sim.name());
  GpioSafetyIo io(chip, cfg_);
  EXPECT_EQ(sim.level(kPower), 0) << "power-enable is requested off";
  // The kernel holds the lines for facectl: nobody else may request them.
  GpiodChip other(sim.name());
  EXPECT_THROW(other.request_input(kEstop, false, "intruder"), std::runtime_error);
  EXPECT_THROW(other.request_output(kPower, false, true, "intruder"), std::runtime_error);
  EXPECT_EQ(sim.level(kPower), 0);

  power_up(io, sim);
  io.set_power_enable(false);
  EXPECT_EQ(sim.level(kPower), 0);
  EXPECT_FALSE(io.fault());
}

// The press the controller must see: a pulse that is over before the next
// tick reads the line is still seen, from the edge the kernel queued, and the
// power output the tick then drops is off at the pin.
TEST_F(GpioInGuest, APulseBetweenTwoTicksTripsAndPowerDrops) {
  GpioSimDevice sim("facectl-press");
  GpiodChip chip(sim.name());
  GpioSafetyIo io(chip, cfg_);
  power_up(io, sim);
  for (int i = 0; i < 20; ++i) ASSERT_FALSE(io.estop_active());

  sim.drive(kEstop, true);
  sim.drive(kEstop, false);  // released again before any tick
  EXPECT_EQ(sim.level(kEstop), 0);
  // The kernel queues the pulse's edge from its interrupt work, which an
  // emulated CPU may run a little later: the pulse must be seen within a
  // few 1 ms ticks, not necessarily on the first read.
  bool pressed = false;
  int ticks = 0;
  for (; ticks < 50 && !pressed; ++ticks) {
    pressed = io.estop_active();
    if (!pressed) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_TRUE(pressed) << "the pulse was lost";
  std::printf("FACECTL-QEMU: gpio: a pulse between two ticks seen on tick %d\n", ticks);
  if (pressed) io.set_power_enable(false);  // what the controller does in ESTOP
  EXPECT_EQ(sim.level(kPower), 0);
  EXPECT_FALSE(io.fault());
}

// Contact bounce on release: the line goes inactive, bounces active for
// less than a tick, and goes inactive again. The e-stop must stay pressed
// until the line has held inactive for the debounce time after the bounce.
TEST_F(GpioInGuest, AReleaseBounceRestartsTheDebounce) {
  GpioSimDevice sim("facectl-bounce");
  GpiodChip chip(sim.name());
  GpioSafetyIo io(chip, cfg_);
  sim.drive(kEstop, true);
  ASSERT_TRUE(io.estop_active());

  const auto release = Clock::now();
  sim.drive(kEstop, false);
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  EXPECT_TRUE(io.estop_active()) << "released before the debounce";
  const auto bounce = Clock::now();
  sim.drive(kEstop, true);
  sim.drive(kEstop, false);
  ASSERT_TRUE(released_within(io, std::chrono::seconds(3)));
  const auto held = Clock::now() - bounce;
  const double held_ms = std::chrono::duration<double, std::milli>(held).count();
  std::printf(
      "FACECTL-QEMU: gpio: released %.1f ms after the bounce, %.1f ms after the first release\n",
      held_ms, std::chrono::duration<double, std::milli>(Clock::now() - release).count());
  EXPECT_GE(held_ms, 100.0) << "the bounce did not restart the debounce";
  EXPECT_LT(held_ms, 1000.0);
}

// The chip goes away under a held request (gpio-sim's device taken down, as
// an unplugged USB GPIO adapter would): a fault, the e-stop reads pressed, and
// driving power-enable on fails rather than passing silently.
TEST_F(GpioInGuest, TheChipVanishingIsAFaultThatReadsPressed) {
  GpioSimDevice sim("facectl-vanish");
  GpiodChip chip(sim.name());
  GpioSafetyIo io(chip, cfg_);
  power_up(io, sim);

  const std::string dev = "/dev/" + sim.name();
  sim.vanish();
  EXPECT_NE(access(dev.c_str(), F_OK), 0) << dev << " is still there";
  EXPECT_TRUE(io.estop_active());
  EXPECT_TRUE(io.fault());
  io.set_power_enable(false);  // the controller's reaction to the fault
  EXPECT_TRUE(io.fault()) << "a fault latches";
  EXPECT_THROW(GpiodChip{sim.name()}, std::runtime_error);
}

}  // namespace
}  // namespace facectl
