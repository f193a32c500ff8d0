#include "control/analysis/mechanism_rate_bounds.hpp"

#include <algorithm>
#include <cmath>

namespace facectl {

StrutRateBound strut_rate_bound(const MandibleMechanism& m, std::size_t strut,
                                const MandibleEnvelope& envelope) {
  const face::MandibleAxes& a = m.axes;
  const MandibleStrut& s = m.strut[strut];
  // Pitch turns the anchor on a circle about the pitch axis (radius r_p, centre
  // c); yaw and protrusion are isometries after it, so |∂p/∂θ| = r_p exactly.
  const Eigen::Vector3d rel = s.mandible - a.pitch_point;
  const Eigen::Vector3d c = a.pitch_point + rel.dot(a.pitch_axis) * a.pitch_axis;
  const double r_p = (s.mandible - c).norm();
  // Yaw: the anchor's distance from the yaw axis, at most its distance from
  // the yaw point, at most |c − yaw point| + r_p wherever pitch has put it.
  const double r_y = (c - a.yaw_point).norm() + r_p;
  StrutRateBound b;
  b.gain = {r_p, r_y, 1.0};
  // Second derivatives of the anchor: |∂θθ p| = r_p, |∂θψ p| <= r_p,
  // |∂ψψ p| <= r_y, none through protrusion (a translation).
  const std::array<std::array<double, 3>, 3> anchor{{{r_p, r_p, 0.0}, {r_p, r_y, 0.0}, {0, 0, 0}}};
  // The anchor moves at most this far from rest (chord <= arc).
  auto reach = [](const Range& r) { return std::max(std::fabs(r.min), std::fabs(r.max)); };
  const double travel =
      r_p * reach(envelope.pitch) + r_y * reach(envelope.yaw) + reach(envelope.protrusion);
  b.min_length = std::max(1e-3, m.rest_length[strut] - travel);
  // L = |s − p|: ∂²L = (∂p_k·∂p_l − (u·∂p_k)(u·∂p_l)) / L − u·∂²p_kl.
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t l = 0; l < 3; ++l) {
      b.curvature[k][l] = b.gain[k] * b.gain[l] / b.min_length + anchor[k][l];
    }
  }
  return b;
}

StrutDemand strut_demand(const MandibleMechanism& m, std::size_t strut,
                         const MandibleEnvelope& envelope, const std::array<ActuatorLimits, 3>& dof,
                         int samples) {
  const StrutRateBound b = strut_rate_bound(m, strut, envelope);
  const Range axes[3] = {envelope.pitch, envelope.yaw, envelope.protrusion};
  std::array<double, 3> h{};  // half spacing of the grid, per axis
  std::array<int, 3> n{};
  for (std::size_t k = 0; k < 3; ++k) {
    n[k] = m.driven[k] ? samples : 1;
    h[k] = m.driven[k] ? 0.5 * (axes[k].max - axes[k].min) / (samples - 1) : 0.0;
  }
  double vel = 0.0, acc = 0.0;
  MandibleStrokes strokes{};
  Eigen::Matrix3d jac;
  for (int i = 0; i < n[0]; ++i) {
    for (int j = 0; j < n[1]; ++j) {
      for (int k = 0; k < n[2]; ++k) {
        const int idx[3] = {i, j, k};
        MandibleVector q;
        for (std::size_t a = 0; a < 3; ++a) {
          q[a] = n[a] == 1 ? 0.0 : axes[a].min + (axes[a].max - axes[a].min) * idx[a] / (n[a] - 1);
        }
        strokes_and_jacobian(m, m.held_in(q), strokes, jac);
        double v = 0.0, a = 0.0;
        for (std::size_t d = 0; d < 3; ++d) {
          if (!m.driven[d]) continue;
          v += std::fabs(jac(static_cast<Eigen::Index>(strut), static_cast<Eigen::Index>(d))) *
               dof[d].max_velocity;
          a += std::fabs(jac(static_cast<Eigen::Index>(strut), static_cast<Eigen::Index>(d))) *
               dof[d].max_acceleration;
        }
        vel = std::max(vel, v);
        acc = std::max(acc, a);
      }
    }
  }
  StrutDemand d;
  d.velocity = vel;
  d.acceleration = acc;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!m.driven[k]) continue;
    double slack = 0.0;  // how much |∂_k L| can grow between grid points
    for (std::size_t l = 0; l < 3; ++l) slack += b.curvature[k][l] * h[l];
    d.velocity += slack * dof[k].max_velocity;
    d.acceleration += slack * dof[k].max_acceleration;
    for (std::size_t l = 0; l < 3; ++l) {
      if (m.driven[l])
        d.acceleration += b.curvature[k][l] * dof[k].max_velocity * dof[l].max_velocity;
    }
  }
  return d;
}

}  // namespace facectl
