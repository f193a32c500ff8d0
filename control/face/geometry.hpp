// The 3-vectors and 3×3 matrices of the face's geometry (head frame, metres).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace facectl::face {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

}  // namespace facectl::face
