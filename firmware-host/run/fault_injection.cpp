#include "firmware-host/run/fault_injection.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/clock.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/run/realtime_loop.hpp"
#include "sim/devices/sim_hardware.hpp"

namespace facectl {
namespace {

double parse_number(const std::string& text, const std::string& whole) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v) || v < 0.0) {
    throw std::invalid_argument("--inject '" + whole + "': expected a number >= 0, found '" + text +
                                "'");
  }
  return v;
}

}  // namespace

Injection parse_injection(const std::string& text) {
  const auto at = text.rfind('@');
  if (at == std::string::npos) {
    throw std::invalid_argument("--inject '" + text +
                                "': expected KIND@SECONDS (estop, bus_fault:BUS, input_loss, "
                                "overrun_storm:MS)");
  }
  Injection inj;
  inj.at_s = parse_number(text.substr(at + 1), text);
  const std::string kind = text.substr(0, at);
  if (kind == "estop") {
    inj.kind = Injection::Kind::kEstop;
  } else if (kind == "input_loss") {
    inj.kind = Injection::Kind::kInputLoss;
  } else if (kind.starts_with("bus_fault:") && kind.size() > 10) {
    inj.kind = Injection::Kind::kBusFault;
    inj.bus = kind.substr(10);
  } else if (kind.starts_with("overrun_storm:")) {
    inj.kind = Injection::Kind::kOverrunStorm;
    inj.stall_ms = parse_number(kind.substr(14), text);
  } else {
    throw std::invalid_argument("--inject '" + text +
                                "': expected estop, bus_fault:BUS, input_loss or "
                                "overrun_storm:MS before '@', found '" +
                                kind + "'");
  }
  return inj;
}

void check_injection_buses(const std::vector<Injection>& injections, const RigConfig& rig) {
  for (const auto& inj : injections) {
    if (inj.kind == Injection::Kind::kBusFault &&
        std::none_of(rig.buses.begin(), rig.buses.end(),
                     [&](const BusConfig& b) { return b.name == inj.bus; })) {
      throw ConfigError("--inject bus_fault:" + inj.bus + ": expected a bus of rig '" + rig.name +
                        "', found no such bus");
    }
  }
}

void fire_due_injections(std::vector<Injection>& injections, double t, SimHardware* sim,
                         const std::function<void()>& silence_input, RealtimeLoop* loop) {
  for (auto& inj : injections) {
    if (inj.done || t < inj.at_s) continue;
    inj.done = true;
    switch (inj.kind) {
      case Injection::Kind::kEstop:
        if (sim != nullptr) sim->io.press_estop();
        break;
      case Injection::Kind::kBusFault:
        if (SimActuatorBus* bus = sim != nullptr ? sim->find(inj.bus) : nullptr) {
          bus->inject_fault("injected bus fault");
        }
        break;
      case Injection::Kind::kInputLoss:
        if (silence_input) silence_input();
        break;
      case Injection::Kind::kOverrunStorm:
        if (loop != nullptr) {
          loop->stall_until(monotonic_ns() + static_cast<std::int64_t>(inj.stall_ms * 1e6));
        }
        break;
    }
  }
}

}  // namespace facectl
