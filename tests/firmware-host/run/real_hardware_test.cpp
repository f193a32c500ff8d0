// `hardware: real` through the configuration: the rig's buses come from
// make_bus and the safety I/O from the runtime file's safety_io block. A
// Modbus TCP rig drives a simulated board behind a real libmodbus server on
// 127.0.0.1, with the GPIO safety I/O on a simulated chip; devices that
// cannot be opened are clear errors, and `facectl run --hardware real` exits 2.
#include "firmware-host/run/real_hardware.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "control/clock.hpp"
#include "control/controller.hpp"
#include "drivers/protocol/wire_encoding.hpp"
#include "sim/devices/dynamixel_pty_wire.hpp"
#include "sim/devices/feetech_pty_wire.hpp"
#include "sim/devices/maestro_pty_wire.hpp"
#include "sim/devices/modbus_board_server.hpp"
#include "sim/devices/sim_gpio_chip.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/drivers/facectl_process.hpp"
#include "tests/drivers/modbus_tcp_rig.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;
using testing::run_facectl;

std::vector<sim::BoardChannel> three_channels() {
  std::vector<sim::BoardChannel> c(3);
  for (auto& ch : c) ch.plant = testing::fast_plant();
  c[2].unit = modbus_map::Unit::kLinear;
  return c;
}

// Opens a simulated GPIO chip instead of a libgpiod one; `chip` gets it.
GpioOpener sim_gpio(SimGpioChip*& chip, bool estop_pressed = false) {
  return [&chip, estop_pressed](const std::string&, const GpioSafetyConfig& g) {
    auto c = std::make_unique<SimGpioChip>();
    c->set_physical(g.estop_line, estop_pressed);
    chip = c.get();
    GpioHardware out;
    out.io = std::make_unique<GpioSafetyIo>(*c, g);
    out.chip = std::move(c);
    return out;
  };
}

// A 1 kHz loop of the controller on real hardware, commanding the jaw.
struct TickLoop {
  TickLoop(const ControllerModel& m, RealHardware& hw)
      : model(m), controller(m, hw.seams, hw.io(), {&mailbox, nullptr, &events}) {}

  // Ticks until done() or `limit`; true if done.
  template <typename Done>
  bool run(std::chrono::milliseconds limit, Done done) {
    const auto t0 = std::chrono::steady_clock::now();
    auto next = t0;
    while (std::chrono::steady_clock::now() - t0 < limit) {
      next += 1ms;
      std::this_thread::sleep_until(next);
      FaceCommand cmd;
      cmd.values = model.neutral;
      cmd.values[model.layout.jaw_pitch()] = jaw_rad;
      cmd.sequence = ++tick;
      cmd.stamp_ns = monotonic_ns();
      mailbox.publish(cmd);
      TickTiming t;
      t.tick = tick;
      t.now_ns = cmd.stamp_ns;
      t.dt_s = 0.001;
      controller.tick(t);
      if (done()) return true;
    }
    return false;
  }

  const ControllerModel& model;
  LatestValueMailbox<FaceCommand> mailbox;
  SpscRing<TransitionEvent> events{64};
  Controller controller;
  double jaw_rad = 0.1;
  std::uint64_t tick = 0;
};

TEST(RealHardware, AModbusTcpRigRunsThroughTheConfigAndTheGpioEstopStopsIt) {
  sim::ModbusActuatorBoard board(1, three_channels());
  auto server = sim::ModbusBoardServer::tcp({&board});
  testing::ModbusTcpRig files(server->port());
  const LoadedConfig cfg = load_config(files.runtime.path());
  ASSERT_EQ(cfg.runtime.hardware, HardwareMode::kReal);

  SimGpioChip* chip = nullptr;
  auto hw = make_real_hardware(cfg.built.model, cfg, sim_gpio(chip));
  ASSERT_EQ(hw->seams.size(), 1u);
  EXPECT_EQ(hw->notes.at(0),
            "modbus0: 1 Modbus boards answer at 127.0.0.1:" + std::to_string(server->port()));

  TickLoop loop(cfg.built.model, *hw);
  Controller& controller = loop.controller;
  auto run = [&](std::chrono::milliseconds limit, auto done) { return loop.run(limit, done); };
  EXPECT_FALSE(hw->io().estop_active()) << "released before the run starts";
  controller.request_enable();
  ASSERT_TRUE(run(5000ms, [&] { return controller.state() == SafetyState::kRunning; }))
      << to_string(controller.state());
  EXPECT_TRUE(chip->physical(4)) << "power enabled while running";
  // The jaw follows the command on the simulated board, through libmodbus.
  ASSERT_TRUE(run(3000ms, [&] { return std::abs(board.position(0) - 0.1) < 0.005; }))
      << board.position(0);

  chip->set_physical(3, true);  // pressed
  int ticks = 0;
  ASSERT_TRUE(run(100ms, [&] {
    ++ticks;
    return controller.state() == SafetyState::kEstop;
  }));
  EXPECT_LE(ticks, 1) << "ESTOP on the tick that reads the edge";
  EXPECT_FALSE(chip->physical(4)) << "power dropped in ESTOP";
}

