// Writing YAML that facectl's loaders read back as written: numbers in their shortest
// exact form, names quoted whenever they are more than a plain identifier.
#pragma once

#include <yaml-cpp/emitter.h>

#include <string>

namespace facectl::face {

// The shortest decimal text that reads back as exactly `v` (-0 as 0). Finite only:
// throws std::invalid_argument for NaN or infinity, which no loader accepts.
std::string exact_number(double v);

// `e << YamlNumber{v}`: exact_number(v), plain. yaml-cpp 0.7 writes doubles with 17
// digits (0.2 as 0.20000000000000001); this keeps 0.2 and still round-trips.
struct YamlNumber {
  double v;
};
YAML::Emitter& operator<<(YAML::Emitter& e, YamlNumber n);

// `e << YamlScaled{si, si_per_unit}`: `si` in the file's unit, as the shortest text t
// whose reading t · si_per_unit (what the loaders compute, e.g. mm · 1e-3) gives back
// exactly `si`, so 0.009 m is written as 9, not 9.000000000000002. Where no decimal
// does, exact_number(si / si_per_unit): exact in the file's unit.
struct YamlScaled {
  double si, si_per_unit;
};
YAML::Emitter& operator<<(YAML::Emitter& e, YamlScaled n);

// `e << YamlName{s}`: plain for an identifier ([A-Za-z0-9_.-], not starting with '-', not null),
// double-quoted otherwise, so that a colon, quote, hash or comma in a name (which a flow
// mapping would split on) reads back as the same string.
struct YamlName {
  const std::string& s;
};
YAML::Emitter& operator<<(YAML::Emitter& e, YamlName n);

// The emitter's text; std::logic_error with yaml-cpp's message if it was misused.
std::string emitted(const YAML::Emitter& e);

}  // namespace facectl::face
