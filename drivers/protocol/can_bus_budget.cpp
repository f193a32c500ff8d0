#include "drivers/protocol/can_bus_budget.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace facectl {

CanBusBudget CanBusBudget::compute(int frames_per_cycle, double cycle_hz, long bitrate) {
  return compute_bits(frames_per_cycle, frames_per_cycle * kBitsPerFrame, cycle_hz, bitrate);
}

CanBusBudget CanBusBudget::compute_bits(int frames_per_cycle, double bits_per_cycle,
                                        double cycle_hz, long bitrate) {
  CanBusBudget b;
  b.frames_per_cycle = frames_per_cycle;
  b.bits_per_cycle = bits_per_cycle;
  b.cycle_hz = cycle_hz;
  b.bitrate = bitrate;
  b.load = bitrate > 0 ? bits_per_cycle * cycle_hz / static_cast<double>(bitrate) : 1e9;
  return b;
}

std::string CanBusBudget::describe(const std::string& bus) const {
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "%s: %d frames per cycle at %g Hz = %.0f bit/s, %.1f%% of %ld bit/s%s", bus.c_str(),
                frames_per_cycle, cycle_hz, bits_per_cycle * cycle_hz, 100.0 * load, bitrate,
                refused()  ? " (refused: above 70%)"
                : warned() ? " (warning: above 50%)"
                           : "");
  return buf;
}

int can_fd_length(int bytes) {
  if (bytes <= 8) return std::max(bytes, 0);
  for (int len : {12, 16, 20, 24, 32, 48}) {
    if (bytes <= len) return len;
  }
  return 64;
}

double can_fd_frame_bits(int bytes, long bitrate, long data_bitrate) {
  const int n = can_fd_length(bytes);
  const double nominal = 17.0 + 4.0 + 13.0;
  const double stuffable = 5.0 + 8.0 * n;  // ESI, DLC, data
  const double crc = n <= 16 ? 17.0 : 21.0;
  const double data = stuffable + std::ceil(stuffable / 4.0) + 5.0 + crc + std::ceil(crc / 4.0);
  const double ratio =
      data_bitrate > 0 ? static_cast<double>(bitrate) / static_cast<double>(data_bitrate) : 1.0;
  return nominal + data * ratio;
}

std::map<int, int> custom_can_boards(std::span<const int> addresses, const CanBusOptions& options) {
  const int per_frame = custom_can::channels_per_frame(options.fd, options.width);
  std::map<int, int> channels;
  for (int a : addresses) {
    const int node = (a - 1) / per_frame + 1;
    channels[node] = std::max(channels[node], (a - 1) % per_frame + 1);
  }
  return channels;
}

double custom_can_frame_bits(int channels, const CanBusOptions& options, long bitrate) {
  if (!options.fd) return CanBusBudget::kBitsPerFrame;
  const long data_bitrate = options.data_bitrate > 0 ? options.data_bitrate : bitrate;
  // Command and feedback carry the same 2 + channels·width bytes.
  return can_fd_frame_bits(2 + channels * static_cast<int>(options.width), bitrate, data_bitrate);
}

CanBusBudget custom_can_budget(std::span<const int> addresses, const CanBusOptions& options,
                               double tick_hz, long bitrate) {
  const std::map<int, int> channels = custom_can_boards(addresses, options);
  const int frames = static_cast<int>(2 * channels.size());
  const double bus_hz = tick_hz / options.cycle_divider;
  if (!options.fd) return CanBusBudget::compute(frames, bus_hz, bitrate);
  double bits = 0.0;
  for (const auto& [node, used] : channels) {
    bits += 2.0 * custom_can_frame_bits(used, options, bitrate);
  }
  return CanBusBudget::compute_bits(frames, bits, bus_hz, bitrate);
}

CanBusBudget cia402_budget(std::size_t drives, const CanBusOptions& options, double tick_hz,
                           long bitrate) {
  const double bus_hz = tick_hz / options.cycle_divider;
  const double n = static_cast<double>(drives);
  const double heartbeats_per_s =
      n * 1000.0 / options.drive_heartbeat_ms + 1000.0 / options.host_heartbeat_ms;
  const double frames = 1.0 + 2.0 * n + heartbeats_per_s / bus_hz;
  return CanBusBudget::compute(static_cast<int>(std::ceil(frames)), bus_hz, bitrate);
}

}  // namespace facectl
