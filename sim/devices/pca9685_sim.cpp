#include "sim/devices/pca9685_sim.hpp"

namespace facectl::sim {

using namespace ::facectl::pca9685;

void Pca9685Sim::power_on() {
  regs_.fill(0);
  regs_[kMode1] = kMode1PowerOn;
  regs_[kMode2] = kMode2OutDrv;
  regs_[0x02] = 0xE2;  // SUBADR1..3, ALLCALLADR
  regs_[0x03] = 0xE4;
  regs_[0x04] = 0xE8;
  regs_[0x05] = 0xE0;
  for (int ch = 0; ch < kChannels; ++ch) regs_[led_on_l(ch) + 3] = kLedFull;  // outputs off
  regs_[kPreScale] = kPreScalePowerOn;
}

std::uint8_t Pca9685Sim::next(std::uint8_t reg) {
  if (reg == 0x45 || reg >= 0xFE) return 0x00;
  return static_cast<std::uint8_t>(reg + 1);
}

void Pca9685Sim::write(std::uint8_t reg, std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t b : bytes) {
    const bool ai = (regs_[kMode1] & kMode1AutoIncrement) != 0;
    write_one(reg, b);
    if (ai) reg = next(reg);
  }
}

void Pca9685Sim::write_one(std::uint8_t reg, std::uint8_t value) {
  if (reg == kMode1) {
    // EXTCLK is sticky until power-off; RESTART is handled below.
    int v = (value & ~kMode1Restart) | (regs_[kMode1] & kMode1ExtClk);
    // RESTART: set when sleep starts with any output running, cleared by a 1.
    bool restart = (regs_[kMode1] & kMode1Restart) != 0 && (value & kMode1Restart) == 0;
    if ((value & kMode1Sleep) != 0 && !sleeping()) {
      for (int ch = 0; ch < kChannels; ++ch) restart = restart || !full_off(ch);
    }
    if (restart) v |= kMode1Restart;
    regs_[kMode1] = static_cast<std::uint8_t>(v);
    return;
  }
  if (reg == kPreScale) {
    if (sleeping() && !ignore_prescale_) {
      regs_[kPreScale] = value < kPreScaleMin ? kPreScaleMin : value;
    }
    return;
  }
  if (reg >= kAllLedOnL && reg <= kAllLedOffH) {
    for (int ch = 0; ch < kChannels; ++ch) regs_[led_on_l(ch) + (reg - kAllLedOnL)] = value;
    return;
  }
  if (reg == 0xFF) return;  // TestMode: reserved
  regs_[reg] = value;
}

std::uint8_t Pca9685Sim::read(std::uint8_t reg) const {
  if (reg >= kAllLedOnL && reg <= kAllLedOffH) return 0;  // write-only, read as 0
  return regs_[reg];
}

LedRegisters Pca9685Sim::led(int channel) const {
  const int r = led_on_l(channel);
  return {regs_[r], regs_[r + 1], regs_[r + 2], regs_[r + 3]};
}

double Pca9685Sim::pulse_us(int channel) const {
  if (sleeping()) return 0.0;
  return pulse_us_of(led(channel), actual_hz());
}

}  // namespace facectl::sim
