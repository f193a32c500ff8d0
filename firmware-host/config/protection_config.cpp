#include "firmware-host/config/protection_config.hpp"

#include <string>

namespace facectl {
namespace {

// What each bus type fills in ActuatorBus::read_health. DYNAMIXEL X-series:
// Present Temperature, Present Load or Current, Present Input Voltage and
// Hardware Error Status (drivers/dynamixel/dynamixel_bus.cpp). Pololu
// Maestro: its error register only (drivers/maestro/maestro_bus.cpp). Feetech
// SCS/STS: Present Temperature, Load and Voltage, and the status packet's
// error flags (drivers/feetech/feetech_bus.cpp).
struct Reported {
  bool temperature = false, load = false, current = false, voltage = false, error = false;
};

Reported reported_by(const std::string& type) {
  if (type == "dynamixel") return {true, true, true, true, true};
  if (type == "maestro") return {false, false, false, false, true};
  if (type == "feetech") return {true, true, false, true, true};
  return {};
}

void refuse_unreported(const ConfigNode& n, const BusConfig& bus, const char* what) {
  n.fail("no " + std::string(what) + " limit: bus '" + bus.name + "' (type " + bus.type +
             ") does not report " + what,
         "a " + std::string(what) + " limit");
}

ProtectionLimit parse_limit(const ConfigNode& n, double lo, double hi) {
  n.expect_keys({"derate", "fault"});
  ProtectionLimit l;
  l.fault = n["fault"].number_in(lo, hi);
  l.derate = l.fault;  // no derating: straight to FAULT
  if (auto d = n.get("derate")) {
    l.derate = d->number_in(lo, hi);
    if (!(l.derate < l.fault)) {
      d->fail("derate below fault (" + std::to_string(l.fault) + ")", std::to_string(l.derate));
    }
  }
  return l;
}

}  // namespace

DriveProtection parse_protection(const ConfigNode& node, const ActuatorModel& a,
                                 const BusConfig& bus) {
  const std::string unit = yaml_unit(a.kind);
  node.expect_keys({"temperature_c", "load", "current_a", "voltage_v", "hardware_error_mask",
                    "derate_floor", "hold_ms", "recover_s", "extreme"});
  const Reported r = reported_by(bus.type);
  DriveProtection p;
  p.configured = true;
  if (auto n = node.get("temperature_c")) {
    if (!r.temperature) refuse_unreported(*n, bus, "temperature");
    p.temperature_c = parse_limit(*n, -40.0, 200.0);
  }
  if (auto n = node.get("load")) {
    if (!r.load) refuse_unreported(*n, bus, "load");
    p.load = parse_limit(*n, 0.0, 1.0);  // a fraction of the servo's max torque
  }
  if (auto n = node.get("current_a")) {
    if (!r.current) refuse_unreported(*n, bus, "current");
    p.current_a = parse_limit(*n, 0.0, 1000.0);
  }
  if (auto n = node.get("voltage_v")) {
    if (!r.voltage) refuse_unreported(*n, bus, "voltage");
    n->expect_keys({"min", "max"});
    if (auto v = n->get("min")) p.voltage_min_v = v->number_in(0.0, 1000.0);
    if (auto v = n->get("max")) p.voltage_max_v = v->number_in(0.0, 1000.0);
    if (!(p.voltage_min_v < p.voltage_max_v)) n->fail("min < max");
  }
  if (auto n = node.get("hardware_error_mask")) {
    if (!r.error) refuse_unreported(*n, bus, "hardware errors");
    p.hardware_error_mask = static_cast<std::uint32_t>(n->integer_in(0, 0xFFFFFFFFL));
  } else if (!r.error) {
    p.hardware_error_mask = 0;
  }
  if (auto n = node.get("derate_floor")) p.derate_floor = n->number_in(0.0, 1.0);
  if (auto n = node.get("hold_ms")) p.hold_s = n->number_in(1.0, 10000.0) * 1e-3;
  if (auto n = node.get("recover_s")) p.recover_s = n->number_in(0.01, 3600.0);
  if (auto n = node.get("extreme")) {
    n->expect_keys({"band_" + unit, "budget_s", "cooldown_s"});
    const ActuatorLimits& l = a.limits;
    const ConfigNode band = (*n)["band_" + unit];
    p.extreme_band = band.positive() * si_per_yaml(a.kind);
    p.extreme_budget_s = (*n)["budget_s"].positive();
    p.extreme_cooldown_s = (*n)["cooldown_s"].positive();
    // A cool-down keeps the command in [min + band, max − band]: rest must
    // be in there, so that derating toward it never enters the band.
    if (!(a.rest > l.position_min + p.extreme_band && a.rest < l.position_max - p.extreme_band)) {
      band.fail("a band that leaves the rest position (" +
                std::to_string(a.rest * yaml_per_si(a.kind)) + " " + unit + ") outside it");
    }
  }
  // The tick copies these and appends the reading: it formats nothing else.
  const auto text = [&](ProtectionCause c, const std::string& rule) {
    p.fault_text[static_cast<std::size_t>(c)] =
        "drive protection: " + a.name + " " + to_string(c) + " " + rule + ", read ";
  };
  const auto num = [](double v) {
    std::string t = std::to_string(v);
    t.erase(t.find_last_not_of('0') + 1);
    if (!t.empty() && t.back() == '.') t.pop_back();
    return t;
  };
  const std::string held = " for " + num(p.hold_s * 1e3) + " ms";
  text(ProtectionCause::kTemperature, ">= " + num(p.temperature_c.fault) + " C" + held);
  text(ProtectionCause::kLoad, "|load| >= " + num(p.load.fault) + held);
  text(ProtectionCause::kCurrent, "|current| >= " + num(p.current_a.fault) + " A" + held);
  text(ProtectionCause::kVoltage,
       "outside [" + num(p.voltage_min_v) + ", " + num(p.voltage_max_v) + "] V" + held);
  text(ProtectionCause::kHardwareError, "bit set, mask " + std::to_string(p.hardware_error_mask));
  text(ProtectionCause::kExtreme, "still in its extreme band after the cool-down began, at");
  return p;
}

}  // namespace facectl
