// Runs inside the QEMU guest (tests/drivers/qemu/run_can_in_qemu.sh): the real
// SocketCAN transport and CAN buses on a vcan interface, against simulated
// CiA 402 drives and custom boards on their own sockets on the same
// interface, in real time. candump records the wire for the script to check.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

#include "drivers/bus_doctor.hpp"
#include "drivers/can/cia402_bus.hpp"
#include "drivers/can/custom_can_bus.hpp"
#include "drivers/can/socketcan_transport.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/cia402_drive_sim.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "tests/drivers/can_test_axes.hpp"

namespace facectl {
namespace {

using Clock = std::chrono::steady_clock;
using testing::fast_plant;
using testing::kDeg;
const auto rotary = testing::rotary_axes;
const char* kIf = "vcan0";

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch())
      .count();
}

// A 1 kHz tick in real time on this thread: read, then write `target(t)`.
// Runs until `done` or `limit_s`; returns the seconds it ran, or -1.
template <typename Done>
double run_ticks(ActuatorBus& bus, std::size_t n, double limit_s, Done done,
                 const std::function<double(double)>& target, bool write = true) {
  std::vector<double> cmd(n), meas(n);
  const auto t0 = Clock::now();
  auto next = t0;
  while (true) {
    next += std::chrono::milliseconds(1);
    std::this_thread::sleep_until(next);
    const double t = std::chrono::duration<double>(Clock::now() - t0).count();
    const TickTime tt{now_ns(), 0.001};
    bus.read(tt, meas);
    for (auto& c : cmd) c = target(t);
    if (write) bus.write(tt, cmd);
    if (done()) return t;
    if (t > limit_s) return -1.0;
  }
}

TEST(Vcan, Cia402DrivesReachOperationEnabledAndFollowTheCommandedPositions) {
  SocketCanTransport host(kIf, false);
  SocketCanTransport wire(kIf, false);
  CanBusOptions options;
  // The drives here are polled at 200 Hz by a thread of a software-emulated
  // CPU, which stalls for 20 ms at times: the 20 ms TPDO timeout is for
  // real drives. So is the 50 ms SDO timeout: a busy host stalls the guest
  // past it (seen: "drive 3: no SDO reply" while a sanitizer build ran).
  options.feedback_timeout_s = 0.1;
  options.sdo_timeout_s = 0.25;
  std::vector<std::unique_ptr<sim::Cia402DriveSim>> drives;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 3; ++n) {
    drives.push_back(
        std::make_unique<sim::Cia402DriveSim>(n, fast_plant(), options.rotary_counts_per_rad, 0.0));
    devices.push_back(drives.back().get());
  }
  sim::CanDeviceNetwork net(wire, devices);
  net.start(200);
  Cia402Bus bus("vcan0", host, rotary(3), std::vector<double>(3, 0.0), options);
  bus.set_enabled(true);
  const double t = run_ticks(
      bus, 3, 5.0,
      [&] {
        for (auto& d : drives) {
          if (d->state() != cia402::DriveState::kOperationEnabled) return false;
        }
        return true;
      },
      [](double) { return 0.0; });
  ASSERT_GT(t, 0.0) << "drive 1 is " << cia402::to_string(drives[0]->state()) << "; bus "
                    << bus.status().reason;
  std::printf("[vcan] 3 CiA 402 drives reached operation enabled after %.3f s\n", t);
  // A ramp to 10 degrees over 0.5 s, then hold.
  run_ticks(
      bus, 3, 1.0, [] { return false; },
      [](double s) { return std::min(s / 0.5, 1.0) * 10 * kDeg; });
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(drives[i]->position(), 10 * kDeg, 0.1 * kDeg);
    std::printf("[vcan] drive %zu: %s, position %.3f deg (commanded 10.000)\n", i + 1,
                cia402::to_string(drives[i]->state()), drives[i]->position() / kDeg);
  }
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;
  EXPECT_EQ(drives[0]->mode(), 8);
  // Disabled, the loop goes on ticking: quick stop, then disable voltage
  // (run_in_qemu.sh looks for the quick stop on the wire).
  bus.set_enabled(false);
  run_ticks(
      bus, 3, 0.3, [] { return false; }, [](double) { return 0.0; }, false);
}

