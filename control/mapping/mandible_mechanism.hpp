// A mandible mechanism: 2 or 3 linear actuators (struts) between the skull and
// the mandible that together produce the mandible pose of thesis §5.2 (see
// facectl/face/mandible.hpp: v' = T(d·u)·Y(yaw)·P(pitch)·v). docs/MANDIBLE_MECHANISM.md
// has the model, the metric and the composition order.
//
// Each strut is a straight line between a skull anchor (fixed in the head frame)
// and a mandible anchor (moves with the mandible). Its actuator position is
//   stroke(pose) = stroke_at_rest + L(pose) − L(rest),   L = |skull − T(pose)·mandible|,
// so a strut that gets longer extends its actuator. The mechanism drives a declared
// set of degrees of freedom (as many as it has struts); the others are held at a
// fixed value (normally 0) because the mechanism cannot move them.
//
// In the tick: strokes() (closed form) and solve() (bounded, allocation-free,
// deterministic). Offline: forward(), conditioning().
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "control/envelope/mandible_envelope.hpp"
#include "control/face/mandible.hpp"
#include "control/units.hpp"

namespace facectl {

enum class MandibleDof : std::uint8_t { kPitch = 0, kYaw = 1, kProtrusion = 2 };
std::string_view to_string(MandibleDof dof);

struct MandibleStrut {
  std::size_t actuator = 0;                            // index of the actuator that drives it
  Eigen::Vector3d skull = Eigen::Vector3d::Zero();     // m, head frame
  Eigen::Vector3d mandible = Eigen::Vector3d::Zero();  // m, head frame, at the rest pose
  double stroke_at_rest = 0.0;                         // m, actuator position at the rest pose
  Range stroke;                                        // m, the actuator's (soft) limits
};

// The nearest-reachable metric: distance² = Σ (scale_k · Δq_k)² over (pitch, yaw,
// protrusion). The default, 1° ≡ 1 mm, counts degrees and millimetres alike.
struct MandibleMetric {
  double angle_per_rad = kDegPerRad;  // 1 rad counts as 57.3 units
  double length_per_m = 1000.0;       // 1 m counts as 1000 units
};

// Pose as a vector (pitch rad, yaw rad, protrusion m).
using MandibleVector = Eigen::Vector3d;
MandibleVector to_vector(const face::MandiblePose& pose);
face::MandiblePose to_pose(const MandibleVector& q);

// One value per strut, in strut order (entries past struts() are unused).
using MandibleStrokes = std::array<double, 3>;

// The const model. Build it with make_mandible_mechanism().
struct MandibleMechanism {
  static constexpr std::size_t kMaxStruts = 3;

  face::MandibleAxes axes;
  std::array<MandibleStrut, kMaxStruts> strut{};
  std::array<MandibleDof, kMaxStruts> dof{};  // dof[i] = i-th driven DOF
  std::size_t count = 0;                      // struts = driven DOFs (2 or 3)
  face::MandiblePose held;                    // value of every DOF not driven
  MandibleMetric metric;

  // Derived by make_mandible_mechanism().
  std::array<bool, 3> driven{};                      // by DOF index (pitch, yaw, protrusion)
  std::array<double, kMaxStruts> rest_length{};      // L(rest), m
  std::array<Eigen::Vector3d, kMaxStruts> arm{};     // mandible anchor − pitch point, m
  Eigen::Vector3d weight = Eigen::Vector3d::Ones();  // metric scale per DOF

