#include "control/mapping/rig_mapping.hpp"

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

namespace facectl {

bool RigMapping::drives(std::size_t actuator) const {
  if (linear.drives(actuator)) return true;
  if (mechanism) {
    for (std::size_t i = 0; i < mechanism->struts(); ++i) {
      if (mechanism->strut[i].actuator == actuator) return true;
    }
  }
  return std::any_of(points.begin(), points.end(),
                     [&](const PointTerm& p) { return p.actuator == actuator && p.gain != 0.0; });
}

void finish_points(RigMapping& mapping) {
  if (mapping.reduced) mapping.projection = project_point_terms(*mapping.reduced, mapping.points);
}

MappingWorkspace make_mapping_workspace(const RigMapping& mapping) {
  if (!mapping.points.empty() && mapping.projection.actuator.empty())
    throw std::logic_error("rig mapping: points without a projection (call finish_points)");
  MappingWorkspace w;
  if (!mapping.reduced || mapping.projection.actuator.empty()) return w;
  // The tick passes the first muscle_count face signals as the model's contractions.
  if (mapping.muscle_count != mapping.reduced->muscles.size())
    throw std::logic_error("rig mapping: " + std::to_string(mapping.muscle_count) +
                           " muscle signals, but the reduced face model has " +
                           std::to_string(mapping.reduced->muscles.size()) + " muscles");
  w.point_features = face::make_subset_workspace(mapping.projection.features);
  return w;
}

face::ReducedInput reduced_input(const RigMapping& m,
                                 const std::array<double, kMaxFaceSignals>& face) {
  face::ReducedInput in;
  in.contractions = std::span<const double>(face.data(), m.muscle_count);
  in.pitch_rad = face[m.jaw_pitch];
  in.yaw_rad = face[m.jaw_yaw];
  in.protrusion_m = face[m.jaw_protrusion];
  in.eyelid_closure[0] = face[m.eyelid_closure[0]];
  in.eyelid_closure[1] = face[m.eyelid_closure[1]];
  return in;
}

void evaluate_control_points(const RigMapping& m, MappingWorkspace& w,
                             const std::array<double, kMaxFaceSignals>& face) {
  if (!m.reduced || m.projection.actuator.empty()) return;
  face::evaluate_features(m.projection.features, w.point_features, reduced_input(m, face));
  Eigen::Map<Eigen::VectorXd> out(w.point_effector.data(), m.projection.weights.rows());
  out.noalias() = m.projection.weights * w.point_features.values;
}

void map_effectors(const RigMapping& m, MappingWorkspace& w,
                   const std::array<double, kMaxFaceSignals>& face) {
  m.linear.apply(face, w.effector);
  for (std::size_t r = 0; r < m.projection.actuator.size(); ++r)
    w.effector[m.projection.actuator[r]] += w.point_effector[r];
}

std::optional<double> transform_effector(const ChannelTransform& t, double effector,
                                         bool* clamped) {
  *clamped = false;
  switch (t.kind) {
    case ChannelTransform::Kind::kNone:
      return effector;
    case ChannelTransform::Kind::kCalibration: {
      *clamped = effector < t.curve.x_min() || effector > t.curve.x_max();
      return t.curve.evaluate(effector);
    }
    case ChannelTransform::Kind::kLinkage: {
      const double e = std::clamp(effector, t.linkage.effector_min, t.linkage.effector_max);
      *clamped = e != effector;
      return t.linkage.to_actuator(e);
    }
  }
  return std::nullopt;
}

std::uint64_t apply_transforms(const RigMapping& m, const MappingWorkspace& w,
                               std::array<double, kMaxActuators>& out) {
  std::uint64_t clamped_bits = 0;
  for (std::size_t i = 0; i < m.actuators(); ++i) {
    bool clamped = false;
    const std::optional<double> position =
        transform_effector(m.transforms[i], w.effector[i], &clamped);
    if (position) {
      out[i] = *position;
    } else {
      clamped = true;  // cannot close: keep the previous position
    }
    if (clamped) clamped_bits |= std::uint64_t{1} << i;
  }
  return clamped_bits;
}

std::uint64_t solve_mechanism(const RigMapping& m, MappingWorkspace& w,
                              const std::array<double, kMaxFaceSignals>& face,
                              std::array<double, kMaxActuators>& out) {
  if (!m.mechanism) return 0;
  const MandibleMechanism& mech = *m.mechanism;
  const face::MandiblePose target{face[m.jaw_pitch], face[m.jaw_yaw], face[m.jaw_protrusion]};
  MandibleStrokes strokes{};
  w.mechanism = solve(mech, target, strokes, &w.mechanism_rotations);
  std::uint64_t bits = 0;
  for (std::size_t i = 0; i < mech.struts(); ++i) {
    out[mech.strut[i].actuator] = strokes[i];
    if (w.mechanism.clamped) bits |= std::uint64_t{1} << mech.strut[i].actuator;
  }
  return bits;
}

std::uint64_t map_to_actuators(const RigMapping& m, MappingWorkspace& w,
                               const std::array<double, kMaxFaceSignals>& face,
                               std::array<double, kMaxActuators>& out) {
  evaluate_control_points(m, w, face);
  map_effectors(m, w, face);
  const std::uint64_t clamped = apply_transforms(m, w, out);
  return clamped | solve_mechanism(m, w, face, out);
}

}  // namespace facectl
