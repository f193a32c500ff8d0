#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/verify/findings.hpp"

namespace facectl::verify {

struct SearchOptions {
  std::uint64_t ticks = 1'000'000;
  std::uint64_t seed = 1;
};

// The smallest margin seen to each of an actuator's limits, in its YAML unit
// (or as a fraction of the limit for velocity, acceleration and jerk: 1 = at
// rest, 0 = at the limit, < 0 = beyond it).
struct ActuatorMargins {
  std::string name;
  double hardware = 1e300, soft = 1e300;  // position, YAML unit
  double velocity = 1.0, acceleration = 1.0, jerk = 1.0;
  double hardware_at_s = 0.0;
};

struct SearchResult {
  std::uint64_t ticks = 0;
  std::vector<ActuatorMargins> actuators;
  double face_constraint_margin = 1e300;      // min over face coupled limits of bound − value
  double actuator_constraint_margin = 1e300;  // the same over actuator coupled limits
  double envelope_margin = 1e300;             // of the jaw inside the envelope, SI
  // Of the pose the mandible mechanism's strut commands produce (forward
  // kinematics), SI; stays 1e300 without a mechanism.
  double mechanism_envelope_margin = 1e300;
  std::uint64_t violations = 0;
  std::vector<Finding> findings;  // violations (the first ones, with time) and notes
  double seconds = 0.0;
};

// Drives the same control objects the tick uses (the Controller on the rig's
// simulated twin) with random, extreme and bang-bang step inputs over each
// signal's whole domain, plus NaN bursts and late and early ticks, and
// measures every commanded trajectory against every limit. Deterministic for
// a seed.
SearchResult adversarial_search(const LoadedConfig& cfg, const SearchOptions& options);

}  // namespace facectl::verify
