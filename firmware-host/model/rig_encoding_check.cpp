#include "firmware-host/model/rig_encoding_check.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "control/units.hpp"
#include "drivers/protocol/cia402_counts.hpp"
#include "drivers/protocol/custom_can_frames.hpp"
#include "drivers/protocol/feetech_table.hpp"
#include "drivers/protocol/maestro_serial.hpp"
#include "drivers/protocol/pca9685_registers.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace facectl {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

[[noreturn]] void refuse(const ActuatorConfig& a, const std::string& expected,
                         const std::string& found) {
  throw ConfigError(a.encoding_where + ": actuator " + a.model.name + " encoding: expected " +
                    expected + ", found " + found);
}

// A smart servo in position control, `steps` steps over its travel; without an
// encoding, 0 deg is its centre. `family` names it in errors.
struct ServoFamily {
  const char* family;         // "DYNAMIXEL"
  ActuatorEncoding::Raw raw;  // its position's wire type
  const char* raw_why;        // "positions are 4 bytes"
  int steps;                  // over its travel
  double travel_deg;          // 360: a turn
  const char* range_why;      // "one turn, position control mode"
};

void check_servo_encoding(ActuatorConfig& actuator, const BusConfig& bus, double per_unit,
                          const ServoFamily& f) {
  ActuatorEncoding& e = actuator.model.encoding;
  const std::string on = std::string(f.family) + " bus " + bus.name;
  if (actuator.model.kind != ActuatorKind::kRotary) {
    throw ConfigError(actuator.where + ": actuator " + actuator.model.name +
                      ": expected kind rotary on " + on + ", found linear");
  }
  if (!actuator.has_encoding) e = {f.raw, f.steps / f.travel_deg, f.steps / 2.0};
  if (e.raw != f.raw) {
    refuse(actuator, std::string("raw ") + raw_name(f.raw) + " on " + on + " (" + f.raw_why + ")",
           std::string("raw ") + raw_name(e.raw));
  }
  const int top = f.steps - 1;
  for (const double si : {actuator.model.limits.position_min, actuator.model.limits.position_max}) {
    const double pulses = std::nearbyint(si / per_unit * e.scale + e.offset);
    if (pulses < 0 || pulses > top) {
      refuse(
          actuator,
          "the hardware range within 0.." + std::to_string(top) + " pulses (" + f.range_why +
              ") on " + on,
          "position " + number(si / per_unit) + " deg encoding to " + number(pulses) + " pulses");
    }
  }
}

constexpr ServoFamily kDynamixel{
    "DYNAMIXEL", ActuatorEncoding::Raw::kInt32,    "positions are 4 bytes", 4096,
    360.0,       "one turn, position control mode"};
// Feetech positions are 2 bytes: 0..4095 over a turn on STS, 0..1023 over
// the 300 deg travel of an SCS servo (SCS0009/SCS15 data sheets).
constexpr ServoFamily kFeetechSts{
    "Feetech STS", ActuatorEncoding::Raw::kUint16, "positions are 2 bytes", 4096,
    360.0,         "one turn of an STS servo"};
constexpr ServoFamily kFeetechScs{
    "Feetech SCS", ActuatorEncoding::Raw::kUint16, "positions are 2 bytes", 1024,
    300.0,         "the travel of an SCS servo"};

}  // namespace

