#pragma once

#include <map>
#include <span>

#include "drivers/i2c/pca9685_options.hpp"

namespace facectl {

// I2C wire time of one Pca9685Bus cycle when every used channel changes
// (docs/PROTOCOLS.md, "PCA9685"). Each byte is 9 SCL clocks (8 bits and
// the ACK), START, repeated START and STOP about one clock each:
// - per board, SMBus I2C-block writes of up to 8 channels (32 bytes) from
//   its lowest to its highest used channel: START, address, register,
//   4 bytes per channel, STOP;
// - per listed board, the MODE1 read-back: START, address, register, repeated
//   START, address, data, STOP.
struct Pca9685CycleBits {
  double total = 0.0;
  std::map<int, double> written;  // board index -> clocks until the end of its last write
};

Pca9685CycleBits pca9685_cycle_bits(std::span<const int> addresses, int board_count);

// Clocks of an SMBus I2C-block write of `channels` channels, and of a byte read.
double pca9685_block_write_bits(int channels);
double pca9685_byte_read_bits();

}  // namespace facectl