  std::size_t struts() const { return count; }
  // `q` with every DOF that is not driven replaced by its held value.
  MandibleVector held_in(const MandibleVector& q) const;
};

// Checks the structure (2 or 3 struts, one distinct DOF each, struts of non-zero
// length, min <= stroke_at_rest <= max, finite numbers, unit axes) and that the
// Jacobian is well conditioned over `envelope` (conditioning() below, at most
// `max_condition`). Throws std::invalid_argument naming the strut, DOF or pose.
MandibleMechanism make_mandible_mechanism(const face::MandibleAxes& axes,
                                          std::span<const MandibleDof> dofs,
                                          std::span<const MandibleStrut> struts,
                                          const MandibleEnvelope& envelope,
                                          const face::MandiblePose& held = {},
                                          const MandibleMetric& metric = {},
                                          double max_condition = 50.0);

// The pitch and yaw rotations of the last pose evaluated, with their angles. A
// call site in the tick keeps its own (one mechanism each): an angle that has not
// changed since, bit for bit (yaw while the jaw only opens, any DOF in a hold),
// reuses its rotation instead of evaluating a sine and cosine again. The same
// results with or without.
struct MandibleRotations {
  double pitch_rad = std::numeric_limits<double>::quiet_NaN();  // NaN: not built yet
  double yaw_rad = std::numeric_limits<double>::quiet_NaN();
  Eigen::Matrix3d pitch, yaw;
};

// Strut strokes at `pose` (closed form; DOFs not driven take their held value).
void strokes(const MandibleMechanism& m, const face::MandiblePose& pose, MandibleStrokes& out,
             MandibleRotations* rotations = nullptr);

// The mandible anchor of strut i at `q` (held DOFs already applied), head frame.
Eigen::Vector3d mandible_anchor(const MandibleMechanism& m, std::size_t i, const MandibleVector& q);

// Strokes and their Jacobian d stroke_i / d q_k (columns: pitch, yaw, protrusion;
// only the driven columns matter) at `q` (held DOFs already applied).
void strokes_and_jacobian(const MandibleMechanism& m, const MandibleVector& q, MandibleStrokes& out,
                          Eigen::Matrix3d& jacobian);

struct MandibleSolveResult {
  face::MandiblePose achieved;  // the pose `out_strokes` produces
  bool clamped = false;         // stroke limits moved it away from the target
  double distance = 0.0;        // metric distance target → achieved (driven DOFs)
  int iterations = 0;           // Gauss–Newton steps used (0: target reachable)
};

// Inverse kinematics in the tick. If the target's strokes are within limits the
// result is exact. Otherwise the pose moves to the nearest reachable one in the
// model's metric: projected Gauss–Newton in stroke space (at most 10 steps, each
// an exact box-QP over the 3^n active sets, with at most 3 halvings and 6 Newton
// steps for the pose). `out_strokes` is always within the stroke limits and
// `achieved` is the pose they produce (to 1e-11 m of stroke). A non-finite
// target gives the rest pose (held DOFs held). Bounded time, deterministic, no
// allocation.
MandibleSolveResult solve(const MandibleMechanism& m, const face::MandiblePose& target,
                          MandibleStrokes& out_strokes, MandibleRotations* rotations = nullptr);

// The strokes forward() converges to by default, in m.
inline constexpr double kForwardTolerance = 1e-11;

// Forward kinematics: Newton from `guess`, at most `max_iterations` steps.
// nullopt if it does not converge to `tolerance` (m of stroke) or the
// Jacobian is singular on the way.
std::optional<face::MandiblePose> forward(const MandibleMechanism& m,
                                          const MandibleStrokes& strokes,
                                          const face::MandiblePose& guess = {},
                                          int max_iterations = 30,
                                          double tolerance = kForwardTolerance);

// A pose (held DOFs applied once `evaluated`) and, once `evaluated`, its strokes and Jacobian
// (strokes_and_jacobian()). A tick's forward() warm-started from the last tick's
// answer keeps one: Newton ends linearised at its answer, so the next solve
// starts without evaluating the kinematics again.
struct MandibleLinearisation {
  MandibleLinearisation() = default;
  explicit MandibleLinearisation(const MandibleVector& q) : pose(q) {}

  MandibleVector pose = MandibleVector::Zero();
  bool evaluated = false;
  MandibleStrokes strokes{};
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
};

// forward() from `warm`, which becomes the answer, linearised there, on success
// and is left as it was on failure. The same answer as forward() from warm.pose.
std::optional<face::MandiblePose> forward(const MandibleMechanism& m,
                                          const MandibleStrokes& strokes,
                                          MandibleLinearisation& warm, int max_iterations,
                                          double tolerance);

// Conditioning of the weighted Jacobian (stroke mm per metric unit) over a grid of
// `samples` points per driven axis of `envelope` (held DOFs at their value). This
// samples, it does not prove.
struct MandibleConditioning {
  double worst_condition = 0.0;      // largest σmax/σmin seen
  face::MandiblePose worst_pose;     // where
  double smallest_singular = 0.0;    // smallest σmin seen (mm per unit)
  face::MandiblePose smallest_pose;  // where
};
MandibleConditioning conditioning(const MandibleMechanism& m, const MandibleEnvelope& envelope,
                                  int samples = 9);

}  // namespace facectl