void check_actuator_encoding(ActuatorConfig& actuator, const BusConfig& bus) {
  ActuatorEncoding& e = actuator.model.encoding;
  const char* raw = raw_name(e.raw);
  if (bus.is_cia402() && actuator.has_encoding && e.raw != ActuatorEncoding::Raw::kInt32) {
    refuse(actuator, "raw int32 on CiA 402 bus " + bus.name + " (drives count in 32 bits)",
           std::string("raw ") + raw);
  }
  if (bus.is_modbus() && e.raw == ActuatorEncoding::Raw::kInt32) {
    refuse(actuator,
           "raw int16 or uint16 on Modbus bus " + bus.name + " (one register per channel)",
           "raw int32");
  }
  if (bus.is_pca9685()) {
    // The raw value is the pulse in µs; it must fit inside one PWM period.
    if (!actuator.has_encoding || e.raw != ActuatorEncoding::Raw::kUint16) {
      refuse(actuator, "raw uint16 on PCA9685 bus " + bus.name + " (the pulse width in µs)",
             actuator.has_encoding ? std::string("raw ") + raw : "no encoding");
    }
    const double period_us = 1e6 / pca9685::frequency_of(pca9685::prescale_for(bus.pca9685.pwm_hz));
    for (const double si :
         {actuator.model.limits.position_min, actuator.model.limits.position_max}) {
      const double us = std::nearbyint(si / si_per_yaml(actuator.model.kind) * e.scale + e.offset);
      if (us <= 0.0 || us >= period_us) {
        refuse(actuator,
               "pulses inside the " + number(period_us) + " µs PWM period of bus " + bus.name,
               "position " + number(si / si_per_yaml(actuator.model.kind)) + " " +
                   yaml_unit(actuator.model.kind) + " giving " + number(us) + " µs");
      }
    }
  }
  if (bus.is_maestro()) {
    // The raw value is the pulse in µs, sent as a 14-bit target in quarter-µs
    // (Maestro guide 5.e); 0 means "no pulses", so a limit must be above it.
    if (!actuator.has_encoding || e.raw != ActuatorEncoding::Raw::kUint16) {
      refuse(actuator, "raw uint16 on Maestro bus " + bus.name + " (the pulse width in µs)",
             actuator.has_encoding ? std::string("raw ") + raw : "no encoding");
    }
    for (const double si :
         {actuator.model.limits.position_min, actuator.model.limits.position_max}) {
      const double us = std::nearbyint(si / si_per_yaml(actuator.model.kind) * e.scale + e.offset);
      if (us < 1.0 || 4.0 * us > maestro::kMaxTarget) {
        refuse(actuator,
               "pulses within 1..4095 µs (a 14-bit target in quarter-µs) on bus " + bus.name,
               "position " + number(si / si_per_yaml(actuator.model.kind)) + " " +
                   yaml_unit(actuator.model.kind) + " giving " + number(us) + " µs");
      }
    }
  }
  if (bus.is_can() && !bus.is_cia402()) {
    if (bus.can.width == custom_can::Width::kInt16 && e.raw == ActuatorEncoding::Raw::kInt32) {
      refuse(actuator, "raw int16 or uint16 on bus " + bus.name + " (values: int16, 2-byte fields)",
             "raw int32");
    }
    if (!actuator.has_encoding) e = custom_can::default_encoding(bus.can.width);
  }
  const double per_unit = si_per_yaml(actuator.model.kind);
  const char* unit = yaml_unit(actuator.model.kind);
  if (bus.is_dynamixel() || bus.is_feetech()) {
    check_servo_encoding(actuator, bus, per_unit,
                         bus.is_dynamixel()                       ? kDynamixel
                         : bus.feetech.series == ft::Series::kSts ? kFeetechSts
                                                                  : kFeetechScs);
    return;
  }
  // A CiA 402 drive counts with the actuator's int32 encoding or, without
  // one, the bus's counts_per_rev / counts_per_mm.
  const bool drive = bus.is_cia402();
  const cia402::DriveCounts drive_counts =
      drive ? cia402::drive_counts(actuator.model, bus.can) : cia402::DriveCounts{};
  const ActuatorEncoding::Raw type = drive ? ActuatorEncoding::Raw::kInt32 : e.raw;
  const double lo = raw_min(type);
  const double hi = raw_max(type);
  for (const double si : {actuator.model.limits.position_min, actuator.model.limits.position_max}) {
    const double counts = drive ? std::nearbyint(si * drive_counts.per_si + drive_counts.offset)
                                : std::nearbyint(si / per_unit * e.scale + e.offset);
    // Strictly inside: a reading at the raw type's limit may be a saturated
    // one, which would hide an actuator beyond its hardware range.
    if (counts <= lo || counts >= hi) {
      refuse(actuator,
             std::string("the hardware range to fit strictly inside raw ") + raw_name(type) + " (" +
                 number(lo) + ", " + number(hi) + ")",
             "position " + number(si / per_unit) + " " + unit + " encoding to " + number(counts) +
                 " counts");
    }
  }
}

}  // namespace facectl
