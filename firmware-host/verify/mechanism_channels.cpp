#include "firmware-host/verify/mechanism_channels.hpp"

#include <algorithm>

#include "control/analysis/mechanism_range_proof.hpp"

namespace facectl::verify {

std::vector<MechanismChannel> mechanism_channels(const ControllerModel& m, const Polytope& set) {
  std::vector<MechanismChannel> out;
  if (!m.mapping.mechanism) return out;
  const MandibleMechanism& mech = *m.mapping.mechanism;
  const std::size_t jaw[3] = {m.layout.jaw_pitch(), m.layout.jaw_yaw(), m.layout.jaw_protrusion()};

  const MandibleEnvelope env{{set.lo[jaw[0]], set.hi[jaw[0]]},
                             {set.lo[jaw[1]], set.hi[jaw[1]]},
                             {set.lo[jaw[2]], set.hi[jaw[2]]}};
  std::vector<MandibleLinearConstraint> rows;
  for (std::size_t r = 0; r < set.rows.size(); ++r) {
    MandibleLinearConstraint c;
    c.b = set.rhs[r];
    bool touches_jaw = false;
    for (std::size_t j = 0; j < set.size(); ++j) {
      const double a = set.rows[r][j];
      if (a == 0.0) continue;
      const auto k = std::find(std::begin(jaw), std::end(jaw), j) - std::begin(jaw);
      if (k < 3) {
        c.a[k] = a;
        touches_jaw = true;
      } else {
        c.b -= std::min(a * set.lo[j], a * set.hi[j]);  // the other terms at their smallest
      }
    }
    if (touches_jaw) rows.push_back(c);
  }
  const MechanismRangeProof proof = prove_stroke_ranges(mech, env, rows);
  if (proof.empty) return out;

  auto face_at = [&](const face::MandiblePose& pose) {
    std::vector<double> x(set.size());
    for (std::size_t j = 0; j < x.size(); ++j)
      x[j] = std::clamp(m.neutral[j], set.lo[j], set.hi[j]);
    x[jaw[0]] = pose.pitch_rad;
    x[jaw[1]] = pose.yaw_rad;
    x[jaw[2]] = pose.protrusion_m;
    return x;
  };
  for (std::size_t i = 0; i < proof.count; ++i) {
    const StrokeEnclosure& e = proof.strut[i];
    out.push_back({mech.strut[i].actuator, e.proven.min, e.proven.max, face_at(e.argmin),
                   face_at(e.argmax), e.converged});
  }
  return out;
}

}  // namespace facectl::verify
