// The real ModbusBus (libmodbus, its own I/O thread) against simulated
// actuator boards served by a real libmodbus server: TCP on 127.0.0.1 and RTU
// over a pseudo-terminal pair. Faults are injected into the server's replies
// and into the boards. The bounds asserted here are the ones docs/PROTOCOLS.md
// documents.
#include "drivers/modbus/modbus_bus.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <thread>

#include "sim/devices/modbus_board_server.hpp"

namespace facectl {
namespace {

using namespace std::chrono_literals;
using sim::BoardChannel;
using sim::ModbusActuatorBoard;
using sim::ModbusBoardServer;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

std::vector<BoardChannel> channels(std::size_t n) {
  std::vector<BoardChannel> c(n);
  for (auto& ch : c) {
    ch.plant.time_constant_s = 0.01;
    ch.plant.max_velocity = 10.0;
    ch.plant.latency_s = 0.0;
  }
  return c;
}

std::vector<ActuatorModel> actuators(int first_address, int count) {
  std::vector<ActuatorModel> a(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    a[static_cast<std::size_t>(i)].name = "servo" + std::to_string(i);
    a[static_cast<std::size_t>(i)].address = first_address + i;
  }
  return a;
}

// Runs a 1 kHz "tick" on its own thread against the bus, as the controller
// does, and records the longest time any seam call took.
class Tick {
 public:
  Tick(ActuatorBus& bus, std::size_t n, std::function<double(std::size_t, double)> target)
      : bus_(bus), n_(n), target_(std::move(target)) {
    thread_ = std::thread([this] { run(); });
  }
  ~Tick() { stop(); }
  void stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  void pause(bool p) { paused_ = p; }
  std::int64_t max_call_ns() const { return max_call_ns_; }
  // What the tick last read. Only the tick's thread calls the bus: read()
  // and write() are one thread's calls (the seam's contract; TSan caught this
  // test reading from a second thread).
  std::vector<double> measured() {
    const std::lock_guard<std::mutex> lock(last_mutex_);
    return last_;
  }

 private:
  void run() {
    const std::int64_t t0 = now_ns();
    std::vector<double> cmd(n_), meas(n_);
    auto next = std::chrono::steady_clock::now();
    while (!stop_) {
      next += 1ms;
      std::this_thread::sleep_until(next);
      if (paused_) continue;
      const double t = static_cast<double>(now_ns() - t0) * 1e-9;
      for (std::size_t i = 0; i < n_; ++i) cmd[i] = target_(i, t);
      const std::int64_t a = now_ns();
      bus_.read({a, 0.001}, meas);
      {
        const std::lock_guard<std::mutex> lock(last_mutex_);
        last_ = meas;
      }
      bus_.write({a, 0.001}, cmd);
      (void)bus_.status();
      max_call_ns_ = std::max(max_call_ns_.load(), now_ns() - a);
    }
  }
  ActuatorBus& bus_;
  std::size_t n_;
  std::function<double(std::size_t, double)> target_;
  std::atomic<bool> stop_{false}, paused_{false};
  std::atomic<std::int64_t> max_call_ns_{0};
  std::mutex last_mutex_;
  std::vector<double> last_ = std::vector<double>(n_);
  std::thread thread_;
};

// Waits up to `limit` for `pred`; returns the time it took, or -1 s.
double wait_for(const std::function<bool()>& pred, std::chrono::milliseconds limit) {
  const auto t0 = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - t0 < limit) {
    if (pred()) return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::this_thread::sleep_for(1ms);
  }
  return -1.0;
}

class ModbusTcp : public ::testing::Test {
 protected:
  void SetUp() override {
    server_ = ModbusBoardServer::tcp({&board1_, &board2_});
    ModbusEndpoint ep;
    ep.tcp = true;
    ep.host = "127.0.0.1";
    ep.port = server_->port();
    bus_ = std::make_unique<ModbusBus>("modbus0", ep, actuators(1, 14),
                                       std::vector<double>(14, 0.0), timing_);
  }
  void TearDown() override {
    tick_.reset();
    bus_.reset();
    server_.reset();
  }
  void start_tick(std::function<double(std::size_t, double)> f = [](std::size_t i, double) {
    return (static_cast<double>(i) + 1.0) * kDeg;
  }) {
    tick_ = std::make_unique<Tick>(*bus_, 14, std::move(f));
  }
  // Documented fault bound: board_timeout_s plus one worst-case I/O cycle (two
  // boards, two transactions each, every attempt timing out).
  double fault_bound_s() const {
    return timing_.board_timeout_s +
           2 * 2 * (1 + timing_.max_retries) * timing_.response_timeout_s + 0.02;
  }

