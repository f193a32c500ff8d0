#include "drivers/i2c/pca9685_options.hpp"

#include <stdexcept>
#include <string>

#include "drivers/protocol/pca9685_registers.hpp"

namespace facectl {

double pca9685_cycle_period_s(const Pca9685Options& options) {
  if (options.cycle_period_s > 0.0) return options.cycle_period_s;
  return 1.0 / pca9685::frequency_of(pca9685::prescale_for(options.pwm_hz));
}

Pca9685Placement pca9685_place(int address, int board_count) {
  if (address < 1 || address > pca9685::kChannels * board_count) {
    throw std::invalid_argument("PCA9685 address " + std::to_string(address) + ": expected 1.." +
                                std::to_string(pca9685::kChannels * board_count) + " (" +
                                std::to_string(board_count) + " board(s) of 16 channels)");
  }
  return {(address - 1) / pca9685::kChannels, (address - 1) % pca9685::kChannels};
}

}  // namespace facectl
