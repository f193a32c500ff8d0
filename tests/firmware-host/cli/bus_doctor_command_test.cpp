// `facectl bus doctor RIG` as a user runs it, against a simulated Modbus
// actuator board behind a real libmodbus TCP server on 127.0.0.1.
#include <gtest/gtest.h>

#include "sim/devices/modbus_board_server.hpp"
#include "tests/drivers/can_test_axes.hpp"
#include "tests/drivers/facectl_process.hpp"
#include "tests/drivers/modbus_tcp_rig.hpp"

namespace facectl {
namespace {

using testing::run_facectl;

std::vector<sim::BoardChannel> channels(int n) {
  std::vector<sim::BoardChannel> c(static_cast<std::size_t>(n));
  for (auto& ch : c) ch.plant = testing::fast_plant();
  return c;
}

TEST(BusDoctorCommand, AHealthyModbusTcpBoardIsOkWithItsRoundTrips) {
  sim::ModbusActuatorBoard board(1, channels(3));
  auto server = sim::ModbusBoardServer::tcp({&board});
  testing::ModbusTcpRig files(server->port());
  std::string out;
  EXPECT_EQ(run_facectl("bus doctor " + files.rig.path() + " --config " + files.runtime.path() +
                            " --samples 10",
                        out),
            0)
      << out;
  EXPECT_NE(out.find("modbus0 (Modbus TCP 127.0.0.1:" + std::to_string(server->port()) + ")"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  ok   board 1: round trip min"), std::string::npos) << out;
  EXPECT_NE(out.find("0 of 10 reads failed"), std::string::npos) << out;
  EXPECT_NE(out.find("no problems found"), std::string::npos) << out;
  EXPECT_EQ(board.enabled(), false) << "the doctor only reads";
  std::printf("%s", out.c_str());
}

TEST(BusDoctorCommand, ASilentBoardIsAProblem) {
  sim::ModbusActuatorBoard board(1, channels(3));
  auto server = sim::ModbusBoardServer::tcp({&board});
  server->faults().drop_every = 1;  // never answers
  testing::ModbusTcpRig files(server->port());
  std::string out;
  EXPECT_EQ(run_facectl("bus doctor " + files.rig.path() + " --config " + files.runtime.path() +
                            " --samples 3",
                        out),
            1)
      << out;
  EXPECT_NE(out.find("  FAIL board 1: does not answer"), std::string::npos) << out;
  EXPECT_NE(out.find("problems found"), std::string::npos) << out;
}

TEST(BusDoctorCommand, UnusableInputIsExitCode2AndTheDefaultRigIsUnreachableHere) {
  std::string out;
  EXPECT_EQ(run_facectl("bus doctor /nonexistent/rig.yaml", out), 2) << out;
  EXPECT_NE(out.find("/nonexistent/rig.yaml: cannot open file"), std::string::npos) << out;
  EXPECT_EQ(run_facectl("bus doctor --bus can9", out), 2) << out;
  EXPECT_NE(out.find("--bus: expected a bus of rig 'default', found 'can9'"), std::string::npos)
      << out;
  // This machine has neither CAN nor /dev/ttyUSB0: both buses are problems,
  // and the CAN bus still gets its load line.
  EXPECT_EQ(run_facectl("bus doctor --samples 1", out), 1) << out;
  EXPECT_NE(out.find("  ok   load: can0: 8 frames per cycle at 250 Hz = 270000 bit/s, 27.0%"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("  FAIL cannot open: SocketCAN can0"), std::string::npos) << out;
  EXPECT_NE(out.find("modbus0 (Modbus RTU /dev/ttyUSB0"), std::string::npos) << out;
}

}  // namespace
}  // namespace facectl
