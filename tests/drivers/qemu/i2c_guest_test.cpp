// Runs inside the QEMU guest: Pca9685Bus over the real i2c-dev character
// device of the kernel's SMBus stub adapter (i2c-stub chip_addr=0x40,0x41),
// two boards of 16 channels. The stub has no PCA9685 semantics, only 256
// registers per address, so what the driver wrote is read back exactly
// through a second i2c-dev file: the start-up registers, the on/off counts
// for given positions on both boards, full-off on disable, and a board
// address with no chip (0x42) as a fault naming it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "drivers/i2c/i2c_dev_transport.hpp"
#include "drivers/i2c/pca9685_bus.hpp"
#include "tests/drivers/pca9685_test_servos.hpp"
#include "tests/support/temp_dir.hpp"

namespace facectl {
namespace {

constexpr double kDeg = testing::kPwmDeg;

// /dev/i2c-N of the adapter named "SMBus stub driver", or "" when absent.
std::string stub_device() {
  for (const auto& e : std::filesystem::directory_iterator("/sys/class/i2c-adapter")) {
    std::ifstream in(e.path() / "name");
    std::string name;
    std::getline(in, name);
    if (name == "SMBus stub driver") return "/dev/" + e.path().filename().string();
  }
  return "";
}

bool wait_for(const std::function<bool()>& ok) {
  return testing::wait_until(ok, 10.0);
}

class Pca9685OnI2cStub : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = stub_device();
    ASSERT_FALSE(device_.empty()) << "no SMBus stub adapter: i2c-stub not loaded";
    ASSERT_TRUE(std::filesystem::exists(device_)) << device_ << ": i2c-dev not loaded";
    probe_ = std::make_unique<I2cDevTransport>(device_);
  }
  // The 12-bit OFF count of a channel, or -1 while full off.
  int off(int board, int channel) {
    const int r = pca9685::led_on_l(channel);
    const int lo = probe_->read_byte(board, static_cast<std::uint8_t>(r + 2));
    const int hi = probe_->read_byte(board, static_cast<std::uint8_t>(r + 3));
    if (lo < 0 || hi < 0) return -2;
    return (hi & pca9685::kLedFull) ? -1 : lo | ((hi & 0x0F) << 8);
  }

  std::string device_;
  std::unique_ptr<I2cDevTransport> probe_;
};

TEST_F(Pca9685OnI2cStub, WritesTheRegistersOfTwoBoards) {
  std::printf("FACECTL-QEMU: PCA9685 guest test on %s\n", device_.c_str());
  Pca9685Options o;
  o.boards = {0x40, 0x41};
  o.cycle_period_s = 0.005;
  // jaw: 0x40 channel 0; eye: 0x40 channel 3; brow: 0x41 channel 1.
  Pca9685Bus bus("servos", std::make_unique<I2cDevTransport>(device_), testing::three_pwm_servos(),
                 {90 * kDeg, 0.0, 0.0}, o);
  ASSERT_TRUE(wait_for([&] { return bus.boards_ready() == 2; })) << bus.status().reason;
  for (int b : {0x40, 0x41}) {
    EXPECT_EQ(probe_->read_byte(b, pca9685::kPreScale), 121) << b;  // 50 Hz
    EXPECT_EQ(probe_->read_byte(b, pca9685::kMode1), pca9685::kMode1AutoIncrement) << b;
    EXPECT_EQ(probe_->read_byte(b, pca9685::kMode2), pca9685::kMode2OutDrv) << b;
    EXPECT_EQ(probe_->read_byte(b, pca9685::kAllLedOffH), pca9685::kLedFull) << b;
  }
  bus.set_enabled(true);
  bus.write({}, testing::kThreePositions);
  // 1200 µs -> 245.9, 1800 µs -> 368.85, 2400 µs -> 491.8 counts at 50.03 Hz.
  EXPECT_TRUE(wait_for([&] { return off(0x41, 1) == 492; })) << off(0x41, 1);
  EXPECT_EQ(off(0x40, 0), 246);
  EXPECT_EQ(off(0x40, 3), 369);
  EXPECT_EQ(probe_->read_byte(0x40, pca9685::led_on_l(0)), 0);  // ON = 0
  EXPECT_FALSE(bus.status().fault) << bus.status().reason;

  std::array<std::uint8_t, 3> flags{1, 0, 1};
  bus.set_actuators_enabled(flags);
  EXPECT_TRUE(wait_for([&] { return off(0x40, 3) == -1; })) << off(0x40, 3);
  EXPECT_EQ(off(0x40, 0), 246);
  EXPECT_EQ(off(0x41, 1), 492);

  bus.set_enabled(false);
  EXPECT_TRUE(wait_for([&] { return off(0x40, 0) == -1 && off(0x41, 1) == -1; }));
  bus.set_enabled(true);  // bumpless: back to the last command, not to 0
  EXPECT_TRUE(wait_for([&] { return off(0x40, 0) == 246 && off(0x41, 1) == 492; }));
  EXPECT_EQ(off(0x40, 3), 369);
  std::printf("FACECTL-QEMU: PCA9685 guest test: %llu transfers, %llu errors\n",
              static_cast<unsigned long long>(bus.status().frames_sent),
              static_cast<unsigned long long>(bus.status().errors));
}

TEST_F(Pca9685OnI2cStub, ABoardWithNoChipIsAFaultNamingIt) {
  Pca9685Options o;
  o.boards = {0x40, 0x42};  // the stub answers 0x40 and 0x41 only
  o.cycle_period_s = 0.005;
  Pca9685Bus bus("servos", std::make_unique<I2cDevTransport>(device_),
                 {testing::pwm_servo("jaw", 1, 600), testing::pwm_servo("brow", 17, 1500)},
                 {90 * kDeg, 0.0}, o);
  ASSERT_TRUE(wait_for([&] { return bus.status().fault; }));
  const std::string reason = bus.status().reason;
  std::printf("FACECTL-QEMU: PCA9685 guest test: fault: %s\n", reason.c_str());
  EXPECT_NE(reason.find("board 0x42 on " + device_), std::string::npos) << reason;
  EXPECT_NE(reason.find("not answering"), std::string::npos) << reason;
  EXPECT_TRUE(wait_for([&] { return bus.boards_ready() == 1; }));
}

}  // namespace
}  // namespace facectl
