// Bus transfer times of the simulated twins, against figures worked by hand.
#include "sim/devices/sim_bus_timing.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace facectl {
namespace {

BusSpec can_bus(const char* protocol) {
  BusSpec b;
  b.name = "can0";
  b.type = "can";
  b.bitrate = 1'000'000;
  b.can_protocol = protocol;
  return b;
}

TEST(SimBusTiming, CustomCanFramesLandInNodeOrderAt135MicrosecondsEach) {
  BusSpec bus = can_bus("custom");
  bus.can.cycle_divider = 4;
  // int16 classic frames carry 3 channels: addresses 1..12 are nodes 1..4.
  const std::vector<int> addresses = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  const SimBusTiming t = sim_bus_timing(bus, addresses, 1000.0);
  ASSERT_EQ(t.arrival_s.size(), 12u);
  EXPECT_NEAR(t.arrival_s[0], 135e-6, 1e-12);  // one classic frame at 1 Mbit/s
  EXPECT_NEAR(t.arrival_s[2], 135e-6, 1e-12);
  EXPECT_NEAR(t.arrival_s[3], 270e-6, 1e-12);
  EXPECT_NEAR(t.arrival_s[11], 540e-6, 1e-12);
  // 4 commands + 4 feedback frames per bus cycle, every 4th tick at 1 kHz.
  EXPECT_NEAR(t.timing.cycle_time_s, 8 * 135e-6, 1e-12);
  EXPECT_NEAR(t.timing.load, 8 * 135.0 * 250.0 / 1e6, 1e-12);
}

TEST(SimBusTiming, Cia402DrivesLatchOnTheSyncAfterEveryRpdo) {
  const BusSpec bus = can_bus("cia402");
  const std::vector<int> addresses = {1, 2};
  const SimBusTiming t = sim_bus_timing(bus, addresses, 250.0);
  EXPECT_NEAR(t.arrival_s[0], 3 * 135e-6, 1e-12);
  EXPECT_NEAR(t.arrival_s[1], 3 * 135e-6, 1e-12);
}

TEST(SimBusTiming, ModbusRtuAt115200BaudMatchesTheHandCount) {
  BusSpec bus;
  bus.name = "servo_board";
  bus.type = "modbus_rtu";
  bus.bitrate = 115200;
  bus.modbus.cycle_period_s = 0.020;
  // Units 1 (channels 0..7) and 2 (channels 0..1).
  const std::vector<int> addresses = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  const SimBusTiming t = sim_bus_timing(bus, addresses, 1000.0);
  const double bit = 1.0 / 115200;
  // Unit 1, 8 channels: write request 9 + 2·10 = 29, reply 8; read request 8,
  // reply 5 + 2·12 = 29; 4 × 3.5 silent characters: 88 characters.
  // Unit 2, 2 channels: 17 + 8 + 8 + 17 + 14 = 64 characters. 10 bits each.
  EXPECT_NEAR(t.arrival_s[0], (29 + 3.5) * 10 * bit, 1e-12);
  EXPECT_NEAR(t.arrival_s[7], (29 + 3.5) * 10 * bit, 1e-12);
  EXPECT_NEAR(t.arrival_s[8], (88 + 17 + 3.5) * 10 * bit, 1e-12);
  EXPECT_NEAR(t.timing.cycle_time_s, (88 + 64) * 10 * bit, 1e-12);  // 13.19 ms
  EXPECT_NEAR(t.timing.load, (88 + 64) * 10 * bit / 0.020, 1e-12);
}

TEST(SimBusTiming, ModbusTcpAddsItsConfiguredNetworkLatency) {
  BusSpec bus;
  bus.type = "modbus_tcp";
  const std::vector<int> addresses = {1, 9};
  EXPECT_EQ(sim_bus_timing(bus, addresses, 1000.0).arrival_s[1], 0.0005);  // the default
  bus.modbus.network_latency_s = 0.003;
  const SimBusTiming t = sim_bus_timing(bus, addresses, 1000.0);
  EXPECT_EQ(t.arrival_s[0], 0.003);
  EXPECT_EQ(t.timing.load, 0.0);
}

TEST(SimBusTiming, Pca9685PulsesChangeAtTheEndOfTheirBoardsWrites) {
  BusSpec bus;
  bus.type = "pca9685";
  bus.pca9685.boards = {0x40, 0x41};
  // Board 0x40: channels 0..9, writes of 8 and 2 channels = 308 + 92 clocks,
  // then its MODE1 read (39); board 0x41: channel 1 alone, 2 + 9 · 6 = 56.
  const std::vector<int> addresses = {1, 10, 18};
  const SimBusTiming t = sim_bus_timing(bus, addresses, 1000.0);
  ASSERT_EQ(t.arrival_s.size(), 3U);
  EXPECT_NEAR(t.arrival_s[0], 400e-5, 1e-12);  // 400 clocks at 100 kHz
  EXPECT_NEAR(t.arrival_s[1], 400e-5, 1e-12);
  EXPECT_NEAR(t.arrival_s[2], (439 + 56) * 1e-5, 1e-12);
  EXPECT_NEAR(t.timing.cycle_time_s, (439 + 56 + 39) * 1e-5, 1e-12);
  // Against one period of 50.03 Hz (PRE_SCALE 121).
  EXPECT_NEAR(t.timing.load, 534e-5 * 25e6 / (4096.0 * 122), 1e-9);
  bus.pca9685.i2c_hz = 400'000;
  EXPECT_NEAR(sim_bus_timing(bus, addresses, 1000.0).arrival_s[0], 1e-3, 1e-12);
}

}  // namespace
}  // namespace facectl
