#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "control/capacity.hpp"
#include "control/face/reduced_face_model.hpp"
#include "control/mapping/calibration_curve.hpp"
#include "control/mapping/linear_mapping.hpp"
#include "control/mapping/linkage.hpp"
#include "control/mapping/mandible_mechanism.hpp"
#include "control/mapping/point_projection.hpp"
#include "control/mapping/point_term.hpp"

namespace facectl {

inline constexpr std::size_t kMaxControlPoints = 32;

// What turns an actuator's effector value (what the face part must do) into
// the actuator position: nothing, a monotone calibration curve, or a linkage
// inverse. Values outside the curve or the linkage's working range are held
// at its end (and flagged), never extrapolated.
struct ChannelTransform {
  enum class Kind { kNone, kCalibration, kLinkage };
  Kind kind = Kind::kNone;
  CalibrationCurve curve;  // effector (x) -> actuator (y), SI
  Linkage linkage;
};

// Step 6 of the tick, as a const model: face signals (and the reduced model's
// control points) -> effector values -> actuator positions. Built once from
// the rig; map_to_actuators() allocates nothing.
struct RigMapping {
  LinearMapping linear;                      // effector = offset + gains · face signals
  std::vector<PointTerm> points;             // control-point sources, any order
  std::vector<ChannelTransform> transforms;  // one per actuator
  // The reduced face model, present iff some actuator reads a control point.
  std::shared_ptr<const face::ReducedFaceModel> reduced;
  // `points` folded into `reduced` (finish_points() builds it), what the tick evaluates.
  PointProjection projection;
  std::size_t muscle_count = 0;  // face signals [0, muscle_count) are the model's muscles
  std::size_t jaw_pitch = 0, jaw_yaw = 0, jaw_protrusion = 0;  // face signal indices
  std::size_t eyelid_closure[2] = {0, 0};                      // left, right
  // Struts that produce the mandible pose together, solved by inverse
  // kinematics after the per-channel transforms (their strut actuators have no
  // linear terms, points or transform).
  std::optional<MandibleMechanism> mechanism;

  std::size_t actuators() const { return linear.actuators(); }
  bool drives(std::size_t actuator) const;
};

// Preallocated scratch space of one mapping (one per controller).
struct MappingWorkspace {
  face::FeatureSubsetWorkspace point_features;         // those the projection weighs
  std::array<double, kMaxActuators> point_effector{};  // one per projection row
  std::array<double, kMaxActuators> effector{};
  MandibleSolveResult mechanism;          // the last inverse kinematics result
  MandibleRotations mechanism_rotations;  // of its target, reused while an angle holds
};

MappingWorkspace make_mapping_workspace(const RigMapping& mapping);

// Builds mapping.projection from mapping.points and mapping.reduced; call it
// once the points are final.
void finish_points(RigMapping& mapping);

// The reduced face model's input from the face signals (contractions, jaw, eyelids).
face::ReducedInput reduced_input(const RigMapping& mapping,
                                 const std::array<double, kMaxFaceSignals>& face);

// Evaluates the control-point sources (step 5) into w.point_effector.
void evaluate_control_points(const RigMapping& mapping, MappingWorkspace& w,
                             const std::array<double, kMaxFaceSignals>& face);

// Effector values from face signals and the evaluated control points.
void map_effectors(const RigMapping& mapping, MappingWorkspace& w,
                   const std::array<double, kMaxFaceSignals>& face);

// Applies each actuator's transform to w.effector. Returns a bit per actuator
// whose effector lay outside its curve or linkage range (held at the end);
// an actuator whose linkage cannot close keeps its previous position in `out`.
std::uint64_t apply_transforms(const RigMapping& mapping, const MappingWorkspace& w,
                               std::array<double, kMaxActuators>& out);

// The mandible mechanism's strut positions for the face's jaw pose (nearest
// reachable pose if the strokes would leave their limits). Returns a bit per
// strut actuator if it clamped; 0 without a mechanism.
std::uint64_t solve_mechanism(const RigMapping& mapping, MappingWorkspace& w,
                              const std::array<double, kMaxFaceSignals>& face,
                              std::array<double, kMaxActuators>& out);

// Steps 5 and 6 together. Returns the bits of apply_transforms() and solve_mechanism().
std::uint64_t map_to_actuators(const RigMapping& mapping, MappingWorkspace& w,
                               const std::array<double, kMaxFaceSignals>& face,
                               std::array<double, kMaxActuators>& out);

// One channel's transform on one value; `clamped` reports a held end.
// nullopt where a linkage cannot close.
std::optional<double> transform_effector(const ChannelTransform& t, double effector, bool* clamped);

}  // namespace facectl
