// CAN encode and send for the default rig's 12 CAN axes, per cycle: the
// tick's whole share of the bus work (write() encodes and sends every frame).
// The transport is the in-process MemoryCanLink drained by the benchmark, so
// this measures the driver's code; the SocketCAN send() system call cost is
// recorded separately (docs/PERFORMANCE.md).
#include <benchmark/benchmark.h>

#include <memory>

#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/memory_can_link.hpp"

namespace facectl {
namespace {

std::vector<ActuatorModel> default_rig_can_axes() {
  std::vector<ActuatorModel> a(12);
  for (int i = 0; i < 12; ++i) {
    a[static_cast<std::size_t>(i)].name = "axis" + std::to_string(i + 1);
    a[static_cast<std::size_t>(i)].address = i + 1;
    a[static_cast<std::size_t>(i)].limits.position_min = -1.0;
    a[static_cast<std::size_t>(i)].limits.position_max = 1.0;
    a[static_cast<std::size_t>(i)].limits.max_velocity = 5.0;
  }
  return a;
}

void drain(MemoryCanLink& link) {
  CanFrame f;
  CanError e;
  while (link.devices().receive(f, e)) {
  }
}

// Brings CiA 402 drives to "operation enabled" with simulated drives, so the
// measured cycles are the steady state (12 RPDOs and a SYNC); custom boards
// need no warm-up.
void warm_up(Cia402Bus& bus, MemoryCanLink& link, std::int64_t& now) {
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 12; ++n) {
    drives.push_back(std::make_unique<sim::Cia402DriveSim>(n, sim::ServoPlantParams{}, 1.0, 0.0));
    devices.push_back(drives.back().get());
  }
  sim::CanDeviceNetwork net(link.devices(), devices);
  std::vector<double> cmd(12, 0.0), meas(12);
  for (int k = 0; k < 300; ++k) {
    now += 1'000'000;
    bus.read({now, 0.001}, meas);
    bus.write({now, 0.001}, cmd);
    net.poll(now);
  }
  if (drives[11]->state() != cia402::DriveState::kOperationEnabled) std::abort();
  drain(link);
}
void warm_up(CustomCanBus&, MemoryCanLink&, std::int64_t&) {}

template <typename Bus>
void encode_and_send(benchmark::State& state) {
  constexpr int kDrainEvery = 1024;  // cycles between (untimed) drains of the wire
  MemoryCanLink link(32 * kDrainEvery);
  Bus bus("can0", link.host(), default_rig_can_axes(), std::vector<double>(12, 0.0));
  bus.set_enabled(true);
  std::vector<double> cmd(12, 0.1);
  std::int64_t now = 1'000'000'000;
  warm_up(bus, link, now);
  const std::uint64_t sent0 = bus.status().frames_sent;
  int since_drain = 0;
  for (auto _ : state) {
    now += 1'000'000;
    for (auto& c : cmd) c += 1e-9;
    bus.write({now, 0.001}, cmd);
    if (++since_drain == kDrainEvery) {
      state.PauseTiming();
      drain(link);
      since_drain = 0;
      state.ResumeTiming();
    }
  }
  if (bus.status().fault) state.SkipWithError(bus.status().reason);
  state.counters["frames/cycle"] =
      benchmark::Counter(static_cast<double>(bus.status().frames_sent - sent0) /
                         static_cast<double>(state.iterations()));
}

BENCHMARK_TEMPLATE(encode_and_send, CustomCanBus)->Name("CanEncodeSend/custom_12_axes");
BENCHMARK_TEMPLATE(encode_and_send, Cia402Bus)->Name("CanEncodeSend/cia402_12_drives");

}  // namespace
}  // namespace facectl

BENCHMARK_MAIN();
