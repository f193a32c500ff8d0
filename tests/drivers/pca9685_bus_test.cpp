// The real Pca9685Bus (its own I/O thread) against simulated PCA9685s on an
// in-memory I2C bus: the start-up sequence, pulses on the right board and
// channel, full-off on disable, bumpless enable, and the fault matrix (a
// board not answering, a wrong read-back, a board that resets).
#include "drivers/i2c/pca9685_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>
#include <thread>

#include "drivers/i2c/pca9685_doctor.hpp"
#include "sim/devices/memory_i2c_bus.hpp"
#include "tests/drivers/pca9685_test_servos.hpp"
#include "tests/support/temp_dir.hpp"

namespace facectl {
namespace {

using sim::MemoryI2cBus;
using sim::Pca9685Sim;

using testing::kThreeCounts;
using testing::kThreePositions;
constexpr double kDeg = testing::kPwmDeg;

bool wait_for(const std::function<bool()>& ok) {
  return testing::wait_until(ok, 2.0);
}

// The bus owns its transport; this one forwards to a twin the test keeps, so
// the boards can be inspected after the bus is gone.
struct Forward final : I2cTransport {
  std::shared_ptr<MemoryI2cBus> to;
  explicit Forward(std::shared_ptr<MemoryI2cBus> t) : to(std::move(t)) {}
  int write_byte(int a, std::uint8_t r, std::uint8_t v) override { return to->write_byte(a, r, v); }
  int write_block(int a, std::uint8_t r, std::span<const std::uint8_t> d) override {
    return to->write_block(a, r, d);
  }
  int read_byte(int a, std::uint8_t r) override { return to->read_byte(a, r); }
  std::string where() const override { return to->where(); }
};

struct Rig {
  std::shared_ptr<MemoryI2cBus> i2c = std::make_shared<MemoryI2cBus>();
  std::unique_ptr<Pca9685Bus> bus;

  // Two boards, 0x40 and 0x41: jaw on 0x40 channel 0, eye on 0x40 channel 3,
  // brow on 0x41 channel 1 (address 18).
  explicit Rig(std::initializer_list<int> present = {0x40, 0x41},
               const std::function<void(MemoryI2cBus&)>& before = {}) {
    for (int a : present) i2c->attach(a);
    if (before) before(*i2c);
    Pca9685Options o;
    o.boards = {0x40, 0x41};
    o.cycle_period_s = 0.002;
    o.retry_init_s = 0.01;
    bus = std::make_unique<Pca9685Bus>("servos", std::make_unique<Forward>(i2c),
                                       testing::three_pwm_servos(),
                                       std::vector<double>{90 * kDeg, 0.0, 0.0}, o);
  }
  int off(int address, int channel) {
    return i2c->with(address, [&](Pca9685Sim& c) {
      const auto r = c.led(channel);
      return (r[3] & pca9685::kLedFull) ? -1 : r[2] | ((r[3] & 0x0F) << 8);
    });
  }
  std::string reason() const { return bus->status().reason; }
  // Both boards set up, the bus enabled and kThreePositions written and seen.
  bool running() {
    if (!wait_for([&] { return bus->boards_ready() == 2; })) return false;
    bus->set_enabled(true);
    bus->write({}, kThreePositions);
    return wait_for([&] { return off(0x41, 1) == kThreeCounts[2]; });
  }
};

TEST(Pca9685Bus, StartUpSetsPrescaleWakesWithAutoIncrementAndAllOff) {
  Rig rig;
  ASSERT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 2; }));
  for (int a : {0x40, 0x41}) {
    rig.i2c->with(a, [&](Pca9685Sim& c) {
      EXPECT_EQ(c.reg(pca9685::kPreScale), 121) << a;  // 50 Hz
      EXPECT_EQ(c.reg(pca9685::kMode1), pca9685::kMode1AutoIncrement) << a;
      EXPECT_EQ(c.reg(pca9685::kMode2), pca9685::kMode2OutDrv) << a;
      for (int ch = 0; ch < 16; ++ch) EXPECT_TRUE(c.full_off(ch)) << a << " ch " << ch;
    });
  }
  EXPECT_FALSE(rig.bus->status().fault);
  EXPECT_NEAR(rig.bus->actual_pwm_hz(), 50.0288, 1e-4);
}

