#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/actuator_model.hpp"
#include "control/capacity.hpp"
#include "control/command/command_shaper.hpp"
#include "control/command/face_layout.hpp"
#include "control/envelope/mandible_envelope.hpp"
#include "control/limits/coupled_constraints.hpp"
#include "control/mapping/rig_mapping.hpp"
#include "control/protection/drive_protection.hpp"
#include "control/safety/safety_state_machine.hpp"

namespace facectl {

// Everything the tick needs that never changes while it runs (MuJoCo's mjModel
// role): built and validated once from the configuration.
struct ControllerModel {
  FaceLayout layout{{}};
  std::array<double, kMaxFaceSignals> neutral{};
  std::array<Range, kMaxFaceSignals> admissible{};
  MandibleEnvelope envelope = MandibleEnvelope::design_default();
  bool envelope_widened = false;  // set only through the explicit override
  // Linear inequalities over the face signals (antagonists, jaw against lips,
  // yaw band by pitch), projected in step 4 after the envelope.
  CoupledConstraints face_constraints;
  ShapingParams shaping;
  SafetyParams safety;
  RigMapping mapping;
  // Linear inequalities over actuator positions (e.g. jaw against lip
  // actuators that collide at their extremes): mapped targets are projected,
  // and each tick the limits become position bounds that the actuators'
  // limiters never cross (coupled_position_bounds.hpp), so commands stay
  // admissible. No strut of the mandible mechanism may appear in them.
  CoupledConstraints actuator_constraints;
  // With a mandible mechanism (mapping.mechanism): the pose is limited in its
  // own DOFs (pitch, yaw, protrusion; position = the envelope) and the struts
  // follow it by inverse kinematics, so they move together. `mandible_rest` is
  // the pose the struts' rest positions make (where STOPPING goes).
  std::array<ActuatorLimits, 3> mandible_limits{};
  face::MandiblePose mandible_rest;
  std::vector<ActuatorModel> actuators;  // ordered by bus
  // Drive-level protection per actuator, same order (docs/SAFETY.md); empty
  // or not configured: none.
  std::vector<DriveProtection> protection;
  std::vector<BusModel> buses;
  double rate_hz = 1000.0;
  // STOPPING ends when, for every actuator, the command is within this
  // fraction of its soft range of rest (and nearly still), the measured
  // position within the second fraction (it carries noise), for rest_dwell_s.
  double rest_tolerance_fraction = 0.002;
  double rest_measured_tolerance_fraction = 0.01;
  double rest_dwell_s = 0.05;
};

}  // namespace facectl
