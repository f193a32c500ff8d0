// Per-actuator encodings (rig `encoding: { raw, scale, offset }`) on the wire:
// command -> bytes -> simulated peer -> feedback for the custom CAN layout and
// the Modbus board, with the bytes checked by hand; the default encoding
// keeps the old fixed scaling bit for bit.
#include "drivers/protocol/wire_encoding.hpp"

#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <thread>

#include "drivers/can/custom_can_bus.hpp"
#include "drivers/modbus/modbus_bus.hpp"
#include "sim/devices/can_device_network.hpp"
#include "sim/devices/custom_can_board_sim.hpp"
#include "sim/devices/memory_can_link.hpp"
#include "sim/devices/modbus_board_server.hpp"
#include "tests/drivers/can_test_axes.hpp"

namespace facectl {
namespace {

using testing::fast_plant;
using testing::kDeg;
using Raw = ActuatorEncoding::Raw;

const ActuatorEncoding kOffsetU16{Raw::kUint16, 50.0, 32768.0};  // 0.02 deg, mid-scale zero
const ActuatorEncoding kFineI32{Raw::kInt32, 10000.0, 0.0};

ActuatorModel actuator(int address, ActuatorKind kind, ActuatorEncoding e) {
  ActuatorModel a;
  a.name = "a" + std::to_string(address);
  a.address = address;
  a.kind = kind;
  a.encoding = e;
  return a;
}

sim::BoardChannel channel(modbus_map::Unit unit, ActuatorEncoding e) {
  sim::BoardChannel c;
  c.plant = fast_plant();
  c.unit = unit;
  c.encoding = e;
  return c;
}

std::uint16_t u16(const CanFrame& f, std::size_t at) {
  return static_cast<std::uint16_t>(f.data[at] | (f.data[at + 1] << 8));
}

TEST(WireEncoding, TheDefaultIsTheOldFixedScalingBitForBit) {
  constexpr double kPi = 3.14159265358979323846;
  const WireEncoding rot(ActuatorKind::kRotary, {});
  const WireEncoding lin(ActuatorKind::kLinear, {});
  for (double v = -400.0; v <= 400.0; v += 0.00731) {
    // The drivers' formula before encodings existed.
    const auto old = [](double si, double step) {
      double c = std::nearbyint(si / step);
      return c < -32767.0 ? -32767.0 : (c > 32767.0 ? 32767.0 : c);
    };
    ASSERT_EQ(rot.encode(v * kDeg), old(v * kDeg, 0.01 * kPi / 180.0)) << v;
    ASSERT_EQ(lin.encode(v * 1e-3), old(v * 1e-3, 0.01e-3)) << v;
    const auto raw = static_cast<std::int16_t>(rot.encode(v * kDeg));
    ASSERT_EQ(rot.decode_u16(static_cast<std::uint16_t>(raw)), raw * (0.01 * kPi / 180.0));
  }
}

TEST(WireEncoding, SaturatesAtTheRawTypeAndDecodesWithTheOffset) {
  const WireEncoding u(ActuatorKind::kRotary, kOffsetU16);
  EXPECT_EQ(u.encode(10 * kDeg), 33268);
  EXPECT_EQ(u.encode(700 * kDeg), 65535);  // 67768 would wrap to 2232
  EXPECT_EQ(u.encode(-700 * kDeg), 0);
  EXPECT_EQ(u.encode(std::nan("")), 0);
  EXPECT_NEAR(u.decode_u16(0xFFFF), (65535.0 - 32768.0) / 50.0 * kDeg, 1e-12);  // not -1
  const WireEncoding i(ActuatorKind::kLinear, kFineI32);
  EXPECT_EQ(i.encode(1e6), 2147483647);
  EXPECT_EQ(i.encode(-1e6), -2147483647);
  EXPECT_NEAR(i.decode(-25000), -2.5e-3, 1e-15);
}

// Host frames as they reach the devices: the last command frame to node 1.
class Capture final : public sim::CanDevice {
 public:
  void on_frame(const CanFrame& f, std::int64_t) override {
    if (f.id == custom_can::kCommandBase + 1) last = f;
  }
  void step(std::int64_t) override {}
  CanFrame last;
};

struct CanRoundTrip {
  CanRoundTrip(custom_can::Width width, bool fd, std::vector<ActuatorModel> acts,
               std::vector<sim::BoardChannel> ch)
      : board(1, std::move(ch), width, fd),
        net(link.devices(), {&board, &capture}),
        bus("can0", link.host(), acts, std::vector<double>(acts.size(), 0.0), options(width, fd)),
        meas(acts.size()) {}
  static CanBusOptions options(custom_can::Width width, bool fd) {
    CanBusOptions o;
    o.width = width;
    o.fd = fd;
    return o;
  }
  void run(const std::vector<double>& cmd, int ticks) {
    for (int k = 0; k < ticks; ++k) {
      now += 1'000'000;
      bus.read({now, 0.001}, meas);
      bus.write({now, 0.001}, cmd);
      net.poll(now);
    }
  }
  MemoryCanLink link{1024};
  sim::CustomCanBoardSim board;
  Capture capture;
  sim::CanDeviceNetwork net;
  CustomCanBus bus;
  std::vector<double> meas;
  std::int64_t now = 1'000'000'000;
};

TEST(CustomCanEncoding, Uint16WithOffsetRoundTripsThroughTwoByteFields) {
  CanRoundTrip t(
      custom_can::Width::kInt16, false,
      {actuator(1, ActuatorKind::kRotary, kOffsetU16), actuator(2, ActuatorKind::kLinear, {})},
      {channel(modbus_map::Unit::kRotary, kOffsetU16), channel(modbus_map::Unit::kLinear, {})});
  t.bus.set_enabled(true);
  t.run({10 * kDeg, 3.5e-3}, 200);
  ASSERT_EQ(t.capture.last.len, 6);
  EXPECT_EQ(t.capture.last.data[2], 0xF4);  // 10 deg · 50 + 32768 = 33268 = 0x81F4
  EXPECT_EQ(t.capture.last.data[3], 0x81);
  EXPECT_EQ(u16(t.capture.last, 4), 350);  // default: 3.5 mm · 100
  EXPECT_NEAR(t.board.position(0), 10 * kDeg, 0.05 * kDeg);
  EXPECT_NEAR(t.board.position(1), 3.5e-3, 0.05e-3);
  EXPECT_NEAR(t.meas[0], 10 * kDeg, 0.05 * kDeg);  // read back unsigned, offset removed
  EXPECT_NEAR(t.meas[1], 3.5e-3, 0.05e-3);
  // Below zero counts and above 65535 the field saturates, it never wraps.
  t.run({-700 * kDeg, 0.0}, 1);
  EXPECT_EQ(u16(t.capture.last, 2), 0);
  t.run({700 * kDeg, 0.0}, 1);
  EXPECT_EQ(u16(t.capture.last, 2), 0xFFFF);
}

TEST(CustomCanEncoding, Int32RoundTripsThroughFourByteFields) {
  const ActuatorEncoding offset_mm{Raw::kInt32, 1000.0, -5000.0};
  CanRoundTrip t(
      custom_can::Width::kInt32, true,  // two int32 channels need FD
      {actuator(1, ActuatorKind::kRotary, kFineI32), actuator(2, ActuatorKind::kLinear, offset_mm)},
      {channel(modbus_map::Unit::kRotary, kFineI32),
       channel(modbus_map::Unit::kLinear, offset_mm)});
  t.bus.set_enabled(true);
  t.run({12.5 * kDeg, -2.5e-3}, 200);
  const CanFrame& f = t.capture.last;
  ASSERT_EQ(f.len, 12);  // 10 bytes, padded to an FD length
  // 12.5 deg · 10000 = 125000 = 0x0001E848, little-endian.
  EXPECT_EQ(f.data[2], 0x48);
  EXPECT_EQ(f.data[3], 0xE8);
  EXPECT_EQ(f.data[4], 0x01);
  EXPECT_EQ(f.data[5], 0x00);
  // -2.5 mm · 1000 - 5000 = -7500 = 0xFFFFE2B4.
  EXPECT_EQ(f.data[6], 0xB4);
  EXPECT_EQ(f.data[7], 0xE2);
  EXPECT_EQ(f.data[8], 0xFF);
  EXPECT_EQ(f.data[9], 0xFF);
  EXPECT_NEAR(t.board.position(0), 12.5 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(t.board.position(1), -2.5e-3, 0.01e-3);  // the peer decoded the offset too
  EXPECT_NEAR(t.meas[0], 12.5 * kDeg, 0.01 * kDeg);
  EXPECT_NEAR(t.meas[1], -2.5e-3, 0.01e-3);
}

TEST(CustomCanEncoding, Int32IsRefusedInATwoByteField) {
  MemoryCanLink link(16);
  EXPECT_THROW(
      CustomCanBus("can0", link.host(), {actuator(1, ActuatorKind::kRotary, kFineI32)}, {0.0}),
      std::invalid_argument);
  EXPECT_THROW(sim::CustomCanBoardSim(1, {channel(modbus_map::Unit::kRotary, kFineI32)},
                                      custom_can::Width::kInt16),
               std::invalid_argument);
}

// Registers `first`.. of unit 1 read by a client of our own (function 0x03
// holding, 0x04 input), once the bus has let go of the server.
std::optional<std::vector<std::uint16_t>> read_registers(int port, bool input, int first, int n) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  std::vector<std::uint16_t> regs(static_cast<std::size_t>(n));
  bool ok = false;
  for (int attempt = 0; attempt < 50 && !ok; ++attempt) {
    if (modbus_connect(ctx) == 0) {
      modbus_set_slave(ctx, 1);
      ok = (input ? modbus_read_input_registers(ctx, first, n, regs.data())
                  : modbus_read_registers(ctx, first, n, regs.data())) == n;
      modbus_close(ctx);
    }
    if (!ok) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  modbus_free(ctx);
  if (!ok) return std::nullopt;
  return regs;
}

TEST(ModbusEncoding, Uint16WithOffsetAndAFinerInt16RoundTripThroughTheRegisters) {
  const ActuatorEncoding fine_mm{Raw::kInt16, 1000.0, 0.0};
  sim::ModbusActuatorBoard board(1, {channel(modbus_map::Unit::kRotary, kOffsetU16),
                                     channel(modbus_map::Unit::kLinear, fine_mm)});
  auto server = sim::ModbusBoardServer::tcp({&board});
  std::vector<double> meas(2);
  {
    ModbusEndpoint ep;
    ep.port = server->port();
    ModbusBus bus("modbus0", ep,
                  {actuator(1, ActuatorKind::kRotary, kOffsetU16),
                   actuator(2, ActuatorKind::kLinear, fine_mm)},
                  {0.0, 0.0});
    bus.set_enabled(true);
    const std::vector<double> cmd{10 * kDeg, 3.5e-3};
    for (int k = 0; k < 3000; ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      bus.read({0, 0.001}, meas);
      bus.write({0, 0.001}, cmd);
      if (k > 300 && std::abs(meas[0] - 10 * kDeg) < 0.05 * kDeg) break;
    }
  }
  // The board decoded exactly the documented raw values.
  EXPECT_NEAR(board.target(0), 10 * kDeg, 1e-12);
  EXPECT_NEAR(board.target(1), 3.5e-3, 1e-12);
  EXPECT_NEAR(meas[0], 10 * kDeg, 0.05 * kDeg);
  EXPECT_NEAR(meas[1], 3.5e-3, 0.01e-3);
  const auto targets = read_registers(server->port(), false, modbus_map::kHrTarget0, 2);
  ASSERT_TRUE(targets);
  EXPECT_EQ((*targets)[0], 33268);  // 10 deg · 50 + 32768
  EXPECT_EQ((*targets)[1], 3500);   // 3.5 mm · 1000
  const auto positions = read_registers(server->port(), true, modbus_map::kIrPosition0, 2);
  ASSERT_TRUE(positions);
  EXPECT_NEAR((*positions)[0], 33268, 2);
  EXPECT_NEAR((*positions)[1], 3500, 2);
}

TEST(ModbusEncoding, Int32IsRefusedForWantOfASecondRegister) {
  EXPECT_THROW(sim::ModbusActuatorBoard(1, {channel(modbus_map::Unit::kRotary, kFineI32)}),
               std::invalid_argument);
  ModbusEndpoint ep;
  ep.port = 1;  // never reached: refused before the I/O thread starts
  EXPECT_THROW(ModbusBus("modbus0", ep, {actuator(1, ActuatorKind::kRotary, kFineI32)}, {0.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace facectl