TEST(Vcan, AnEmcyInjectedWithCansendFaultsTheBusWithItsCode) {
  // run_in_qemu.sh copies cansend into the guest; its absence is a broken guest, not a skip.
  ASSERT_EQ(std::system("command -v cansend >/dev/null"), 0) << "cansend missing from the guest";
  SocketCanTransport host(kIf, false);
  Cia402Bus bus("vcan0", host, rotary(3), std::vector<double>(3, 0.0));
  std::thread inject([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    (void)std::system("cansend vcan0 083#1023040000000000");
  });
  const double t = run_ticks(
      bus, 3, 3.0, [&] { return bus.status().fault; }, [](double) { return 0.0; }, false);
  inject.join();
  ASSERT_GT(t, 0.0);
  EXPECT_STREQ(bus.status().reason, "vcan0 drive 3: emergency (EMCY)");
  EXPECT_EQ(bus.last_emcy(2), 0x2310);
  std::printf("[vcan] cansend 083#1023040000000000 -> %s, code 0x%04X\n", bus.status().reason,
              bus.last_emcy(2));
}

TEST(Vcan, CustomBoardsFollowAndNothingIsTransmittedAfterTheEstop) {
  SocketCanTransport host(kIf, false);
  SocketCanTransport wire(kIf, false);
  std::vector<std::unique_ptr<sim::CustomCanBoardSim>> boards;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 4; ++n) {
    std::vector<sim::BoardChannel> ch(3);
    for (auto& c : ch) c.plant = fast_plant();
    boards.push_back(std::make_unique<sim::CustomCanBoardSim>(n, ch, custom_can::Width::kInt16));
    devices.push_back(boards.back().get());
  }
  sim::CanDeviceNetwork net(wire, devices);
  net.start(200);
  CustomCanBus bus("vcan0", host, rotary(12), std::vector<double>(12, 0.0));
  bus.set_enabled(true);
  run_ticks(
      bus, 12, 0.5, [] { return false; }, [](double) { return -7 * kDeg; });
  for (const auto& b : boards) EXPECT_NEAR(b->position(2), -7 * kDeg, 0.1 * kDeg);
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;
  std::printf("[vcan] 4 custom boards at %.3f deg (commanded -7.000)\n",
              boards[3]->position(2) / kDeg);

  // E-stop: the controller disables the bus; a sniffer on the wire must see
  // no command frame from then on, even though the tick keeps calling write().
  bus.set_enabled(false);
  const std::uint64_t sent = bus.status().frames_sent;
  // Frames handed to the kernel before the e-stop may still be in flight.
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::uint64_t commands = boards[0]->commands();
  SocketCanTransport sniffer(kIf, false);
  std::uint64_t host_frames = 0;
  run_ticks(
      bus, 12, 0.3,
      [&] {
        CanFrame f;
        CanError e;
        while (sniffer.receive(f, e)) {
          if (e == CanError::kNone && f.id > custom_can::kCommandBase &&
              f.id <= custom_can::kCommandBase + 63) {
            ++host_frames;
          }
        }
        return false;
      },
      [](double) { return 5 * kDeg; });
  EXPECT_EQ(host_frames, 0u);
  EXPECT_EQ(boards[0]->commands(), commands);
  EXPECT_EQ(bus.status().frames_sent, sent);
  std::printf("[vcan] after the e-stop: %llu command frames on the wire\n",
              static_cast<unsigned long long>(host_frames));
}

