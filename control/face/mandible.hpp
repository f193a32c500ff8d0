// The rigid 3-DOF mandible of thesis §5.2 (eqs. 5.1–5.5, erratum 11: the standard
// Rodrigues matrix). Axes are fixed to the skull and computed from rest landmarks:
//   pitch  about the line 2.14 → 2.13 (right to left condyle); +pitch opens the mouth;
//   yaw    about the line mid(2.13, 2.14) → 11.4 (upward); +yaw turns the chin to the
//          head's left (+x);
//   protrusion  along 7.1 → 2.10, in metres; + moves the chin forward (and down).
// Composition, applied to a rest-pose point v:  v' = T(d·u_t) · Y(yaw) · P(pitch) · v,
// i.e. pitch first, then yaw about the skull-fixed yaw axis, then protrusion.
#pragma once

#include "control/face/geometry.hpp"

namespace facectl::face {

struct RigidTransform {
  Mat3 R = Mat3::Identity();
  Vec3 t = Vec3::Zero();
  Vec3 apply(const Vec3& v) const { return R * v + t; }
  Vec3 rotate(const Vec3& n) const { return R * n; }
};

// R = cos θ I + (1 − cos θ) u uᵀ + sin θ [u]×, for unit u.
Mat3 rodrigues(const Vec3& unit_axis, double angle_rad);
// Rotation by `angle_rad` about the line through `point` along `unit_axis` (eqs. 5.3–5.4).
RigidTransform rotation_about_line(const Vec3& point, const Vec3& unit_axis, double angle_rad);
RigidTransform compose(const RigidTransform& outer, const RigidTransform& inner);

struct MandibleAxes {
  Vec3 pitch_point, pitch_axis;  // through 2.13/2.14
  Vec3 yaw_point, yaw_axis;      // through mid(2.13, 2.14) and 11.4
  Vec3 protrusion_dir;           // unit 7.1 → 2.10
};

MandibleAxes mandible_axes(const Vec3& fdp_2_13, const Vec3& fdp_2_14, const Vec3& fdp_11_4,
                           const Vec3& fdp_7_1, const Vec3& fdp_2_10);

struct MandiblePose {
  double pitch_rad = 0, yaw_rad = 0, protrusion_m = 0;
};

RigidTransform mandible_transform(const MandibleAxes& axes, const MandiblePose& pose);

}  // namespace facectl::face
