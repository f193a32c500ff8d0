#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/command/face_layout.hpp"
#include "control/mapping/rig_mapping.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// One mapping term: gain from a face signal to the effector, SI per SI.
struct MappingTerm {
  std::size_t signal = 0;
  double gain_si = 0.0;
};

// A control-point source as written: the point is resolved against the
// head's reduced model when the model is built.
struct PointTermConfig {
  std::string point;
  std::array<double, 3> axis{};  // unit
  double gain_si = 0.0;          // effector SI per metre
  std::string where;
};

// An actuator's `map:` block. The effector is what the face part must do;
// without a transform it is the actuator position itself.
struct MappingConfig {
  std::string effector_unit;  // deg, mm, or "" (dimensionless)
  double offset_si = 0.0;
  std::vector<MappingTerm> terms;
  std::vector<PointTermConfig> points;
  ChannelTransform transform;
  std::string calibration_problem;  // set (with where) if the curve turns back
  std::string where;                // the `map` block
  std::string transform_where;      // its calibration or linkage block
};

// The layout index of the face signal `key` (its YAML key: a muscle name,
// jaw_pitch_deg, ...); fails at `at` if the head has no such signal.
std::size_t face_signal(const FaceLayout& layout, const std::string& key, const ConfigNode& at);

// Parses `map:` for an actuator whose position unit is `actuator_unit`
// ("deg" or "mm"). Throws ConfigError naming file:line:col and the key.
MappingConfig parse_mapping(const ConfigNode& map, const FaceLayout& layout,
                            const std::string& actuator_unit);

// deg -> rad, mm -> m, "" -> 1.
double unit_to_si(const std::string& unit);

}  // namespace facectl
