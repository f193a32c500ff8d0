#include "firmware-host/run/protection_columns.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>

#include "control/protection/drive_protection.hpp"

namespace facectl {

void write_protection_header(std::FILE* out, const ControllerModel& model) {
  for (std::size_t i = 0; i < model.actuators.size() && i < model.protection.size(); ++i) {
    if (!model.protection[i].configured) continue;
    const char* n = model.actuators[i].name.c_str();
    std::fprintf(out,
                 ",temp_c.%s,load.%s,current_a.%s,voltage_v.%s,hw_error.%s,derate.%s,"
                 "extreme_s.%s,protection.%s",
                 n, n, n, n, n, n, n, n);
  }
}

char* write_protection_columns(char* p, const TelemetryRecord& r) {
  // A reading with 5 significant digits, or empty when the bus did not report it.
  const auto value = [&](float v) {
    *p++ = ',';
    if (std::isfinite(v)) p = std::to_chars(p, p + 20, v, std::chars_format::general, 5).ptr;
  };
  for (std::uint64_t bits = r.protected_mask; bits != 0; bits &= bits - 1) {
    const auto i = static_cast<std::size_t>(std::countr_zero(bits));
    if (i >= r.actuator_count) break;
    value(r.temperature_c[i]);
    value(r.load[i]);
    value(r.current_a[i]);
    value(r.voltage_v[i]);
    *p++ = ',';
    p = std::to_chars(p, p + 10, r.hardware_error[i]).ptr;
    value(r.derate[i]);
    value(r.extreme_s[i]);
    *p++ = ',';
    const char* mode = to_string(static_cast<ProtectionMode>(r.protection[i]));
    const std::size_t len = std::strlen(mode);
    std::memcpy(p, mode, len);
    p += len;
  }
  return p;
}

}  // namespace facectl
