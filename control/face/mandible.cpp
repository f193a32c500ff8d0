#include "control/face/mandible.hpp"

#include <cmath>

namespace facectl::face {

Mat3 rodrigues(const Vec3& u, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  Mat3 K;
  K << 0, -u.z(), u.y(), u.z(), 0, -u.x(), -u.y(), u.x(), 0;
  return c * Mat3::Identity() + (1 - c) * u * u.transpose() + s * K;
}

RigidTransform rotation_about_line(const Vec3& point, const Vec3& axis, double angle) {
  RigidTransform T;
  T.R = rodrigues(axis, angle);
  T.t = point - T.R * point;  // tra(p)·rot·tra(−p)
  return T;
}

RigidTransform compose(const RigidTransform& outer, const RigidTransform& inner) {
  return {outer.R * inner.R, outer.R * inner.t + outer.t};
}

MandibleAxes mandible_axes(const Vec3& l213, const Vec3& l214, const Vec3& l114, const Vec3& l71,
                           const Vec3& l210) {
  MandibleAxes a;
  a.pitch_point = l214;
  a.pitch_axis = (l213 - l214).normalized();
  a.yaw_point = 0.5 * (l213 + l214);
  a.yaw_axis = (l114 - a.yaw_point).normalized();
  a.protrusion_dir = (l210 - l71).normalized();
  return a;
}

RigidTransform mandible_transform(const MandibleAxes& a, const MandiblePose& pose) {
  RigidTransform P = rotation_about_line(a.pitch_point, a.pitch_axis, pose.pitch_rad);
  RigidTransform Y = rotation_about_line(a.yaw_point, a.yaw_axis, pose.yaw_rad);
  RigidTransform T;
  T.t = pose.protrusion_m * a.protrusion_dir;
  return compose(T, compose(Y, P));
}

}  // namespace facectl::face
