// How fast a mandible mechanism's struts can move when its pose moves within
// given rates: rigorous bounds that the model builder uses to check that the
// mandible's own limits (pitch, yaw, protrusion rates) never ask a strut for
// more than its velocity or acceleration limit. docs/MANDIBLE_MECHANISM.md,
// "Moving the struts together", derives them.
#pragma once

#include <array>

#include "control/actuator_model.hpp"
#include "control/envelope/mandible_envelope.hpp"
#include "control/mapping/mandible_mechanism.hpp"

namespace facectl {

// Per strut, over every pose of the envelope: |∂L/∂q_k| <= gain[k] and
// |∂²L/∂q_k∂q_l| <= curvature[k][l] (L the strut length; q = pitch rad,
// yaw rad, protrusion m).
struct StrutRateBound {
  std::array<double, 3> gain{};
  std::array<std::array<double, 3>, 3> curvature{};
  double min_length = 0.0;  // m, a lower bound of L over the envelope
};

StrutRateBound strut_rate_bound(const MandibleMechanism& m, std::size_t strut,
                                const MandibleEnvelope& envelope);

// Bounds on the largest stroke velocity and acceleration the strut can see
// while each DOF moves within its own limits:
//   velocity     <= max_q Σ |∂_k L(q)| v_k
//   acceleration <= max_q Σ |∂_k L(q)| a_k + Σ C_kl v_k v_l.
// The maxima are taken on a grid of `samples` points per driven axis and made
// rigorous by the curvature bound: between grid points |∂_k L| changes by at
// most Σ_l C_kl h_l (h_l the half spacing).
struct StrutDemand {
  double velocity = 0.0;
  double acceleration = 0.0;
};
StrutDemand strut_demand(const MandibleMechanism& m, std::size_t strut,
                         const MandibleEnvelope& envelope, const std::array<ActuatorLimits, 3>& dof,
                         int samples = 33);

}  // namespace facectl
