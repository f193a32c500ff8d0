#pragma once

// The in-process CAN rig shared by the CAN bus tests: the host bus and
// simulated devices on a MemoryCanLink, in simulated time: 1 ms ticks, host
// first (read, write), then the devices.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "drivers/can/cia402_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "tests/drivers/can_test_axes.hpp"

namespace facectl::testing {

constexpr std::int64_t kMs = 1'000'000;

// Counts the host's frames as they reach the devices' side of the wire.
class Sniffer final : public sim::CanDevice {
 public:
  void on_frame(const CanFrame&, std::int64_t) override { ++frames; }
  void step(std::int64_t) override {}
  std::uint64_t frames = 0;
};

template <typename Bus>
class Rig {
 public:
  Rig(Bus& bus, sim::CanDeviceNetwork& net, std::size_t n)
      : bus_(bus), net_(net), cmd_(n), meas_(n) {}
  // One tick: the host reads and (if enabled) writes, then the devices run.
  void tick(double target, bool write = true) {
    now_ += kMs;
    bus_.read({now_, 0.001}, meas_);
    for (auto& c : cmd_) c = target;
    if (write) bus_.write({now_, 0.001}, cmd_);
    net_.poll(now_);
  }
  // Ticks until `pred` or `limit_ms`; returns the ms taken or -1.
  template <typename Pred>
  int until(Pred pred, int limit_ms, double target = 0.0, bool write = true) {
    for (int k = 1; k <= limit_ms; ++k) {
      tick(target, write);
      if (pred()) return k;
    }
    return -1;
  }
  std::vector<double>& measured() { return meas_; }
  std::int64_t now() const { return now_; }

 private:
  Bus& bus_;
  sim::CanDeviceNetwork& net_;
  std::vector<double> cmd_, meas_;
  std::int64_t now_ = 1'000 * kMs;
};

class Cia402 : public ::testing::Test {
 protected:
  Cia402() { build(); }
  // (Re)builds the drives, network and bus with options_.
  void build() {
    drives_.clear();
    for (int n = 1; n <= 3; ++n) {
      drives_.push_back(std::make_unique<sim::Cia402DriveSim>(n, fast_plant(),
                                                              options_.rotary_counts_per_rad, 0.0));
    }
    net_ = std::make_unique<sim::CanDeviceNetwork>(
        link_.devices(), std::vector<sim::CanDevice*>{drives_[0].get(), drives_[1].get(),
                                                      drives_[2].get(), &sniffer_});
    bus_ = std::make_unique<Cia402Bus>("can0", link_.host(), rotary_axes(3),
                                       std::vector<double>(3, 0.0), options_);
    rig_ = std::make_unique<Rig<Cia402Bus>>(*bus_, *net_, 3);
  }
  bool all_enabled() const {
    for (const auto& d : drives_) {
      if (d->state() != cia402::DriveState::kOperationEnabled) return false;
    }
    return true;
  }
  void enable() {
    bus_->set_enabled(true);
    ASSERT_GT(rig_->until([&] { return all_enabled(); }, 200), 0)
        << "drive 1 is " << cia402::to_string(drives_[0]->state());
  }

  CanBusOptions options_{};
  MemoryCanLink link_{1024};
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives_;
  Sniffer sniffer_;
  std::unique_ptr<sim::CanDeviceNetwork> net_;
  std::unique_ptr<Cia402Bus> bus_;
  std::unique_ptr<Rig<Cia402Bus>> rig_;
};

}  // namespace facectl::testing