TEST(Vcan, ASilentDriveIsAHeartbeatLossFault) {
  SocketCanTransport host(kIf, false);
  SocketCanTransport wire(kIf, false);
  CanBusOptions options;
  sim::Cia402DriveSim d1(1, fast_plant(), options.rotary_counts_per_rad, 0.0);
  sim::Cia402DriveSim d2(2, fast_plant(), options.rotary_counts_per_rad, 0.0);
  sim::CanDeviceNetwork net(wire, {&d1, &d2});
  net.start(200);
  Cia402Bus bus("vcan0", host, rotary(2), std::vector<double>(2, 0.0), options);
  bus.set_enabled(true);
  ASSERT_GT(run_ticks(
                bus, 2, 5.0, [&] { return d2.state() == cia402::DriveState::kOperationEnabled; },
                [](double) { return 0.0; }),
            0.0);
  d2.faults().silent = true;
  const double t = run_ticks(
      bus, 2, 2.0, [&] { return bus.status().fault; }, [](double) { return 0.0; });
  ASSERT_GT(t, 0.0);
  EXPECT_STREQ(bus.status().reason, "vcan0 drive 2: heartbeat lost");
  std::printf("[vcan] silent drive 2 -> '%s' after %.3f s (timeout %.3f s)\n", bus.status().reason,
              t, options.heartbeat_timeout_s);
}

TEST(Vcan, ACanFdFramePacksTwelveChannelsForOneBoard) {
  // vcan1 has a 72-byte MTU: CAN FD.
  SocketCanTransport host("vcan1", true);
  SocketCanTransport wire("vcan1", true);
  std::vector<sim::BoardChannel> ch(12);
  for (auto& c : ch) c.plant = fast_plant();
  sim::CustomCanBoardSim board(1, ch, custom_can::Width::kInt16, true);
  sim::CanDeviceNetwork net(wire, {&board});
  net.start(200);
  CanBusOptions fd;
  fd.fd = true;
  CustomCanBus bus("vcan1", host, rotary(12), std::vector<double>(12, 0.0), fd);
  EXPECT_EQ(bus.board_count(), 1u);
  bus.set_enabled(true);
  run_ticks(
      bus, 12, 0.5, [] { return false; }, [](double) { return 4 * kDeg; });
  EXPECT_NEAR(board.position(11), 4 * kDeg, 0.1 * kDeg);
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;
  std::printf(
      "[vcan] CAN FD: 1 board, 12 channels in one FD frame (26 bytes, sent as 32), channel 12 at "
      "%.3f deg\n",
      board.position(11) / kDeg);
}

TEST(Vcan, BusDoctorFindsTheDrivesOnARealSocket) {
  SocketCanTransport host(kIf, false);
  SocketCanTransport wire(kIf, false);
  sim::Cia402DriveSim d1(1, fast_plant(), 1000.0, 0.0);
  sim::Cia402DriveSim d2(2, fast_plant(), 1000.0, 0.0);
  sim::CanDeviceNetwork net(wire, {&d1, &d2});
  net.start(200);
  const DoctorReport r =
      diagnose_can("vcan0", host, "cia402", rotary(2), CanBusOptions{}, 250.0, 1'000'000, 0.5);
  std::printf("[vcan] bus doctor:\n%s", r.to_text().c_str());
  EXPECT_FALSE(r.has_problems());
}