  ModbusTiming timing_{};
  ModbusActuatorBoard board1_{1, channels(8)};
  ModbusActuatorBoard board2_{2, channels(6)};
  std::unique_ptr<ModbusBoardServer> server_;
  std::unique_ptr<ModbusBus> bus_;
  std::unique_ptr<Tick> tick_;
};

TEST_F(ModbusTcp, EnabledBoardsFollowTheCommandedTargetsAndReportPositions) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board2_.enabled() && board2_.target_writes() > 200; }, 3000ms), 0)
      << "board 2 never received targets";
  std::this_thread::sleep_for(100ms);
  for (std::size_t ch = 0; ch < 8; ++ch) {
    EXPECT_NEAR(board1_.target(ch), static_cast<double>(ch + 1) * kDeg, 0.005 * kDeg);
    EXPECT_NEAR(board1_.position(ch), static_cast<double>(ch + 1) * kDeg, 0.05 * kDeg);
  }
  EXPECT_NEAR(board2_.target(5), 14.0 * kDeg, 0.005 * kDeg);  // address 14 = unit 2, channel 5
  const std::vector<double> m = tick_->measured();
  for (std::size_t i = 0; i < 14; ++i)
    EXPECT_NEAR(m[i], static_cast<double>(i + 1) * kDeg, 0.05 * kDeg);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  EXPECT_FALSE(bus_->command_stale(0));
  // One write-multiple per board per cycle at most.
  EXPECT_LE(board1_.target_writes(), bus_->stats().cycles);
  EXPECT_EQ(bus_->stats().failures, 0u);
}

TEST_F(ModbusTcp, TheTickNeverBlocksWhileTheIoThreadWaitsOnTimeouts) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  server_->faults().delay_us = 30'000;  // every reply later than the 20 ms timeout
  std::this_thread::sleep_for(400ms);
  EXPECT_GT(bus_->stats().timeouts, 4u);
  // Far below one I/O timeout: the tick only touched mailboxes and atomics.
  EXPECT_LT(tick_->max_call_ns(), 2'000'000)
      << "a seam call took " << tick_->max_call_ns() << " ns";
}

TEST_F(ModbusTcp, ASilentBoardFaultsWithinTheDocumentedBoundAndItsCommandsGoStale) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  ASSERT_FALSE(bus_->status().fault);
  server_->faults().silent = true;
  const double t = wait_for([&] { return bus_->status().fault; }, 2000ms);
  ASSERT_GT(t, 0.0) << "no FAULT";
  EXPECT_GE(t, timing_.board_timeout_s - 0.01);
  EXPECT_LE(t, fault_bound_s());
  // The whole server is silent: whichever board's timeout expires first names itself.
  EXPECT_NE(std::string(bus_->status().reason).find(": not answering"), std::string::npos)
      << bus_->status().reason;
  EXPECT_GT(wait_for([&] { return bus_->command_stale(0) && bus_->command_stale(13); },
                     std::chrono::milliseconds(static_cast<int>(fault_bound_s() * 1000))),
            0)
      << "the silent boards' commands were not marked stale";
  // The boards' own watchdog drops their outputs: nobody feeds them any more.
  EXPECT_GT(wait_for([&] { return !board1_.enabled() && board1_.watchdog_tripped(); }, 500ms), 0);
  // Retries are bounded: at most 1 + max_retries attempts per transaction.
  const ModbusStats s = bus_->stats();
  EXPECT_LE(s.timeouts, (s.cycles + 2) * 4 * static_cast<std::uint64_t>(1 + timing_.max_retries));
}

