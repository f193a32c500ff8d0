// A sound range proof of a mandible mechanism's strut strokes, for `facectl
// verify`: over every admissible pose (the mandible envelope, less what linear
// constraints over (pitch, yaw, protrusion) exclude), each strut's stroke lies in
// the proven enclosure. Branch and bound on pose boxes with a rigorous Lipschitz
// bound (docs/MANDIBLE_MECHANISM.md, "Range proof"). Offline; it allocates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>

#include "control/envelope/mandible_envelope.hpp"
#include "control/mapping/mandible_mechanism.hpp"

namespace facectl {

// a · (pitch rad, yaw rad, protrusion m) <= b. Used only to prune: a box whose
// smallest a·x exceeds b holds no admissible pose.
struct MandibleLinearConstraint {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  double b = 0.0;
};

struct StrokeEnclosure {
  Range proven;               // m: every admissible pose's stroke lies in here
  Range attained;             // m: strokes at the two witnesses below
  face::MandiblePose argmin;  // admissible poses attaining attained.min / .max
  face::MandiblePose argmax;
  bool converged = false;  // both gaps (proven − attained) <= tolerance
};

enum class MechanismReach {
  kProven,     // every admissible pose is within every strut's stroke limits
  kViolated,   // a witness pose needs a stroke beyond a limit
  kUndecided,  // a limit lies inside a gap the box budget could not close
};

struct MechanismRangeProof {
  std::array<StrokeEnclosure, MandibleMechanism::kMaxStruts> strut{};
  std::size_t count = 0;
  bool empty = false;  // the constraints exclude every pose: nothing to bound
  MechanismReach reach = MechanismReach::kUndecided;
  std::size_t witness_strut = 0;  // kViolated: the strut, the pose, and its stroke
  face::MandiblePose witness;
  double witness_stroke = 0.0;
  std::size_t boxes = 0;  // boxes bounded, all struts
};

struct RangeProofOptions {
  double tolerance = 1e-6;            // m: target gap between proven and attained
  std::size_t max_boxes = 4'000'000;  // per strut and side
};

// DOFs the mechanism does not drive take their held value, whatever the envelope
// says for them. Throws std::invalid_argument for an empty or non-finite envelope.
MechanismRangeProof prove_stroke_ranges(const MandibleMechanism& m,
                                        const MandibleEnvelope& envelope,
                                        std::span<const MandibleLinearConstraint> constraints = {},
                                        const RangeProofOptions& options = {});

}  // namespace facectl
