// GPIO safety I/O over the chip interface: the simulated chip for behaviour,
// the real libgpiod v1 chip for its error path (this machine's kernel has no
// gpio-sim, so no real line can be requested here).
#include "drivers/gpio/gpio_safety_io.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "drivers/gpio/gpiod_chip.hpp"
#include "sim/devices/sim_gpio_chip.hpp"

namespace facectl {
namespace {

std::int64_t g_now = 0;
std::int64_t fake_clock() {
  return g_now;
}
constexpr std::int64_t kMs = 1'000'000;

class GpioSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    g_now = 1000 * kMs;
    chip_.set_physical(0, false);  // e-stop released (active high by default)
    cfg_.led_line = 2;
  }
  GpioSafetyIo make() { return GpioSafetyIo(chip_, cfg_, &fake_clock); }
  // One 1 kHz tick's read.
  bool tick(GpioSafetyIo& io) {
    g_now += kMs;
    return io.estop_active();
  }
  SimGpioChip chip_;
  GpioSafetyConfig cfg_;
};

TEST_F(GpioSafety, APressIsSeenOnTheFirstTickThatReadsIt) {
  GpioSafetyIo io = make();
  for (int i = 0; i < 10; ++i) tick(io);
  ASSERT_FALSE(tick(io));
  chip_.set_physical(0, true);
  EXPECT_TRUE(tick(io));
}

TEST_F(GpioSafety, APulseShorterThanATickStillTrips) {
  GpioSafetyIo io = make();
  for (int i = 0; i < 10; ++i) tick(io);
  chip_.set_physical(0, true);
  chip_.set_physical(0, false);  // pressed and bounced back between two ticks
  EXPECT_TRUE(tick(io));
}

TEST_F(GpioSafety, ReleaseWaitsForTheDebounceAndBounceRestartsIt) {
  GpioSafetyIo io = make();
  chip_.set_physical(0, true);
  ASSERT_TRUE(tick(io));
  chip_.set_physical(0, false);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(tick(io)) << "released after " << i + 1 << " ms";
  chip_.set_physical(0, true);  // contact bounce
  chip_.set_physical(0, false);
  // Still pressed on the tick that reads the bounce and for the 5 ms after it.
  int pressed_ticks = 0;
  while (tick(io) && pressed_ticks < 100) ++pressed_ticks;
  EXPECT_EQ(pressed_ticks, 5);
}

TEST_F(GpioSafety, ActiveLowWiringIsConfigurable) {
  cfg_.estop_active_low = true;
  chip_.set_physical(0, true);  // released: high through the pull-up
  GpioSafetyIo io = make();
  for (int i = 0; i < 10; ++i) tick(io);
  ASSERT_FALSE(tick(io));
  chip_.set_physical(0, false);
  EXPECT_TRUE(tick(io));
}

TEST_F(GpioSafety, PowerEnableAndLedFollowTheOutputsAndTheLedBlinksInEstop) {
  GpioSafetyIo io = make();
  EXPECT_FALSE(chip_.physical(1)) << "power must start off";
  for (int i = 0; i < 10; ++i) tick(io);
  io.set_power_enable(true);
  tick(io);
  EXPECT_TRUE(chip_.physical(1));
  EXPECT_TRUE(chip_.physical(2));
  io.set_power_enable(false);
  tick(io);
  EXPECT_FALSE(chip_.physical(1));
  EXPECT_FALSE(chip_.physical(2));
  chip_.set_physical(0, true);
  std::vector<std::int64_t> toggles;
  bool led = chip_.physical(2);
  for (int i = 0; i < 1000; ++i) {
    tick(io);
    if (chip_.physical(2) != led) toggles.push_back(g_now);
    led = chip_.physical(2);
  }
  ASSERT_GE(toggles.size(), 4u);
  for (std::size_t i = 1; i < toggles.size(); ++i) {
    EXPECT_EQ(toggles[i] - toggles[i - 1], 250 * kMs);  // 2 Hz
  }
}

TEST_F(GpioSafety, AVanishedLineIsAFaultAndReadsAsPressed) {
  GpioSafetyIo io = make();
  for (int i = 0; i < 10; ++i) tick(io);
  ASSERT_FALSE(io.fault());
  chip_.remove_line(0);
  EXPECT_TRUE(tick(io));
  EXPECT_TRUE(io.fault());
}

TEST(GpiodChip, AMissingChipIsRefusedByName) {
  try {
    GpiodChip chip("facectl-no-such-chip");
    FAIL() << "opened a chip that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("GPIO chip 'facectl-no-such-chip' cannot be opened"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace facectl
