#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "control/actuator_model.hpp"
#include "control/mapping/mandible_mechanism.hpp"
#include "firmware-host/config/config_node.hpp"

namespace facectl {

// One strut as the rig writes it; the actuator is resolved by name when the
// model is built (its soft limits become the stroke limits).
struct StrutConfig {
  std::string actuator;
  Eigen::Vector3d skull = Eigen::Vector3d::Zero();     // m, head frame
  Eigen::Vector3d mandible = Eigen::Vector3d::Zero();  // m, head frame, at rest
  std::optional<double> stroke_at_rest;                // m; default: the actuator's rest
  std::string where;
};

// A rig's `mandible_mechanism:` block (docs/MANDIBLE_MECHANISM.md):
//   mandible_mechanism:
//     dofs: [pitch, yaw, protrusion]
//     held: { protrusion_mm: 0 }        # DOFs not driven (2 struts)
//     metric: { mm_per_deg: 1 }         # nearest-reachable metric
//     limits:                           # the mandible's rates, every driven DOF
//       pitch: { max_velocity_deg_s: 150, max_acceleration_deg_s2: 3000, max_jerk_deg_s3: 150000 }
//       protrusion: { max_velocity_mm_s: 40, max_acceleration_mm_s2: 800 }
//     struts:
//       - { actuator: jaw_digastric, skull_mm: [0, -105, -25], mandible_mm: [0, -78, 38] }
struct MandibleMechanismConfig {
  std::vector<MandibleDof> dofs;
  std::vector<StrutConfig> struts;
  face::MandiblePose held;
  MandibleMetric metric;
  // The mandible's own rate limits, per DOF (pitch, yaw, protrusion), SI; the
  // position fields are unused (the envelope bounds the pose).
  std::array<ActuatorLimits, 3> limits{};
  std::string limits_where;
  std::string where;
};

// Throws ConfigError naming file:line:col, the key, what was expected and found.
MandibleMechanismConfig parse_mandible_mechanism(const ConfigNode& node);

}  // namespace facectl
