#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "control/controller_model.hpp"
#include "control/limits/coupled_constraints.hpp"
#include "control/protection/drive_protection.hpp"
#include "firmware-host/config/bus_config.hpp"
#include "firmware-host/config/config_node.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/mandible_mechanism_config.hpp"
#include "firmware-host/config/rig_mapping_config.hpp"
#include "sim/plant/servo_plant.hpp"

namespace facectl {

// An `expect_direction` entry: the actuator's position rises (sign +1) or
// falls (sign -1) as the named face signal rises. `facectl verify` checks the
// mapping against it (docs/VERIFY.md, "Direction").
struct DirectionExpectation {
  std::size_t signal = 0;  // face layout index
  int sign = 1;
  std::string key;  // the signal as written (jaw_pitch_deg)
  std::string where;
};

struct ActuatorConfig {
  ActuatorModel model;
  MappingConfig map;  // empty (where = the actuator) for a strut of the mandible mechanism
  bool has_map = false;
  sim::ServoPlantParams plant;  // the simulated twin
  std::string where;
  std::string plant_where;           // position of its `plant` block, or of the actuator
  std::string encoding_where;        // position of its `encoding` block, or of the actuator
  bool has_encoding = false;         // an `encoding` block was written
  std::string fault_reaction_where;  // position of its `fault_reaction`, or of the actuator
  std::vector<DirectionExpectation> expect_direction;
  DriveProtection protection;    // its `protection` block; not configured if none
  std::string protection_where;  // position of that block
};

// A coupled limit as written: Σ coeff · signal (YAML units) <= max, over
// face signals (`face:`) or over actuator positions (`actuators:`).
struct CoupledLimitConfig {
  CoupledConstraints::Constraint constraint;  // SI coefficients
  bool over_actuators = false;                // indices are file-order actuator indices
  std::string where;
};

struct RigConfig {
  std::string file;
  std::string name;
  std::vector<BusConfig> buses;
  std::vector<ActuatorConfig> actuators;  // in file order
  std::optional<EnvelopeSpec> envelope;
  std::vector<CoupledLimitConfig> coupled_limits;
  std::optional<MandibleMechanismConfig> mechanism;
};

// Loads a rig against the head's face layout (mapping terms name its signals).
RigConfig load_rig_config(const std::string& path, const FaceLayout& layout);

}  // namespace facectl
