#pragma once

#include <array>
#include <cstdint>

// The NXP PCA9685 16-channel, 12-bit PWM controller's register map and the
// arithmetic on it (NXP PCA9685 product data sheet, rev. 4, sections 7.3 and
// 7.3.5; register numbers as in Linux's drivers/pwm/pwm-pca9685.c and
// Adafruit_PWMServoDriver). No I/O: shared by the driver and its twin.
namespace facectl::pca9685 {

inline constexpr std::uint8_t kMode1 = 0x00;
inline constexpr std::uint8_t kMode2 = 0x01;
inline constexpr std::uint8_t kLed0OnL = 0x06;  // LEDn_ON_L = 6 + 4n, then ON_H, OFF_L, OFF_H
inline constexpr std::uint8_t kAllLedOnL = 0xFA;
inline constexpr std::uint8_t kAllLedOffH = 0xFD;
inline constexpr std::uint8_t kPreScale = 0xFE;

// MODE1 bits.
inline constexpr std::uint8_t kMode1Restart = 0x80;
inline constexpr std::uint8_t kMode1ExtClk = 0x40;
inline constexpr std::uint8_t kMode1AutoIncrement = 0x20;
inline constexpr std::uint8_t kMode1Sleep = 0x10;
inline constexpr std::uint8_t kMode1AllCall = 0x01;
inline constexpr std::uint8_t kMode1PowerOn = 0x11;  // SLEEP | ALLCALL after power-on reset
// MODE2: OUTDRV = totem-pole outputs, what a servo's signal input wants.
inline constexpr std::uint8_t kMode2OutDrv = 0x04;

// Bit 4 of LEDn_ON_H / LEDn_OFF_H: full on / full off (full off wins).
inline constexpr std::uint8_t kLedFull = 0x10;

inline constexpr int kChannels = 16;
inline constexpr double kOscillatorHz = 25e6;  // internal oscillator
inline constexpr int kPreScaleMin = 3;         // the chip forces lower values to 3
inline constexpr int kPreScaleMax = 255;
inline constexpr int kPreScalePowerOn = 0x1E;  // 200 Hz
inline constexpr int kCountsPerPeriod = 4096;
inline constexpr double kWakeUpS = 500e-6;  // oscillator start-up after SLEEP is cleared
// First and last 7-bit addresses the A0..A5 pins give (0x70 is the
// power-on ALLCALL address; the application decides whether to use it).
inline constexpr int kFirstAddress = 0x40;
inline constexpr int kLastAddress = 0x7F;

constexpr std::uint8_t led_on_l(int channel) {
  return static_cast<std::uint8_t>(kLed0OnL + 4 * channel);
}

// PRE_SCALE for a PWM frequency: round(25 MHz / (4096 · f)) − 1 (data sheet
// eq. 1), clamped to 3..255.
int prescale_for(double pwm_hz);
// The frequency a prescale actually gives: 25 MHz / (4096 · (prescale + 1)).
double frequency_of(int prescale);

// The four LEDn registers (ON_L, ON_H, OFF_L, OFF_H) of one channel.
using LedRegisters = std::array<std::uint8_t, 4>;

// The OFF count for a pulse of `pulse_us` at the actual frequency, the output
// going high at count 0: round(pulse · f · 4096), clamped to 0..4095.
int off_count(double pulse_us, double actual_hz);
// A pulse: ON = 0, OFF = off_count.
LedRegisters pulse_registers(double pulse_us, double actual_hz);
// The output held low (OFF_H full-off bit): a servo without a signal goes limp.
LedRegisters full_off_registers();
// The pulse width the registers give, in µs; 0 when full off.
double pulse_us_of(const LedRegisters& r, double actual_hz);

}  // namespace facectl::pca9685
