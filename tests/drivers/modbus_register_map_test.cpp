// The Modbus register map's scaling and placement, byte for byte as
// docs/PROTOCOLS.md documents them.
#include "drivers/protocol/modbus_register_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace facectl::modbus_map {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(ModbusRegisterMap, RotaryTargetsAreHundredthsOfADegreeTwosComplement) {
  EXPECT_EQ(to_register(Unit::kRotary, 12.5 * kDeg), 0x04E2);  // 1250
  EXPECT_EQ(to_register(Unit::kRotary, -4.0 * kDeg), 0xFE70);  // -400
  EXPECT_EQ(to_register(Unit::kRotary, 0.0), 0x0000);
  EXPECT_NEAR(from_register(Unit::kRotary, 0xFE70), -4.0 * kDeg, 1e-12);
}

TEST(ModbusRegisterMap, LinearTargetsAreHundredthsOfAMillimetre) {
  EXPECT_EQ(to_register(Unit::kLinear, 0.0035), 0x015E);  // 3.5 mm = 350
  EXPECT_NEAR(from_register(Unit::kLinear, 0x015E), 0.0035, 1e-12);
}

TEST(ModbusRegisterMap, OutOfRangeSaturatesInsteadOfWrapping) {
  EXPECT_EQ(to_register(Unit::kRotary, 400.0 * kDeg), 0x7FFF);
  EXPECT_EQ(to_register(Unit::kRotary, -400.0 * kDeg), 0x8001);
  EXPECT_EQ(to_register(Unit::kRotary, std::numeric_limits<double>::quiet_NaN()), 0x8001);
}

TEST(ModbusRegisterMap, AddressesNumberChannelsAcrossBoards) {
  EXPECT_EQ(place(1).unit, 1);
  EXPECT_EQ(place(1).channel, 0);
  EXPECT_EQ(place(8).unit, 1);
  EXPECT_EQ(place(8).channel, 7);
  EXPECT_EQ(place(9).unit, 2);
  EXPECT_EQ(place(9).channel, 0);
  EXPECT_EQ(place(1976).unit, 247);
}

TEST(ModbusRegisterMap, BadAddressesAreRefusedByName) {
  try {
    place(0);
    FAIL() << "address 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("address 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(place(1977), std::invalid_argument);
}

}  // namespace
}  // namespace facectl::modbus_map