TEST(Pca9685Bus, WritesPulsesOnTheRightBoardAndChannel) {
  Rig rig;
  ASSERT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 2; }));
  rig.bus->set_enabled(true);
  const auto& pos = kThreePositions;
  rig.bus->write({}, pos);
  // jaw 600 + 600 = 1200 µs -> 245.9; eye 1800 µs -> 368.85; brow 2400 µs -> 491.8.
  EXPECT_TRUE(wait_for([&] { return rig.off(0x40, 0) == 246; })) << rig.off(0x40, 0);
  EXPECT_EQ(rig.off(0x40, 3), 369);
  EXPECT_TRUE(wait_for([&] { return rig.off(0x41, 1) == 492; })) << rig.off(0x41, 1);
  EXPECT_EQ(rig.off(0x40, 1), -1);  // unused channels stay off
  EXPECT_EQ(rig.off(0x41, 0), -1);
  std::array<double, 3> read{};
  rig.bus->read({}, read);
  EXPECT_EQ(read, pos);  // no feedback: the last commanded position
  EXPECT_FALSE(rig.bus->status().fault);
}

TEST(Pca9685Bus, DisableGoesFullOffAndEnableHoldsTheLastCommand) {
  Rig rig;
  ASSERT_TRUE(rig.running());
  const auto& pos = kThreePositions;
  // Per actuator: only the eye goes limp.
  std::array<std::uint8_t, 3> flags{1, 0, 1};
  rig.bus->set_actuators_enabled(flags);
  EXPECT_EQ(flags, (std::array<std::uint8_t, 3>{1, 0, 1}));  // per channel: nothing else off
  EXPECT_TRUE(wait_for([&] { return rig.off(0x40, 3) == -1; }));
  EXPECT_EQ(rig.off(0x40, 0), 246);
  EXPECT_EQ(rig.off(0x41, 1), 492);
  // The whole bus.
  rig.bus->set_enabled(false);
  EXPECT_TRUE(wait_for([&] { return rig.off(0x40, 0) == -1 && rig.off(0x41, 1) == -1; }));
  const std::array<double, 3> ignored{0, 0, 0};
  rig.bus->write({}, ignored);  // not enabled: dropped
  std::array<double, 3> read{};
  rig.bus->read({}, read);
  EXPECT_EQ(read, pos);
  // Enabled again without a write: held where read() says, not 0.
  rig.bus->set_enabled(true);
  EXPECT_TRUE(wait_for([&] { return rig.off(0x40, 0) == 246 && rig.off(0x41, 1) == 492; }));
  EXPECT_EQ(rig.off(0x40, 3), 369);
}

TEST(Pca9685Bus, StopLeavesEveryOutputOff) {
  Rig rig;
  ASSERT_TRUE(rig.running());
  rig.bus.reset();  // facectl stopping
  for (int a : {0x40, 0x41}) {
    for (int ch = 0; ch < 16; ++ch) EXPECT_EQ(rig.off(a, ch), -1) << a << " ch " << ch;
  }
}

TEST(Pca9685BusFaults, ABoardNotAnsweringIsAFaultNamingIt) {
  Rig rig({0x40});  // 0x41 absent: no ACK
  ASSERT_TRUE(wait_for([&] { return rig.bus->status().fault; }));
  EXPECT_NE(rig.reason().find("servos board 0x41"), std::string::npos) << rig.reason();
  EXPECT_NE(rig.reason().find("not answering"), std::string::npos) << rig.reason();
  EXPECT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 1; }));
  // It appears (plugged in): set up on the next retry, and the fault clears.
  rig.i2c->attach(0x41);
  EXPECT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 2; }));
  EXPECT_TRUE(wait_for([&] { return !rig.bus->status().fault; }));
}

TEST(Pca9685BusFaults, AReadBackMismatchIsALatchedFaultNamingTheBoard) {
  Rig rig({0x40, 0x41}, [](MemoryI2cBus& i2c) {
    i2c.with(0x41, [](Pca9685Sim& c) { c.set_ignore_prescale(true); });
  });
  ASSERT_TRUE(wait_for([&] { return rig.bus->status().fault; }));
  const std::string r = rig.reason();
  EXPECT_NE(r.find("board 0x41"), std::string::npos) << r;
  EXPECT_NE(r.find("PRE_SCALE 0x1e"), std::string::npos) << r;  // the power-on 200 Hz
  EXPECT_NE(r.find("expected 0x79"), std::string::npos) << r;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(rig.bus->boards_ready(), 1U);
  EXPECT_TRUE(rig.bus->status().fault);  // latched
  // The wrong board is never driven.
  rig.bus->set_enabled(true);
  rig.bus->write({}, kThreePositions);
  EXPECT_TRUE(wait_for([&] { return rig.off(0x40, 0) == 246; }));
  EXPECT_EQ(rig.off(0x41, 1), -1);
}