TEST(RealHardware, BoardsWhoseRegistersStartElsewhereAreDrivenAtTheConfiguredAddresses) {
  sim::ModbusActuatorBoard board(1, three_channels());
  auto server = sim::ModbusBoardServer::tcp({&board}, {100, 110, 200});
  testing::ModbusTcpRig files(server->port(), "sim", false,
                              ", enable_register: 100, status_register: 200");
  const LoadedConfig cfg = load_config(files.runtime.path());
  EXPECT_EQ(cfg.rig.buses[0].modbus_registers.watchdog, 110);
  SimGpioChip* chip = nullptr;
  auto hw = make_real_hardware(cfg.built.model, cfg, sim_gpio(chip));
  hw->seams[0]->set_enabled(true);
  const std::vector<double> target{0.05, 0.0, 0.001};
  std::vector<double> measured(3);
  for (int k = 0; k < 2000 && std::abs(board.position(0) - 0.05) > 0.002; ++k) {
    const TickTime t{monotonic_ns(), 0.001};
    hw->seams[0]->read(t, measured);
    hw->seams[0]->write(t, target);
    std::this_thread::sleep_for(1ms);
  }
  EXPECT_NEAR(board.position(0), 0.05, 0.002);
  EXPECT_TRUE(board.enabled());
  EXPECT_FALSE(hw->seams[0]->status().fault) << hw->seams[0]->status().reason;
  hw->seams[0]->set_enabled(false);

  // The same rig against a board at the default addresses: refused by the board.
  sim::ModbusActuatorBoard plain(1, three_channels());
  auto plain_server = sim::ModbusBoardServer::tcp({&plain});
  testing::ModbusTcpRig wrong(plain_server->port(), "sim", false,
                              ", enable_register: 100, status_register: 200");
  const LoadedConfig cfg2 = load_config(wrong.runtime.path());
  try {
    make_real_hardware(cfg2.built.model, cfg2, sim_gpio(chip));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("modbus0 board 1"), std::string::npos) << e.what();
  }
}

TEST(RealHardware, DevicesThatCannotBeOpenedAreClearErrors) {
  // Nothing listens on the port: the board never answers.
  int port = 0;
  {
    sim::ModbusActuatorBoard board(1, three_channels());
    port = sim::ModbusBoardServer::tcp({&board})->port();
  }
  testing::ModbusTcpRig files(port);
  const LoadedConfig cfg = load_config(files.runtime.path());
  try {
    make_real_hardware(cfg.built.model, cfg);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("modbus0"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("board 1"), std::string::npos) << e.what();
  }

  // Board 1 answers, board 2 (unit 2) is not there.
  {
    sim::ModbusActuatorBoard board(1, three_channels());
    auto server = sim::ModbusBoardServer::tcp({&board});
    testing::ModbusTcpRig two(server->port(), "sim", /*board_2=*/true);
    const LoadedConfig cfg3 = load_config(two.runtime.path());
    try {
      make_real_hardware(cfg3.built.model, cfg3);
      FAIL();
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("modbus0 board 2"), std::string::npos) << e.what();
    }
  }

  // The board answers; the GPIO chip does not exist.
  sim::ModbusActuatorBoard board(1, three_channels());
  auto server = sim::ModbusBoardServer::tcp({&board});
  testing::ModbusTcpRig good(server->port(), "gpiochip-missing");
  const LoadedConfig cfg2 = load_config(good.runtime.path());
  try {
    make_real_hardware(cfg2.built.model, cfg2);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gpiochip-missing"), std::string::npos) << e.what();
  }

  // An e-stop that reads pressed at start: refused, not a latched ESTOP.
  try {
    SimGpioChip* chip = nullptr;
    make_real_hardware(cfg2.built.model, cfg2, sim_gpio(chip, true));
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the e-stop (gpiochip-missing line 3) reads pressed"),
              std::string::npos)
        << e.what();
  }

  // And as a user sees it: exit code 2, naming the chip.
  std::string out;
  EXPECT_EQ(run_facectl("run --quiet --config " + good.runtime.path(), out), 2) << out;
  EXPECT_NE(out.find("gpiochip-missing"), std::string::npos) << out;
}

