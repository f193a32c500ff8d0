#include "facectl/face/yaml_emit.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace facectl::face {

std::string exact_number(double v) {
  if (!std::isfinite(v)) throw std::invalid_argument("cannot write a non-finite number as YAML");
  if (v == 0) return "0";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, r.ptr);
}

YAML::Emitter& operator<<(YAML::Emitter& e, YamlNumber n) {
  return e << exact_number(n.v);
}

YAML::Emitter& operator<<(YAML::Emitter& e, YamlScaled n) {
  const double v = n.si / n.si_per_unit;
  if (std::isfinite(v) && n.si != 0) {
    char buf[40];
    for (int digits = 1; digits <= 17; ++digits) {
      const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
      double back = 0;
      std::from_chars(buf, r.ptr, back);
      if (back * n.si_per_unit == n.si) return e << exact_number(back);  // 30, not 3e+01
    }
  }
  return e << exact_number(v);
}

YAML::Emitter& operator<<(YAML::Emitter& e, YamlName n) {
  // yaml-cpp reads a plain null as no string at all.
  bool plain =
      !n.s.empty() && n.s.front() != '-' && n.s != "null" && n.s != "Null" && n.s != "NULL";
  for (const char c : n.s)
    plain = plain && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      c == '_' || c == '.' || c == '-');
  if (plain) return e << n.s;
  return e << YAML::DoubleQuoted << n.s;
}

std::string emitted(const YAML::Emitter& e) {
  if (!e.good()) throw std::logic_error("YAML emitter: " + e.GetLastError());
  return std::string(e.c_str()) + "\n";
}

}  // namespace facectl::face
