#pragma once

#include <string>
#include <vector>

#include "control/analysis/lp_range.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/verify/findings.hpp"

namespace facectl::verify {

// What the proof established for one actuator, in its YAML unit.
struct ActuatorRange {
  std::string name;
  std::string unit;           // deg or mm
  double lo = 0.0, hi = 0.0;  // every admissible face input maps inside [lo, hi]
  double hardware_min = 0.0, hardware_max = 0.0, soft_min = 0.0, soft_max = 0.0;
  double hardware_margin = 0.0;  // min distance to the hardware range; < 0 = outside
  double soft_margin = 0.0;
  std::string method;  // how [lo, hi] was obtained
  bool proven = true;  // false where a step is numerical, not a proof
  // Admissible faces (SI, layout order) whose commands attain lo and hi, where known.
  std::vector<double> at_lo, at_hi;
};

struct StaticProof {
  std::vector<ActuatorRange> actuators;
  std::vector<Finding> findings;
  double seconds = 0.0;
};

// The admissible face set: each signal's admissible range (the mandible
// envelope for the jaw), intersected with the rig's coupled face limits.
Polytope admissible_face_set(const ControllerModel& m);

// "zygomaticus_major_l=1, jaw_pitch_deg=18": the signals of `x` away from neutral.
std::string describe_face(const ControllerModel& m, const std::vector<double>& x);

// Proves, over the whole admissible face set, where each actuator's mapped
// command can go, and checks the rig's other static obligations.
StaticProof prove(const LoadedConfig& cfg);

}  // namespace facectl::verify
