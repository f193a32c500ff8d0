#pragma once

#include <string>
#include <vector>

#include "control/controller_model.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/config/rig_config.hpp"
#include "firmware-host/config/runtime_config.hpp"

namespace facectl {

struct BuiltModel {
  ControllerModel model;
  std::vector<std::string> warnings;  // loud notices (e.g. a widened envelope)
  // What makes the rig unsafe or unusable although every file parsed (an
  // actuator nothing drives, a calibration that turns back, an envelope
  // widened without the override, a linkage of the wrong unit). `facectl run`
  // refuses to start on any; `facectl verify` reports them all. Each names
  // file:line:col and the actuator.
  std::vector<std::string> problems;
  std::vector<std::size_t> file_order;  // controller actuator index of each rig-file actuator
};

// Combines head, rig and runtime settings into the const model the tick runs
// on. Validates what no single file can (e.g. every actuator is driven).
BuiltModel build_model(const HeadConfig& head, const RigConfig& rig, const RuntimeConfig& runtime);

// Each face signal's range as the tick admits it (SI): the envelope for the
// jaw, the admissible range for the rest.
struct FaceBounds {
  std::array<double, kMaxFaceSignals> lo{};
  std::array<double, kMaxFaceSignals> hi{};
};
FaceBounds face_bounds(const ControllerModel& m);

}  // namespace facectl
