// The PCA9685 register arithmetic against the NXP data sheet's formulas,
// worked by hand: prescale = round(25 MHz / (4096 · f)) − 1, clamped 3..255.
#include "drivers/protocol/pca9685_registers.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "drivers/i2c/pca9685_options.hpp"

namespace facectl {
namespace {

using namespace pca9685;

TEST(Pca9685Registers, MapMatchesTheDataSheet) {
  EXPECT_EQ(kMode1, 0x00);
  EXPECT_EQ(kMode2, 0x01);
  EXPECT_EQ(led_on_l(0), 0x06);
  EXPECT_EQ(led_on_l(15), 0x42);  // LED15_ON_L; LED15_OFF_H is 0x45
  EXPECT_EQ(kAllLedOnL, 0xFA);
  EXPECT_EQ(kAllLedOffH, 0xFD);
  EXPECT_EQ(kPreScale, 0xFE);
}

TEST(Pca9685Registers, PrescaleFromFrequency) {
  EXPECT_EQ(prescale_for(50.0), 121);    // 122.07 -> 122 - 1
  EXPECT_EQ(prescale_for(200.0), 0x1E);  // the power-on value is 200 Hz
  EXPECT_EQ(prescale_for(60.0), 101);    // 101.73 -> 102 - 1
  EXPECT_EQ(prescale_for(1526.0), 3);    // the fastest the chip runs
  EXPECT_EQ(prescale_for(5000.0), 3);    // clamped up
  EXPECT_EQ(prescale_for(24.0), 253);    // 254.31 -> 254 - 1
  EXPECT_EQ(prescale_for(10.0), 255);    // clamped down
  EXPECT_EQ(prescale_for(0.0), 255);
  EXPECT_EQ(prescale_for(std::nan("")), 255);
}

TEST(Pca9685Registers, ActualFrequencyIsWhatThePrescaleGives) {
  EXPECT_NEAR(frequency_of(121), 50.0288, 1e-4);  // 25e6 / (4096 · 122)
  EXPECT_NEAR(frequency_of(3), 1525.88, 1e-2);
}

TEST(Pca9685Registers, PulseCountsUseTheActualFrequency) {
  const double f = frequency_of(121);
  // 1500 µs · 50.0288 Hz · 4096 = 307.38; at exactly 50 Hz it would be 307.2.
  EXPECT_EQ(off_count(1500, f), 307);
  EXPECT_EQ(off_count(1800, f), 369);  // 368.85
  EXPECT_EQ(off_count(600, f), 123);   // 122.95
  EXPECT_EQ(off_count(2400, f), 492);  // 491.80
  EXPECT_EQ(off_count(-5, f), 0);
  EXPECT_EQ(off_count(std::nan(""), f), 0);
  EXPECT_EQ(off_count(1e6, f), 4095);  // a whole period and more: never wraps
  const LedRegisters r = pulse_registers(2400, f);
  EXPECT_EQ(r, (LedRegisters{0x00, 0x00, 0xEC, 0x01}));  // OFF = 492 = 0x1EC
  EXPECT_NEAR(pulse_us_of(r, f), 2400.0, 1e6 / f / 4096);
}

TEST(Pca9685Registers, FullOffIsBit4OfOffH) {
  const LedRegisters r = full_off_registers();
  EXPECT_EQ(r[3], 0x10);
  EXPECT_EQ(pulse_us_of(r, 50.0), 0.0);
  EXPECT_EQ(pulse_us_of(LedRegisters{0, 0x10, 0, 0}, 50.0), 20000.0);  // full on
}

TEST(Pca9685Placement, SixteenChannelsPerBoardInListOrder) {
  EXPECT_EQ(pca9685_place(1, 2).board, 0);
  EXPECT_EQ(pca9685_place(1, 2).channel, 0);
  EXPECT_EQ(pca9685_place(16, 2).channel, 15);
  EXPECT_EQ(pca9685_place(17, 2).board, 1);
  EXPECT_EQ(pca9685_place(17, 2).channel, 0);
  EXPECT_THROW(pca9685_place(0, 2), std::invalid_argument);
  EXPECT_THROW(pca9685_place(33, 2), std::invalid_argument);
}

}  // namespace
}  // namespace facectl
