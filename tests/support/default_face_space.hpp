// The default head's admissible face space for verify tests and benchmarks: the shipped
// reduced face model, the box (muscles [0, 1], the design mandible envelope) and a few
// coupled limits of the kind a rig declares.
#pragma once

#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/analysis/channel_bound.hpp"
#include "facectl/face/head_spec.hpp"
#include "facectl/face/reduced_model_fit.hpp"

namespace facectl::testing {

struct DefaultFaceSpace {
  face::ReducedFaceModel model;
  // Muscles; pitch = n, yaw = n + 1, protrusion = n + 2, eyelid closures n + 3 and n + 4.
  int n = 0;
  std::vector<verify::Interval> box;  // n + 5 intervals, SI

  int muscle(const std::string& name) const {
    for (int i = 0; i < n; ++i)
      if (model.muscles[static_cast<std::size_t>(i)] == name) return i;
    throw std::runtime_error("no muscle " + name);
  }
  int point(const std::string& name) const {
    for (std::size_t i = 0; i < model.control_points.size(); ++i)
      if (model.control_points[i] == name) return static_cast<int>(i);
    throw std::runtime_error("no control point " + name);
  }
  verify::LinearInequality row(std::vector<std::pair<int, double>> a, double b) const {
    verify::LinearInequality r{std::vector<double>(box.size(), 0.0), b};
    for (auto [v, c] : a) r.a[static_cast<std::size_t>(v)] = c;
    return r;
  }
  // Antagonists on the left lip corner, zygomaticus_major_l + depressor_anguli_oris_l ≤ 1,
  // and yaw within a band that widens with pitch, |yaw| ≤ 0.05 + 0.3·pitch.
  std::vector<verify::LinearInequality> coupled_limits() const {
    return {row({{muscle("zygomaticus_major_l"), 1}, {muscle("depressor_anguli_oris_l"), 1}}, 1),
            row({{n + 1, 1}, {n, -0.3}}, 0.05), row({{n + 1, -1}, {n, -0.3}}, 0.05)};
  }
};

inline const DefaultFaceSpace& default_face_space() {
  static const DefaultFaceSpace s = [] {
    constexpr double kDeg = std::numbers::pi / 180;
    DefaultFaceSpace r;
    r.model = face::load_reduced_model(FACECTL_DEFAULT_HEAD_DIR "/reduced_face.txt",
                                       face::load_head_spec(FACECTL_DEFAULT_HEAD_DIR));
    r.n = static_cast<int>(r.model.muscles.size());
    r.box.assign(static_cast<std::size_t>(r.n), verify::Interval{0, 1});
    r.box.push_back({-4 * kDeg, 18 * kDeg});
    r.box.push_back({-5 * kDeg, 5 * kDeg});
    r.box.push_back({0, 0.008});
    r.box.push_back({0, 1});  // eyelid closures
    r.box.push_back({0, 1});
    return r;
  }();
  return s;
}

}  // namespace facectl::testing
