#include "firmware-host/cli/placement_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <cstdlib>

#include "facectl/face/yaml_emit.hpp"

namespace facectl {
namespace {

using face::YamlName;
using face::YamlNumber;
using Y = YAML::Emitter;

// A proposal for a person to read and copy into a rig, not data to read back exactly:
// lengths to 0.01 mm (finer than any servo places a skin point), directions to 1e-4.
constexpr int kMmDecimals = 2, kAxisDecimals = 4, kErrorDecimals = 3;

// The double nearest v rounded to `decimals` places, which prints as that short decimal.
YamlNumber rounded(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return {std::strtod(text, nullptr)};
}

void vec(Y& y, const face::Vec3& v, int decimals) {
  y << YAML::Flow << YAML::BeginSeq << rounded(v.x(), decimals) << rounded(v.y(), decimals)
    << rounded(v.z(), decimals) << YAML::EndSeq;
}

void entry(Y& y, const char* key, double v, int decimals) {
  y << YAML::Key << key << YAML::Value << rounded(v, decimals);
}

}  // namespace

// Rig points name the head's control points (docs/CONFIG.md), so each entry names the
// nearest one as `point`, and the vertex itself beside it.
std::string placement_yaml(const face::Placement& p, const std::string& command) {
  Y y;
  y << YAML::Comment(command +
                     "\nEach actuator moves its skin point along `axis` (head frame) by "
                     "travel_mm. `point`\nis the control point nearest the vertex (rig maps can "
                     "name only those), at\ncontrol_point_distance_mm; `landmark` when the vertex "
                     "is one.")
    << YAML::Newline << YAML::BeginMap << YAML::Key << "actuators" << YAML::Value << YAML::BeginSeq;
  for (const face::PlacedActuator& x : p.actuators) {
    y << YAML::Flow << YAML::BeginMap;
    y << YAML::Key << "point" << YAML::Value << YamlName{x.nearest_control_point};
    y << YAML::Key << "vertex" << YAML::Value << x.vertex;
    if (!x.landmark.empty()) y << YAML::Key << "landmark" << YAML::Value << YamlName{x.landmark};
    entry(y, "control_point_distance_mm", x.control_point_distance_mm, kMmDecimals);
    y << YAML::Key << "position_mm" << YAML::Value;
    vec(y, x.position_mm, kMmDecimals);
    y << YAML::Key << "axis" << YAML::Value;
    vec(y, x.axis, kAxisDecimals);
    y << YAML::Key << "travel_mm" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << rounded(x.travel_min_mm, kMmDecimals) << rounded(x.travel_max_mm, kMmDecimals)
      << YAML::EndSeq;
    y << YAML::EndMap;
  }
  y << YAML::EndSeq << YAML::Newline
    << YAML::Comment("Skin error left (mm) over the moving vertices, and with no actuators.");
  y << YAML::Key << "errors" << YAML::Value << YAML::BeginMap;
  for (const face::ExpressionFit& f : p.fits) {
    y << YAML::Key << YamlName{f.name} << YAML::Value << YAML::Flow << YAML::BeginMap;
    entry(y, "rms_mm", f.rms_mm, kErrorDecimals);
    entry(y, "max_mm", f.max_mm, kErrorDecimals);
    entry(y, "rms_mm_no_actuators", f.rms0_mm, kErrorDecimals);
    entry(y, "max_mm_no_actuators", f.max0_mm, kErrorDecimals);
    if (!f.settled) y << YAML::Key << "unsettled" << YAML::Value << true;
    y << YAML::EndMap;
  }
  y << YAML::EndMap << YAML::EndMap;
  return face::emitted(y);
}

}  // namespace facectl
