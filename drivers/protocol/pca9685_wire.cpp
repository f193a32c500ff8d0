#include "drivers/protocol/pca9685_wire.hpp"

#include <algorithm>

#include "drivers/protocol/pca9685_registers.hpp"

namespace facectl {

double pca9685_block_write_bits(int channels) {
  return 2.0 + 9.0 * (2 + 4 * channels);
}

double pca9685_byte_read_bits() {
  return 3.0 + 9.0 * 4;
}

Pca9685CycleBits pca9685_cycle_bits(std::span<const int> addresses, int board_count) {
  std::map<int, std::pair<int, int>> span;  // board -> lowest, highest used channel
  for (const int a : addresses) {
    const Pca9685Placement p = pca9685_place(a, board_count);
    auto it = span.try_emplace(p.board, p.channel, p.channel).first;
    it->second.first = std::min(it->second.first, p.channel);
    it->second.second = std::max(it->second.second, p.channel);
  }
  Pca9685CycleBits out;
  // Every listed board is read back each cycle, even one with no actuator.
  for (int board = 0; board < board_count; ++board) {
    if (const auto it = span.find(board); it != span.end()) {
      const auto [lo, hi] = it->second;
      for (int first = lo; first <= hi; first += 8) {
        out.total += pca9685_block_write_bits(std::min(8, hi - first + 1));
      }
      out.written[board] = out.total;
    }
    out.total += pca9685_byte_read_bits();
  }
  return out;
}

}  // namespace facectl
