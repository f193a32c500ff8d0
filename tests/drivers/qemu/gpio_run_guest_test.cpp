// Runs inside the QEMU guest: `facectl run --hardware real` as a user runs
// it, with its safety_io on a gpio-sim chip (libgpiod, the kernel's GPIO
// character device) and its rig on a simulated Modbus board behind a real
// libmodbus server on 127.0.0.1. Mid-run the e-stop line is pressed, or the
// chip taken away, from the simulator's side; the power-enable pin must drop
// and the run must end in ESTOP or FAULT.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "sim/devices/modbus_board_server.hpp"
#include "tests/drivers/qemu/gpio_sim_configfs.hpp"

namespace facectl {
namespace {

using Clock = std::chrono::steady_clock;
using testing::GpioSimDevice;

// A rig of three jaw actuators on board 1 of a Modbus TCP bus at `port`, and
// a runtime file on the guest's head (/cfg/head.yaml) that holds the neutral
// face, with the safety I/O on `chip` (e-stop line 0, power-enable line 1).
// 250 Hz, a high overrun limit and slack timeouts: the emulated CPU is slow
// and shared, and a FAULT of the loop or the bus would hide what this test
// looks for.
void write_run_files(int port, const std::string& chip) {
  std::string rig =
      "rig:\n  name: gpio\n  buses:\n    - { name: modbus0, type: modbus_tcp, host: 127.0.0.1:" +
      std::to_string(port) +
      ", response_timeout_ms: 50, retries: 2, fault_after_ms: 2000, watchdog_ms: 2000 }\n" +
      "  actuators:\n";
  const char* signals[] = {"jaw_pitch_deg", "jaw_yaw_deg", "neck_pan_deg"};
  for (int i = 0; i < 3; ++i) {
    rig += "    - { name: a" + std::to_string(i + 1) +
           ", kind: rotary, bus: modbus0, address: " + std::to_string(i + 1) +
           ", position_deg: { min: -20, max: 20 }, max_velocity_deg_s: 100, "
           "max_acceleration_deg_s2: 1000, rest_deg: 0, map: { terms: { " +
           signals[i] + ": 1 } } }\n";
  }
  std::ofstream("/tmp/gpio_rig.yaml") << rig;
  std::ofstream("/tmp/gpio_expressions.yaml") << "expressions:\n  neutral: {}\n";
  std::ofstream("/tmp/gpio_show.yaml")
      << "show:\n  name: hold\n  keyframes:\n    - { t: 0.0, expression: neutral }\n"
         "    - { t: 60.0, expression: neutral }\n";
  std::ofstream("/tmp/gpio_runtime.yaml")
      << "runtime: { rate_hz: 250, overrun_fault_count: 100000, realtime: { priority: 0, "
         "cpu: -1, lock_memory: false, cpu_dma_latency_us: -1 } }\n"
         "head: /cfg/head.yaml\nrig: /tmp/gpio_rig.yaml\n"
         "expressions: /tmp/gpio_expressions.yaml\nshow: /tmp/gpio_show.yaml\n"
         "hardware: real\nsafety_io: { chip: "
      << chip << ", estop_line: 0, power_line: 1, release_debounce_ms: 5 }\n";
}

// `facectl run` on its own thread, for at most 30 s of show.
class FacectlRun {
 public:
  FacectlRun()
      : thread_([this] {
          status_ = std::system(
              "/bin/facectl run --config /tmp/gpio_runtime.yaml --duration 30 "
              "> /tmp/gpio_run.txt 2>&1");
        }) {}
  ~FacectlRun() {
    if (thread_.joinable()) thread_.join();
  }
  // Waits for the run to end; its exit code and what it printed.
  int finish(std::string& out) {
    thread_.join();
    std::stringstream s;
    s << std::ifstream("/tmp/gpio_run.txt").rdbuf();
    out = s.str();
    // Shown on the console's filtered copy (run_in_qemu.sh keeps FACECTL lines).
    std::printf("FACECTL-QEMU: gpio: facectl run exited %d\n", WEXITSTATUS(status_));
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) {
      std::printf("FACECTL-QEMU: gpio: | %s\n", line.c_str());
    }
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }

