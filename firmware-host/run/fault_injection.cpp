#include "firmware-host/run/fault_injection.hpp"

#include <cmath>
#include <stdexcept>

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

}  // namespace facectl
