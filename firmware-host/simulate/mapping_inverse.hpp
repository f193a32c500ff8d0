// The inverse of a rig's mapping (control/mapping/rig_mapping.hpp): from actuator
// positions back to the face command that the rig's forward mapping turns into
// those positions, as closely as possible. Offline only (`facectl simulate
// --render` draws the face this gives); docs/SIMULATE.md, "Render frames".
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <span>

#include "control/capacity.hpp"
#include "control/controller_model.hpp"
#include "control/mapping/rig_mapping.hpp"

namespace facectl {

// The const model of the inverse, built once from the controller model.
//
// Problem: with E(x) the effector values of face signals x (linear terms and
// control points) and e the effector values that the positions need (each
// channel's calibration or linkage inverted), minimise
//   Σ_a (w_a · (E_a(x) − e_a))² + λ Σ_s ((x_s − neutral_s) / span_s)²
// over the admissible box, w_a = 1 / (the actuator's effector span). The small
// λ picks, among faces that reproduce the positions, the one nearest neutral.
// With a mandible mechanism the jaw pose is its forward kinematics of the
// strut positions instead. Signals no actuator observes stay neutral.
// Solved by projected Levenberg–Marquardt from neutral, and once more from the
// middle of the box when that leaves a misfit (a local minimum at a bound).
struct MappingInverse {
  static constexpr int kMaxIterations = 50;

  const RigMapping* mapping = nullptr;  // lives in the ControllerModel
  std::size_t signals = 0;
  std::array<double, kMaxFaceSignals> neutral{};
  std::array<double, kMaxFaceSignals> lower{}, upper{};  // admissible box (jaw: the envelope)
  std::array<double, kMaxFaceSignals> span{};            // upper − lower (1 where zero)
  std::array<bool, kMaxFaceSignals> observed{};          // some actuator's effector reads it
  std::array<double, kMaxActuators> weight{};            // 0: actuator not used (strut, undriven)
  face::MandiblePose mandible_rest;                      // forward kinematics' first guess
  double regularisation = 1e-8;
  bool second_start = true;  // false: the descent from neutral alone (tests compare with it)
};

MappingInverse make_mapping_inverse(const ControllerModel& model);

// Preallocated scratch space: a solve allocates nothing.
struct MappingInverseWorkspace {
  static constexpr int N = static_cast<int>(kMaxFaceSignals);
  static constexpr int A = static_cast<int>(kMaxActuators);
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, A, N>;
  using Normal = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, N, N>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, N, 1>;
  using Residual = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, A, 1>;

  MappingWorkspace mapping;
  std::array<double, kMaxFaceSignals> face{}, trial{}, best{};
  std::array<double, kMaxActuators> target{};   // effector values the positions need
  std::array<int, kMaxFaceSignals> variable{};  // signal index of each free variable
  Matrix jacobian;
  Normal normal, damped;  // JᵀJ + λI, and with the Levenberg–Marquardt damping added
  Vector gradient, step;
  Residual residual, residual_trial;
};

MappingInverseWorkspace make_mapping_inverse_workspace(const MappingInverse& inverse);

struct MappingInverseResult {
  double residual = 0.0;  // RMS of w_a · (E_a − e_a) over the used actuators
  int iterations = 0;
  bool mandible_solved = true;  // false: forward kinematics failed, jaw held at rest
};

// The second start's trigger: some used actuator's weighted misfit (a fraction of its
// effector span) above 1e-4. The worst actuator, not an average: one servo left far off
// among twenty well-fitted ones is a visible error, though the RMS is small.
bool needs_second_start(std::span<const double> weighted_residual);

// Writes the face (SI, layout order; entries past `signals` untouched) whose
// mapping best reproduces `positions` (actuator order, SI).
MappingInverseResult invert_mapping(const MappingInverse& inverse, MappingInverseWorkspace& w,
                                    std::span<const double> positions,
                                    std::array<double, kMaxFaceSignals>& face);

}  // namespace facectl