TEST(RealHardware, TheDefaultRunStaysSimulatedAndRealNeedsItsDevices) {
  std::string out;
  // The shipped rig's can0 does not exist on this machine (nor CAN at all).
  EXPECT_EQ(run_facectl("run --quiet --hardware real --duration 0.2", out), 2) << out;
  EXPECT_NE(out.find("real hardware: bus can0: SocketCAN can0"), std::string::npos) << out;
  EXPECT_EQ(run_facectl("run --quiet --hardware sideways", out), 2) << out;
  EXPECT_NE(out.find("--hardware: expected sim or real"), std::string::npos) << out;
  EXPECT_EQ(run_facectl("run --quiet --duration 0.3", out), 0) << out;
  EXPECT_NE(out.find("(simulated)"), std::string::npos) << out;
}

TEST(RealHardware, RealHardwareWithoutASafetyIoBlockIsRefused) {
  testing::ModbusTcpRig files(1502);
  std::string text = testing::ModbusTcpRig::runtime_text(files.rig.path(), "x");
  text = text.substr(0, text.find("safety_io"));
  testing::TempFile runtime(text);
  const LoadedConfig cfg = load_config(runtime.path());
  try {
    make_real_hardware(cfg.built.model, cfg);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()),
              runtime.path() +
                  ": hardware: real: expected a safety_io block (the e-stop input and the "
                  "power-enable output), found none; nothing is enabled without an e-stop");
  }
}

// The shipped DYNAMIXEL hobby rig, its port pointed at ten simulated XL430s
// standing at their actuators' rest: set up, enabled bumplessly, the jaw
// commanded through its four-bar linkage, and the e-stop drops the torque.
TEST(RealHardware, TheShippedDynamixelRigDrivesSimulatedServos) {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/config/rigs/hobby_dynamixel.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const auto rig_on = [&](const std::string& device) {
    std::string r = text.str();
    const std::string from = "device: /dev/ttyUSB0";
    r.replace(r.find(from), from.size(), "device: " + device);
    return r;
  };
  // Where each servo stands: its actuator's rest, in its pulses.
  std::vector<std::unique_ptr<sim::DynamixelServoSim>> servos;
  {
    testing::TempFile rig(rig_on("/dev/null"));
    testing::TempFile runtime(testing::ModbusTcpRig::runtime_text(rig.path(), "sim"));
    const LoadedConfig cfg = load_config(runtime.path());
    for (const ActuatorModel& a : cfg.built.model.actuators) {
      const WireEncoding enc(a.kind, a.encoding);
      servos.push_back(
          std::make_unique<sim::DynamixelServoSim>(static_cast<std::uint8_t>(a.address), 1060,
                                                   static_cast<std::int32_t>(enc.encode(a.rest))));
    }
  }
  ASSERT_EQ(servos.size(), 10u);
  sim::DynamixelPtyWire wire(std::move(servos));
  testing::TempFile rig(rig_on(wire.device()));
  testing::TempFile runtime(testing::ModbusTcpRig::runtime_text(rig.path(), "sim"));
  const LoadedConfig cfg = load_config(runtime.path());
  SimGpioChip* chip = nullptr;
  auto hw = make_real_hardware(cfg.built.model, cfg, sim_gpio(chip));
  EXPECT_EQ(hw->notes.at(0), "servos: 10 DYNAMIXEL servos set up at " + wire.device());

  TickLoop loop(cfg.built.model, *hw);
  loop.jaw_rad = 0.0;
  Controller& controller = loop.controller;
  auto run = [&](std::chrono::milliseconds limit, auto done) { return loop.run(limit, done); };
  std::int32_t rest_goal = 0;
  wire.with_servo(1, [&](sim::DynamixelServoSim& s) { rest_goal = s.present(); });
  controller.request_enable();
  ASSERT_TRUE(run(5000ms, [&] { return controller.state() == SafetyState::kRunning; }))
      << to_string(controller.state()) << " " << hw->seams.at(0)->status().reason;
  bool torque = false;
  EXPECT_TRUE(run(500ms, [&] {
    wire.with_servo(1, [&](sim::DynamixelServoSim& s) { torque = s.torque(); });
    return torque;
  })) << "torque on while running";
  // Open the jaw 10 deg: the horn turns through the linkage, away from rest.
  loop.jaw_rad = 10.0 * 3.14159265358979 / 180.0;
  std::int32_t goal = rest_goal;
  ASSERT_TRUE(run(3000ms,
                  [&] {
                    wire.with_servo(1, [&](sim::DynamixelServoSim& s) { goal = s.goal(); });
                    return std::abs(goal - rest_goal) > 100;
                  }))
      << goal << " vs rest " << rest_goal;
  EXPECT_EQ(controller.state(), SafetyState::kRunning) << hw->seams.at(0)->status().reason;

  chip->set_physical(3, true);  // e-stop pressed
  ASSERT_TRUE(run(100ms, [&] { return controller.state() == SafetyState::kEstop; }));
  EXPECT_FALSE(chip->physical(4)) << "power dropped in ESTOP";
  ASSERT_TRUE(run(500ms, [&] {
    wire.with_servo(1, [&](sim::DynamixelServoSim& s) { torque = s.torque(); });
    return !torque;
  })) << "torque off in ESTOP";
}