TEST_F(ModbusTcp, ExceptionResponsesFaultWithTheirOwnReason) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  server_->faults().exception_code = 4;  // server device failure
  const double t = wait_for([&] { return bus_->status().fault; }, 2000ms);
  ASSERT_GT(t, 0.0);
  EXPECT_LE(t, fault_bound_s());
  EXPECT_NE(std::string(bus_->status().reason).find("exception responses"), std::string::npos)
      << bus_->status().reason;
  EXPECT_GT(bus_->stats().exceptions, 0u);
}

TEST_F(ModbusTcp, CorruptRepliesAreRejectedAndFaultWithTheirOwnReason) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  server_->faults().corrupt_next = 1'000'000;
  const double t = wait_for([&] { return bus_->status().fault; }, 2000ms);
  ASSERT_GT(t, 0.0);
  EXPECT_LE(t, fault_bound_s());
  EXPECT_NE(std::string(bus_->status().reason).find("corrupt replies"), std::string::npos)
      << bus_->status().reason;
  EXPECT_GT(bus_->stats().bad_replies, 0u);
}

TEST_F(ModbusTcp, ADroppedConnectionIsReopenedWithoutAFault) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  server_->faults().close_connection = true;
  ASSERT_GT(wait_for([&] { return server_->connections() >= 2; }, 1000ms), 0) << "no reconnect";
  const std::uint64_t writes = board1_.target_writes();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > writes + 50; }, 1000ms), 0);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
  EXPECT_GE(bus_->stats().link_errors, 1u);
}

TEST_F(ModbusTcp, AnIntermittentTimeoutStormIsRiddenOutByBoundedRetries) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  server_->faults().drop_every = 3;  // every third request unanswered
  std::this_thread::sleep_for(500ms);
  EXPECT_GT(bus_->stats().timeouts, 5u);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(ModbusTcp, ABoardReportedFaultReachesTheBusStatus) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board2_.target_writes() > 50; }, 3000ms), 0);
  board2_.inject_fault(modbus_map::FaultCode::kOverTemperature);
  ASSERT_GT(wait_for([&] { return bus_->status().fault; }, 200ms), 0);
  EXPECT_STREQ(bus_->status().reason, "modbus0 board 2: reports a fault");
  EXPECT_FALSE(board2_.enabled());
}

TEST_F(ModbusTcp, NoTargetIsSentOnceDisabledAsInEstop) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  bus_->set_enabled(false);  // what the controller does on the ESTOP tick
  ASSERT_GT(wait_for([&] { return !board1_.enabled() && !board2_.enabled(); }, 100ms), 0)
      << "boards not disabled within 100 ms";
  const std::uint64_t w1 = board1_.target_writes();
  const std::uint64_t w2 = board2_.target_writes();
  std::this_thread::sleep_for(200ms);  // the tick keeps calling write(): it must be ignored
  EXPECT_EQ(board1_.target_writes(), w1);
  EXPECT_EQ(board2_.target_writes(), w2);
  EXPECT_EQ(board1_.target_writes_while_disabled() + board2_.target_writes_while_disabled(), 0u);
  EXPECT_FALSE(bus_->status().fault);
}