 private:
  int status_ = -1;
  std::thread thread_;
};

// Polls `pred` every millisecond for at most `limit`; the time it took, or -1.
template <class Pred>
double wait_ms(std::chrono::milliseconds limit, Pred pred) {
  const auto t0 = Clock::now();
  while (Clock::now() - t0 < limit) {
    if (pred()) return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return -1.0;
}

class FacectlRunOnGpio : public ::testing::Test {
 protected:
  void SetUp() override {
    if (access(testing::kGpioSimModule, F_OK) != 0) {
      GTEST_SKIP() << "gpio-sim not built: " << testing::kGpioSimModule
                   << " missing (packages linux-source-6.1, linux-headers-amd64; "
                      "tests/drivers/qemu/build_gpio_sim.sh)";
    }
    // The ctest entry always passes the binary to run_in_qemu.sh: missing is a failure.
    ASSERT_EQ(access("/bin/facectl", X_OK), 0) << "no /bin/facectl in this guest";
    board_ = std::make_unique<sim::ModbusActuatorBoard>(1, std::vector<sim::BoardChannel>(3));
    server_ = sim::ModbusBoardServer::tcp({board_.get()});
  }
  std::unique_ptr<sim::ModbusActuatorBoard> board_;
  std::unique_ptr<sim::ModbusBoardServer> server_;
};

TEST_F(FacectlRunOnGpio, TheEstopPressedMidRunDropsPowerAndEndsInEstop) {
  GpioSimDevice sim("facectl-run-estop");
  write_run_files(server_->port(), sim.name());
  FacectlRun run;
  // Power-enable comes on with ENABLING; let the run settle into RUNNING.
  const double on_ms = wait_ms(std::chrono::seconds(30), [&] { return sim.level(1) == 1; });
  ASSERT_GE(on_ms, 0.0) << "power-enable never came on";
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_EQ(sim.level(1), 1) << "power-enable dropped before the press";

  sim.drive(0, true);  // pressed, and held
  const double off_ms = wait_ms(std::chrono::seconds(2), [&] { return sim.level(1) == 0; });
  std::printf(
      "FACECTL-QEMU: gpio: power-enable on %.0f ms after the start, off %.1f ms after the press\n",
      on_ms, off_ms);
  EXPECT_GE(off_ms, 0.0) << "power-enable stayed on with the e-stop pressed";

  std::string out;
  EXPECT_EQ(run.finish(out), 3) << "an ESTOP run exits 3";
  EXPECT_NE(out.find("RUNNING -> ESTOP: e-stop input active"), std::string::npos);
  EXPECT_NE(out.find("final state ESTOP"), std::string::npos);
  EXPECT_EQ(out.find("-> FAULT"), std::string::npos) << "an e-stop, not a fault";
  EXPECT_EQ(sim.level(1), 0);
}

// An unreadable e-stop reads pressed and is a safety I/O fault at once; the
// e-stop wins over faults (docs/SAFETY.md, "States"), so the run reports
// ESTOP. Either way power-enable is off and the run ends.
TEST_F(FacectlRunOnGpio, TheChipVanishingMidRunStopsTheRun) {
  GpioSimDevice sim("facectl-run-vanish");
  write_run_files(server_->port(), sim.name());
  FacectlRun run;
  ASSERT_GE(wait_ms(std::chrono::seconds(30), [&] { return sim.level(1) == 1; }), 0.0)
      << "power-enable never came on";
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ASSERT_EQ(sim.level(1), 1) << "power-enable dropped before the chip went";
  sim.vanish();  // the pin goes with the chip: nothing to read back

  std::string out;
  EXPECT_EQ(run.finish(out), 3) << "an ESTOP or FAULT run exits 3";
  const bool estop = out.find("RUNNING -> ESTOP: e-stop input active") != std::string::npos;
  const bool fault = out.find("RUNNING -> FAULT: safety I/O fault") != std::string::npos;
  EXPECT_TRUE(estop || fault) << "the run went on without its e-stop";
  EXPECT_TRUE(out.find("final state ESTOP") != std::string::npos ||
              out.find("final state FAULT") != std::string::npos);
}

}  // namespace
}  // namespace facectl