TEST(Pca9685BusFaults, AnExternalClockShowsInMode1) {
  Rig rig({0x40, 0x41}, [](MemoryI2cBus& i2c) {
    i2c.with(0x40, [](Pca9685Sim& c) {
      const std::uint8_t v = pca9685::kMode1Sleep | pca9685::kMode1ExtClk;  // sticky
      c.write(pca9685::kMode1, std::span(&v, 1));
    });
  });
  ASSERT_TRUE(wait_for([&] { return rig.bus->status().fault; }));
  EXPECT_NE(rig.reason().find("board 0x40"), std::string::npos) << rig.reason();
  EXPECT_NE(rig.reason().find("MODE1 0x60"), std::string::npos) << rig.reason();
}

TEST(Pca9685BusFaults, ABoardGoingSilentFaultsAndRecovers) {
  Rig rig;
  ASSERT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 2; }));
  rig.i2c->set_answering(0x40, false);
  ASSERT_TRUE(wait_for([&] { return rig.bus->status().fault; }));
  EXPECT_NE(rig.reason().find("board 0x40"), std::string::npos) << rig.reason();
  EXPECT_GT(rig.bus->status().errors, 0U);
  rig.i2c->set_answering(0x40, true);
  EXPECT_TRUE(wait_for([&] { return !rig.bus->status().fault; }));
}

TEST(Pca9685BusFaults, ABoardThatResetsIsALatchedFault) {
  Rig rig;
  ASSERT_TRUE(wait_for([&] { return rig.bus->boards_ready() == 2; }));
  rig.i2c->with(0x41, [](Pca9685Sim& c) { c.power_on(); });  // a brown-out
  ASSERT_TRUE(wait_for([&] { return rig.bus->status().fault; }));
  EXPECT_NE(rig.reason().find("board 0x41"), std::string::npos) << rig.reason();
  EXPECT_NE(rig.reason().find("lost its set-up"), std::string::npos) << rig.reason();
  EXPECT_EQ(rig.bus->boards_ready(), 1U);
}

TEST(Pca9685BusConfig, RefusesBadAddressesAndEncodings) {
  const auto make = [](std::vector<ActuatorModel> acts) {
    Pca9685Options o;
    o.boards = {0x40};
    std::vector<double> init(acts.size(), 0.0);
    return Pca9685Bus("servos", std::make_unique<MemoryI2cBus>(), acts, init, o);
  };
  try {
    make({testing::pwm_servo("jaw", 17, 600)});
    ADD_FAILURE() << "address 17 on one board";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("jaw"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1..16"), std::string::npos) << e.what();
  }
  EXPECT_THROW(make({testing::pwm_servo("a", 2, 600), testing::pwm_servo("b", 2, 600)}),
               std::invalid_argument);
  ActuatorModel s16 = testing::pwm_servo("jaw", 1, 600);
  s16.encoding.raw = ActuatorEncoding::Raw::kInt16;
  EXPECT_THROW(make({s16}), std::invalid_argument);
}

// Bus doctor only reads: a board that was never set up stays asleep.
TEST(Pca9685Doctor, ReportsEachBoardReadOnly) {
  MemoryI2cBus i2c;
  i2c.attach(0x40);  // power-on: asleep, PRE_SCALE 30 (25 MHz / 4096 / 31)
  i2c.attach(0x42);
  i2c.with(0x42, [](Pca9685Sim& c) {
    const std::uint8_t v = pca9685::kMode1ExtClk;
    c.write(pca9685::kMode1, std::span(&v, 1));
  });
  Pca9685Options o;
  o.boards = {0x40, 0x41, 0x42};
  const DoctorReport r = diagnose_pca9685("servos", i2c, testing::three_pwm_servos(), o, 3);
  const std::string text = r.to_text();
  EXPECT_TRUE(r.has_problems()) << text;
  EXPECT_NE(text.find("board 0x40: MODE1 0x11 (asleep), MODE2 0x04, PRE_SCALE 30 = 196.89 Hz"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("FAIL board 0x41: not answering (3 of 3 reads failed)"), std::string::npos)
      << text;
  EXPECT_NE(text.find("FAIL board 0x42: EXTCLK is set"), std::string::npos) << text;
  EXPECT_NE(text.find("board 0x42: no actuator on it (addresses 33..48)"), std::string::npos)
      << text;
  EXPECT_EQ(i2c.with(0x40, [](Pca9685Sim& c) { return c.reg(pca9685::kMode1); }),
            pca9685::kMode1PowerOn);  // untouched
}

}  // namespace
}  // namespace facectl