TEST_F(ModbusTcp, ABoardSwitchedOffAloneGetsNoTargetsWhileTheOtherRuns) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board2_.target_writes() > 50; }, 3000ms), 0);
  // FAULT with a relax actuator on unit 2 (address 9), hold ones elsewhere:
  // its board-mates (addresses 10..14) are switched off with it.
  std::array<std::uint8_t, 14> on{};
  on.fill(1);
  on[8] = 0;
  bus_->set_actuators_enabled(on);
  EXPECT_EQ(std::count(on.begin(), on.begin() + 8, std::uint8_t{1}), 8);
  EXPECT_EQ(std::count(on.begin() + 8, on.end(), std::uint8_t{0}), 6);
  ASSERT_GT(wait_for([&] { return !board2_.enabled(); }, 100ms), 0)
      << "board 2 not disabled within 100 ms";
  const std::uint64_t w1 = board1_.target_writes(), w2 = board2_.target_writes();
  std::this_thread::sleep_for(200ms);
  EXPECT_EQ(board2_.target_writes(), w2);
  EXPECT_GT(board1_.target_writes(), w1 + 50) << "board 1 is still commanded";
  EXPECT_TRUE(board1_.enabled());
  EXPECT_FALSE(board1_.watchdog_tripped());
  EXPECT_EQ(board2_.target_writes_while_disabled(), 0u);
  EXPECT_FALSE(bus_->status().fault) << bus_->status().reason;
}

TEST_F(ModbusTcp, ACommandWrittenBeforeADisableIsNeverSentAfterTheNextEnable) {
  bus_->set_enabled(true);
  std::vector<double> cmd(14, 1.0 * kDeg);
  for (int i = 0; i < 50; ++i) {
    bus_->write({now_ns(), 0.001}, cmd);
    std::this_thread::sleep_for(1ms);
  }
  ASSERT_NEAR(board1_.target(0), 1.0 * kDeg, 0.01 * kDeg);
  server_->faults().silent = true;  // the next write cannot get through
  std::this_thread::sleep_for(5ms);
  std::fill(cmd.begin(), cmd.end(), 10.0 * kDeg);
  bus_->write({now_ns(), 0.001}, cmd);
  bus_->set_enabled(false);
  bus_->set_enabled(true);  // re-enabled before the I/O thread noticed, and no write since
  std::this_thread::sleep_for(50ms);
  server_->faults().silent = false;
  std::this_thread::sleep_for(300ms);
  EXPECT_NEAR(board1_.target(0), 1.0 * kDeg, 0.01 * kDeg)
      << "the 10 degree command from before the disable reached the board";
}

TEST_F(ModbusTcp, ADeadTickStopsTheHeartbeatAndTheBoardWatchdogTrips) {
  bus_->set_enabled(true);
  start_tick();
  ASSERT_GT(wait_for([&] { return board1_.target_writes() > 50; }, 3000ms), 0);
  tick_->pause(true);  // the real-time loop hangs; the I/O thread lives on
  const double t = wait_for([&] { return board1_.watchdog_tripped(); }, 1000ms);
  ASSERT_GT(t, 0.0) << "board kept its outputs on without fresh commands";
  EXPECT_LE(t, timing_.board_watchdog_ms * 1e-3 + 0.02);
  ASSERT_GT(wait_for([&] { return bus_->status().fault; }, 100ms), 0);
  EXPECT_STREQ(bus_->status().reason, "modbus0 board 1: watchdog tripped");
}

TEST(ModbusRtu, APtyBoardFollowsCommandsAndASilentOneFaults) {
  ModbusActuatorBoard board{1, channels(4)};
  auto server = ModbusBoardServer::rtu_pty(&board, 115200);
  ModbusTiming timing;
  timing.cycle_period_s = 0.002;
  ModbusBus bus("modbus_rtu0", ModbusEndpoint::parse("modbus_rtu", server->device(), 115200),
                actuators(1, 4), std::vector<double>(4, 0.0), timing);
  bus.set_enabled(true);
  {
    Tick tick(bus, 4,
              [](std::size_t i, double) { return -2.0 * static_cast<double>(i + 1) * kDeg; });
    ASSERT_GT(wait_for([&] { return board.target_writes() > 100; }, 3000ms), 0)
        << "no targets over " << server->device();
    std::this_thread::sleep_for(100ms);
    for (std::size_t ch = 0; ch < 4; ++ch) {
      EXPECT_NEAR(board.target(ch), -2.0 * static_cast<double>(ch + 1) * kDeg, 0.005 * kDeg);
    }
    const std::vector<double> m = tick.measured();
    EXPECT_NEAR(m[3], -8.0 * kDeg, 0.05 * kDeg);
    EXPECT_FALSE(bus.status().fault) << bus.status().reason;
    EXPECT_EQ(bus.stats().failures, 0u);

    server->faults().silent = true;
    const double t = wait_for([&] { return bus.status().fault; }, 2000ms);
    ASSERT_GT(t, 0.0);
    EXPECT_LE(t, timing.board_timeout_s + 2 * (1 + timing.max_retries) * timing.response_timeout_s +
                     0.02);
    EXPECT_STREQ(bus.status().reason, "modbus_rtu0 board 1: not answering within 20 ms");
  }
}