// The shipped Maestro hobby rig, its port pointed at a simulated Mini Maestro
// 12 set up as the rig's header says (each channel's range widened): no
// pulses until enabled, then the rest pulse, the jaw commanded through its
// four-bar linkage, and the e-stop stops the pulses.
TEST(RealHardware, TheShippedMaestroRigDrivesASimulatedMaestro) {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/config/rigs/hobby_maestro.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string r = text.str();
  sim::MaestroSim maestro(12);
  for (int c = 0; c < 12; ++c) maestro.set_range(c, 544 * 4, 2400 * 4);
  sim::MaestroPtyWire wire(std::move(maestro));
  const std::string from = "device: /dev/ttyACM0";
  r.replace(r.find(from), from.size(), "device: " + wire.device());
  testing::TempFile rig(r);
  testing::TempFile runtime(testing::ModbusTcpRig::runtime_text(rig.path(), "sim"));
  const LoadedConfig cfg = load_config(runtime.path());
  SimGpioChip* chip = nullptr;
  auto hw = make_real_hardware(cfg.built.model, cfg, sim_gpio(chip));
  EXPECT_EQ(hw->notes.at(0), "servo_board: a Maestro with 10 channels answers at " + wire.device());
  const auto target = [&](int channel) {
    int v = 0;
    wire.with_maestro([&](sim::MaestroSim& m) { v = m.target(channel); });
    return v;
  };
  EXPECT_EQ(target(1), 0) << "no pulses before the enable";

  TickLoop loop(cfg.built.model, *hw);
  loop.jaw_rad = 0.0;
  Controller& controller = loop.controller;
  auto run = [&](std::chrono::milliseconds limit, auto done) { return loop.run(limit, done); };
  controller.request_enable();
  ASSERT_TRUE(run(5000ms, [&] { return controller.state() == SafetyState::kRunning; }))
      << to_string(controller.state()) << " " << hw->seams.at(0)->status().reason;
  // The jaw's rest, 89.5 deg: 600 + 895 = 1495 us.
  ASSERT_TRUE(run(500ms, [&] { return target(1) != 0; })) << "pulses on while running";
  EXPECT_NEAR(target(1), 4 * 1495, 4 * 3) << target(1);
  const int rest = target(1);
  loop.jaw_rad = 10.0 * 3.14159265358979 / 180.0;
  ASSERT_TRUE(run(3000ms, [&] { return std::abs(target(1) - rest) > 4 * 50; }))
      << target(1) << " vs rest " << rest;
  EXPECT_EQ(controller.state(), SafetyState::kRunning) << hw->seams.at(0)->status().reason;

  chip->set_physical(3, true);  // e-stop pressed
  ASSERT_TRUE(run(100ms, [&] { return controller.state() == SafetyState::kEstop; }));
  EXPECT_FALSE(chip->physical(4)) << "power dropped in ESTOP";
  ASSERT_TRUE(run(500ms, [&] { return target(1) == 0 && target(10) == 0; }))
      << "pulses off in ESTOP";
}

