#include "drivers/protocol/pca9685_registers.hpp"

#include <algorithm>
#include <cmath>

namespace facectl::pca9685 {

int prescale_for(double pwm_hz) {
  if (!(pwm_hz > 0.0)) return kPreScaleMax;  // NaN or nonsense: the slowest, never a division by 0
  const double p = std::round(kOscillatorHz / (kCountsPerPeriod * pwm_hz)) - 1.0;
  return static_cast<int>(std::clamp(p, double{kPreScaleMin}, double{kPreScaleMax}));
}

double frequency_of(int prescale) {
  return kOscillatorHz / (kCountsPerPeriod * (static_cast<double>(prescale) + 1.0));
}

int off_count(double pulse_us, double actual_hz) {
  const double c = std::round(pulse_us * 1e-6 * actual_hz * kCountsPerPeriod);
  if (!(c >= 0.0)) return 0;  // also NaN: no pulse rather than a wrapped one
  return static_cast<int>(std::min(c, double{kCountsPerPeriod - 1}));
}

LedRegisters pulse_registers(double pulse_us, double actual_hz) {
  const int off = off_count(pulse_us, actual_hz);
  return {0, 0, static_cast<std::uint8_t>(off & 0xFF), static_cast<std::uint8_t>(off >> 8)};
}

LedRegisters full_off_registers() {
  return {0, 0, 0, kLedFull};
}

double pulse_us_of(const LedRegisters& r, double actual_hz) {
  if ((r[3] & kLedFull) != 0) return 0.0;
  const int on = r[0] | ((r[1] & 0x0F) << 8);
  const int off = r[2] | ((r[3] & 0x0F) << 8);
  if ((r[1] & kLedFull) != 0) return 1e6 / actual_hz;
  const int high = (off - on + kCountsPerPeriod) % kCountsPerPeriod;
  return high * 1e6 / (actual_hz * kCountsPerPeriod);
}

}  // namespace facectl::pca9685