// `facectl bus doctor` as a user runs it, on a rig of three CiA 402 drives
// on vcan0 of which two answer (the script puts /bin/facectl and the head
// file /cfg/head.yaml into the guest).
TEST(Vcan, FacectlBusDoctorNamesTheDriveThatDoesNotAnswer) {
  // The ctest entry always passes the binary to run_in_qemu.sh: missing is a failure.
  ASSERT_EQ(access("/bin/facectl", X_OK), 0) << "no /bin/facectl in this guest";
  std::string rig =
      "rig:\n  name: vcan\n  buses:\n    - { name: can0, type: can, interface: vcan0, "
      "bitrate: 1000000, protocol: cia402, rate_divider: 4 }\n  actuators:\n";
  const char* signals[] = {"jaw_pitch_deg", "jaw_yaw_deg", "neck_pan_deg"};
  for (int i = 1; i <= 3; ++i) {
    rig += "    - { name: a" + std::to_string(i) +
           ", kind: rotary, bus: can0, address: " + std::to_string(i) +
           ", position_deg: { min: -20, max: 20 }, max_velocity_deg_s: 100, "
           "max_acceleration_deg_s2: 1000, rest_deg: 0, map: { terms: { " +
           signals[i - 1] + ": 1 } } }\n";
  }
  std::FILE* f = std::fopen("/tmp/doctor_rig.yaml", "w");
  ASSERT_NE(f, nullptr);
  std::fputs(rig.c_str(), f);
  std::fclose(f);
  f = std::fopen("/tmp/doctor_runtime.yaml", "w");
  ASSERT_NE(f, nullptr);
  std::fputs("head: /cfg/head.yaml\nrig: /tmp/doctor_rig.yaml\nexpressions: unused.yaml\n", f);
  std::fclose(f);

  SocketCanTransport wire(kIf, false);
  sim::Cia402DriveSim d1(1, fast_plant(), 131072.0 / (2 * 3.14159265358979), 0.0);
  sim::Cia402DriveSim d2(2, fast_plant(), 131072.0 / (2 * 3.14159265358979), 0.0);
  sim::CanDeviceNetwork net(wire, {&d1, &d2});
  net.start(200);
  const int status = std::system(
      "/bin/facectl bus doctor /tmp/doctor_rig.yaml --config /tmp/doctor_runtime.yaml "
      "--listen 0.5 > /tmp/doctor.txt 2>&1");
  std::string out;
  if (std::FILE* in = std::fopen("/tmp/doctor.txt", "r")) {
    char buf[512];
    while (std::fgets(buf, sizeof buf, in) != nullptr) out += buf;
    std::fclose(in);
  }
  std::printf("[vcan] facectl bus doctor (exit %d):\n%s", WEXITSTATUS(status), out.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1) << "a drive is missing: problems found";
  EXPECT_NE(out.find("  ok   load: can0:"), std::string::npos);
  EXPECT_NE(out.find("  ok   drive 1: SDO round trip"), std::string::npos);
  EXPECT_NE(out.find("  ok   drive 2: SDO round trip"), std::string::npos);
  EXPECT_NE(out.find("  FAIL drive 3"), std::string::npos);
  EXPECT_EQ(d1.sdo_writes(), 0u) << "the doctor only reads";
}

TEST(Vcan, EncodeAndSendPerCycleThroughTheRealSocket) {
  SocketCanTransport host(kIf, false);
  SocketCanTransport wire(kIf, false);
  std::vector<std::unique_ptr<sim::CustomCanBoardSim>> boards;
  std::vector<sim::CanDevice*> devices;
  for (int n = 1; n <= 4; ++n) {
    boards.push_back(std::make_unique<sim::CustomCanBoardSim>(n, std::vector<sim::BoardChannel>(3),
                                                              custom_can::Width::kInt16));
    devices.push_back(boards.back().get());
  }
  sim::CanDeviceNetwork net(wire, devices);
  net.start(200);
  CustomCanBus bus("vcan0", host, rotary(12), std::vector<double>(12, 0.0));
  bus.set_enabled(true);
  std::vector<double> cmd(12, 0.0), meas(12);
  std::vector<std::int64_t> ns;
  for (int k = 0; k < 2000; ++k) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    const TickTime tt{now_ns(), 0.001};
    bus.read(tt, meas);
    const auto a = Clock::now();
    bus.write(tt, cmd);
    ns.push_back(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - a).count());
  }
  std::sort(ns.begin(), ns.end());
  std::printf(
      "[vcan] custom 12 axes, write() = encode + 4 send(): p50 %.2f us, p99 %.2f us "
      "(QEMU TCG, software-emulated CPU)\n",
      static_cast<double>(ns[ns.size() / 2]) * 1e-3,
      static_cast<double>(ns[ns.size() * 99 / 100]) * 1e-3);
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;
}

}  // namespace
}  // namespace facectl