// docs/PROTOCOLS.md's worked example, checked on the wire: the bytes the
// driver puts on a serial line (the master side of a pty, nobody answering).
TEST(ModbusRtu, TheDocumentedFirstCycleBytesAreWhatGoesOnTheWire) {
  int master = -1;
  int slave = -1;
  char name[128] = {};
  ASSERT_EQ(openpty(&master, &slave, name, nullptr, nullptr), 0);
  termios tio{};
  tcgetattr(slave, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave, TCSANOW, &tio);
  auto acts = actuators(1, 3);
  acts[2].kind = ActuatorKind::kLinear;
  std::vector<std::uint8_t> wire;
  {
    ModbusBus bus("m", ModbusEndpoint::parse("modbus_rtu", name, 115200), acts, {0.0, 0.0, 0.0});
    bus.set_enabled(true);
    const std::vector<double> cmd{12.5 * kDeg, -4.0 * kDeg, 0.0035};
    bus.write({now_ns(), 0.001}, cmd);
    const auto end = std::chrono::steady_clock::now() + 300ms;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{master, POLLIN, 0};
      if (poll(&p, 1, 10) <= 0) continue;
      std::uint8_t buf[256];
      const ssize_t n = ::read(master, buf, sizeof buf);
      if (n > 0) wire.insert(wire.end(), buf, buf + n);
    }
  }
  close(master);
  close(slave);
  const auto contains = [&](const std::vector<std::uint8_t>& frame) {
    return std::search(wire.begin(), wire.end(), frame.begin(), frame.end()) != wire.end();
  };
  EXPECT_TRUE(contains({0x01, 0x06, 0x00, 0x0A, 0x00, 0x64, 0xA8, 0x23})) << "watchdog write";
  EXPECT_TRUE(contains({0x01, 0x10, 0x00, 0x00, 0x00, 0x05, 0x0A, 0x00, 0x03, 0x00, 0x01, 0x04,
                        0xE2, 0xFE, 0x70, 0x01, 0x5E, 0x4C, 0x01}))
      << "first target write";
  EXPECT_TRUE(contains({0x01, 0x04, 0x00, 0x00, 0x00, 0x07, 0xB1, 0xC8})) << "input read";
}

TEST(ModbusConfig, BadEndpointsAndAddressesAreRefusedWithTheirNames) {
  EXPECT_THROW(ModbusEndpoint::parse("modbus_rtu", "/dev/ttyUSB0", 1234567), std::invalid_argument);
  EXPECT_THROW(ModbusEndpoint::parse("modbus_tcp", "board:99999", 0), std::invalid_argument);
  EXPECT_EQ(ModbusEndpoint::parse("modbus_tcp", "10.0.0.5:1502", 0).port, 1502);
  EXPECT_EQ(ModbusEndpoint::parse("modbus_tcp", "10.0.0.5", 0).port, 502);
  auto dup = actuators(1, 2);
  dup[1].address = 1;
  try {
    ModbusBus bus("m", ModbusEndpoint{}, dup, {0.0, 0.0});
    FAIL() << "two actuators on one address accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("share address 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace facectl
