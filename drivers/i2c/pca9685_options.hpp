#pragma once

#include <vector>

namespace facectl {

// A PCA9685 bus's settings (docs/CONFIG.md, "PCA9685 buses"). An actuator's
// rig address n (1-based) is channel (n − 1) % 16 of board (n − 1) / 16 in
// `boards`: addresses 1..16 are the first board's channels 0..15, 17..32 the
// second's.
struct Pca9685Options {
  std::vector<int> boards = {0x40};  // 7-bit I2C addresses, 0x40..0x7F
  double pwm_hz = 50.0;              // asked for; the prescale gives the actual one
  // I/O cycle; 0 = one PWM period (the servo samples its pulse once a period,
  // so writing more often changes nothing).
  double cycle_period_s = 0.0;
  long i2c_hz = 100'000;      // the adapter's SCL clock (set by the kernel), for the budget
  double retry_init_s = 1.0;  // a board not answering at start-up is tried again this often
};

// The I/O cycle: cycle_period_s, or one period of the actual PWM frequency.
double pca9685_cycle_period_s(const Pca9685Options& options);

struct Pca9685Placement {
  int board = 0;    // index into Pca9685Options::boards
  int channel = 0;  // 0..15
};

// Throws std::invalid_argument naming the address when it is outside
// 1..16 · board_count.
Pca9685Placement pca9685_place(int address, int board_count);

}  // namespace facectl
