// Structure-of-arrays point storage: x, y and z each contiguous, so the solver's
// loops over one coordinate stream through memory and nothing is boxed per particle.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "control/face/geometry.hpp"

namespace facectl::face {

struct Points {
  std::vector<double> x, y, z;

  std::size_t size() const { return x.size(); }
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  void push_back(const Vec3& v) {
    x.push_back(v.x());
    y.push_back(v.y());
    z.push_back(v.z());
  }
  Vec3 get(std::size_t i) const { return {x[i], y[i], z[i]}; }
  void set(std::size_t i, const Vec3& v) {
    x[i] = v.x();
    y[i] = v.y();
    z[i] = v.z();
  }
  void add(std::size_t i, const Vec3& v) {
    x[i] += v.x();
    y[i] += v.y();
    z[i] += v.z();
  }
};

}  // namespace facectl::face
