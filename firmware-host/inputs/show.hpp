#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "firmware-host/config/expression_library.hpp"

namespace facectl {

enum class Ease { kLinear, kEaseIn, kEaseOut, kEaseInOut, kStep };

double ease(Ease curve, double u);

// A show: timed keyframes, each a full face pose built from an expression
// (with a weight) plus explicit muscle, mandible and rigid values. Between
// keyframes each signal follows the easing curve of the keyframe it moves to.
//   show:
//     name: demo
//     keyframes:
//       - { t: 0.0, expression: neutral }
//       - { t: 1.2, expression: joy, weight: 0.8, ease: ease_in_out, mandible: { pitch_deg: 6 } }
class Show {
 public:
  struct Keyframe {
    double t = 0.0;
    Ease ease = Ease::kEaseInOut;
    std::array<double, kMaxFaceSignals> values{};
  };

  static Show load(const std::string& path, const FaceLayout& layout,
                   const std::array<double, kMaxFaceSignals>& neutral,
                   const ExpressionLibrary& expressions);

  const std::string& name() const { return name_; }
  double duration() const { return keyframes_.empty() ? 0.0 : keyframes_.back().t; }
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }
  // The pose at time t (clamped to the show's span).
  void evaluate(double t, std::array<double, kMaxFaceSignals>& out) const;

 private:
  std::string name_;
  std::vector<Keyframe> keyframes_;
  std::size_t signal_count_ = 0;
};

}  // namespace facectl