// The shipped Feetech hobby rig, its port pointed at ten simulated STS3215s
// standing at their actuators' rest: set up, enabled bumplessly, the jaw
// commanded through its linkage, and the e-stop drops the torque.
TEST(RealHardware, TheShippedFeetechRigDrivesSimulatedServos) {
  std::ifstream in(std::string(FACECTL_SOURCE_DIR) + "/config/rigs/hobby_feetech.yaml");
  std::stringstream text;
  text << in.rdbuf();
  const auto rig_on = [&](const std::string& device) {
    std::string r = text.str();
    const std::string from = "device: /dev/ttyUSB0";
    r.replace(r.find(from), from.size(), "device: " + device);
    return r;
  };
  std::vector<std::unique_ptr<sim::FeetechServoSim>> servos;
  {
    testing::TempFile rig(rig_on("/dev/null"));
    testing::TempFile runtime(testing::ModbusTcpRig::runtime_text(rig.path(), "sim"));
    const LoadedConfig cfg = load_config(runtime.path());
    for (const ActuatorModel& a : cfg.built.model.actuators) {
      const WireEncoding enc(a.kind, a.encoding);
      servos.push_back(std::make_unique<sim::FeetechServoSim>(
          static_cast<std::uint8_t>(a.address), ft::Series::kSts,
          static_cast<std::int32_t>(enc.encode(a.rest))));
    }
  }
  ASSERT_EQ(servos.size(), 10u);
  sim::FeetechPtyWire wire(std::move(servos));
  testing::TempFile rig(rig_on(wire.device()));
  testing::TempFile runtime(testing::ModbusTcpRig::runtime_text(rig.path(), "sim"));
  const LoadedConfig cfg = load_config(runtime.path());
  SimGpioChip* chip = nullptr;
  auto hw = make_real_hardware(cfg.built.model, cfg, sim_gpio(chip));
  EXPECT_EQ(hw->notes.at(0), "servos: 10 Feetech servos set up at " + wire.device());

  TickLoop loop(cfg.built.model, *hw);
  loop.jaw_rad = 0.0;
  Controller& controller = loop.controller;
  auto run = [&](std::chrono::milliseconds limit, auto done) { return loop.run(limit, done); };
  std::int32_t rest_goal = 0;
  wire.with_servo(1, [&](sim::FeetechServoSim& s) { rest_goal = s.present(); });
  controller.request_enable();
  ASSERT_TRUE(run(5000ms, [&] { return controller.state() == SafetyState::kRunning; }))
      << to_string(controller.state()) << " " << hw->seams.at(0)->status().reason;
  bool torque = false;
  EXPECT_TRUE(run(500ms, [&] {
    wire.with_servo(1, [&](sim::FeetechServoSim& s) { torque = s.torque(); });
    return torque;
  })) << "torque on while running";
  loop.jaw_rad = 10.0 * 3.14159265358979 / 180.0;
  std::int32_t goal = rest_goal;
  ASSERT_TRUE(run(3000ms,
                  [&] {
                    wire.with_servo(1, [&](sim::FeetechServoSim& s) { goal = s.goal(); });
                    return std::abs(goal - rest_goal) > 100;
                  }))
      << goal << " vs rest " << rest_goal;
  EXPECT_EQ(controller.state(), SafetyState::kRunning) << hw->seams.at(0)->status().reason;

  chip->set_physical(3, true);  // e-stop pressed
  ASSERT_TRUE(run(100ms, [&] { return controller.state() == SafetyState::kEstop; }));
  EXPECT_FALSE(chip->physical(4)) << "power dropped in ESTOP";
  ASSERT_TRUE(run(500ms, [&] {
    wire.with_servo(1, [&](sim::FeetechServoSim& s) { torque = s.torque(); });
    return !torque;
  })) << "torque off in ESTOP";
}

}  // namespace
}  // namespace facectl
