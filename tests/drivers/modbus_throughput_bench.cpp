// Modbus TCP on loopback: transactions per second of the ModbusBus I/O thread
// against a bare libmodbus client loop, both talking to the same simulated
// boards on the same server, in interleaved rounds of one run.
// Usage: facectl_modbus_bench [rounds] [seconds_per_round]
#include <modbus/modbus.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "drivers/modbus/modbus_bus.hpp"
#include "sim/devices/modbus_board_server.hpp"

using namespace facectl;
using Clock = std::chrono::steady_clock;

namespace {

std::vector<sim::BoardChannel> channels(std::size_t n) {
  std::vector<sim::BoardChannel> c(n);
  for (auto& ch : c) ch.plant.latency_s = 0.0;
  return c;
}

// The same work as the driver below: cycles back to back; in each, per board,
// a write-multiple of CONTROL, HEARTBEAT and the targets when a new 1 kHz
// command is due, and one read of the input registers.
double bare_loop(int port, double seconds) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  modbus_set_response_timeout(ctx, 0, 20'000);
  if (modbus_connect(ctx) != 0) {
    std::fprintf(stderr, "bare client: connect failed\n");
    std::exit(1);
  }
  std::uint16_t regs[10] = {1};
  std::uint16_t in[12];
  const int channels_of[2] = {8, 6};
  std::uint64_t ok = 0;
  const auto t0 = Clock::now();
  const auto end = t0 + std::chrono::duration<double>(seconds);
  auto next_command = t0;
  while (true) {
    const auto now = Clock::now();
    if (now >= end) break;
    const bool fresh = now >= next_command;
    if (fresh) {
      next_command += std::chrono::milliseconds(1);
      ++regs[1];
    }
    for (int b = 0; b < 2; ++b) {
      modbus_set_slave(ctx, b + 1);
      if (fresh && modbus_write_registers(ctx, 0, 2 + channels_of[b], regs) > 0) ++ok;
      if (modbus_read_input_registers(ctx, 0, 4 + channels_of[b], in) > 0) ++ok;
    }
  }
  const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
  modbus_close(ctx);
  modbus_free(ctx);
  return static_cast<double>(ok) / dt;
}

// The driver runs back to back (cycle_period_s = 0) while this thread plays
// the 1 kHz tick, publishing fresh targets every millisecond.
double driver_loop(int port, double seconds, double& writes_share) {
  std::vector<ActuatorModel> acts(14);
  for (int i = 0; i < 14; ++i) acts[static_cast<std::size_t>(i)].address = i + 1;
  ModbusEndpoint ep;
  ep.port = port;
  ModbusTiming timing;
  timing.cycle_period_s = 0.0;
  ModbusBus bus("bench", ep, acts, std::vector<double>(14, 0.0), timing);
  bus.set_enabled(true);
  std::vector<double> cmd(14, 0.0);
  // Let it connect before counting.
  while (bus.stats().transactions < 10) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const ModbusStats s0 = bus.stats();
  const auto t0 = Clock::now();
  const auto end = t0 + std::chrono::duration<double>(seconds);
  double x = 0.0;
  auto next = t0;
  while (Clock::now() < end) {
    x += 1e-4;
    for (auto& c : cmd) c = x;
    bus.write({}, cmd);
    next += std::chrono::milliseconds(1);
    std::this_thread::sleep_until(next);
  }
  const ModbusStats s1 = bus.stats();
  const double dt = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cycles = static_cast<double>(s1.cycles - s0.cycles);
  const double tx = static_cast<double>(s1.transactions - s0.transactions);
  // Reads are 2 per cycle; whatever is left were writes.
  writes_share = cycles > 0 ? (tx - 2.0 * cycles) / (2.0 * cycles) : 0.0;
  if (s1.failures != s0.failures)
    std::fprintf(stderr, "driver: %llu failures\n",
                 static_cast<unsigned long long>(s1.failures - s0.failures));
  return tx / dt;
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 5;
  const double seconds = argc > 2 ? std::atof(argv[2]) : 2.0;
  sim::ModbusActuatorBoard b1{1, channels(8)};
  sim::ModbusActuatorBoard b2{2, channels(6)};
  auto server = sim::ModbusBoardServer::tcp({&b1, &b2});
  std::printf("Modbus TCP loopback, 2 boards (8 + 6 channels), %d rounds of %.1f s each\n", rounds,
              seconds);
  std::printf("%-6s %14s %14s %8s %12s\n", "round", "bare tx/s", "driver tx/s", "ratio",
              "cycles w/ write");
  double sum_bare = 0.0;
  double sum_driver = 0.0;
  std::vector<double> ratios;
  for (int r = 0; r < rounds; ++r) {
    const double bare = bare_loop(server->port(), seconds);
    double share = 0.0;
    const double drv = driver_loop(server->port(), seconds, share);
    sum_bare += bare;
    sum_driver += drv;
    ratios.push_back(drv / bare);
    std::printf("%-6d %14.0f %14.0f %8.3f %11.0f%%\n", r + 1, bare, drv, drv / bare, 100.0 * share);
  }
  std::printf("mean   %14.0f %14.0f %8.3f\n", sum_bare / rounds, sum_driver / rounds,
              sum_driver / sum_bare);
  // Other processes share the CPUs: the median of the per-round ratios is the
  // figure least moved by a round that one of them disturbed.
  std::sort(ratios.begin(), ratios.end());
  const std::size_t n = ratios.size();
  const double median = n % 2 == 1 ? ratios[n / 2] : 0.5 * (ratios[n / 2 - 1] + ratios[n / 2]);
  std::printf("median ratio (driver / bare) %.3f, min %.3f, max %.3f\n", median, ratios.front(),
              ratios.back());
  return 0;
}
