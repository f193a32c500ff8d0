#include "firmware-host/config/feetech_bus_config.hpp"

#include <cmath>
#include <string>

namespace facectl {

void parse_feetech(const ConfigNode& node, BusConfig& bus) {
  node.expect_keys({"name", "type", "device", "baud", "series", "response_timeout_ms",
                    "fault_after_ms", "cycle_ms", "reconnect_ms", "return_delay_us",
                    "write_position_limits"});
  bus.endpoint = node["device"].string();
  bus.bitrate = node["baud"].integer();
  // The rates of the Baud Rate item (6), codes 0..7 (SMS_STS.h, SCSCL.h).
  bool known = false;
  for (const long b : {38400L, 57600L, 76800L, 115200L, 128000L, 250000L, 500000L, 1'000'000L}) {
    known = known || b == bus.bitrate;
  }
  if (!known) {
    node["baud"].fail(
        "a rate a Feetech servo runs at: 38400, 57600, 76800, 115200, 128000, 250000, 500000 or "
        "1000000");
  }
  FeetechOptions& o = bus.feetech;
  {
    const ConfigNode n = node["series"];
    const std::string series = n.string();
    if (series == "sts") {
      o.series = ft::Series::kSts;
    } else if (series == "scs") {
      o.series = ft::Series::kScs;
    } else {
      n.fail("sts (STS/SMS, e.g. STS3215) or scs (SCS, e.g. SCS0009)");
    }
  }
  if (auto n = node.get("response_timeout_ms"))
    o.response_timeout_s = n->number_in(1.0, 100.0) * 1e-3;
  if (auto n = node.get("fault_after_ms")) o.fault_after_s = n->number_in(5.0, 10'000.0) * 1e-3;
  if (auto n = node.get("cycle_ms")) o.cycle_period_s = n->number_in(1.0, 100.0) * 1e-3;
  if (auto n = node.get("reconnect_ms"))
    o.reconnect_interval_s = n->number_in(1.0, 10'000.0) * 1e-3;
  if (auto n = node.get("return_delay_us")) {
    o.return_delay_us = static_cast<int>(n->integer_in(0, 508));
    if (o.return_delay_us % 2 != 0) n->fail("an even number of microseconds (the unit is 2 us)");
  }
  if (auto n = node.get("write_position_limits")) o.write_position_limits = n->boolean();
  if (o.fault_after_s <= o.response_timeout_s) {
    const ConfigNode at = node.get("fault_after_ms") ? node["fault_after_ms"] : node;
    at.fail("fault_after_ms above response_timeout_ms (" +
                std::to_string(std::lround(o.response_timeout_s * 1e3)) + " ms)",
            std::to_string(std::lround(o.fault_after_s * 1e3)) + " ms");
  }
}

}  // namespace facectl
