#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "control/capacity.hpp"

namespace facectl {

// Step 6 (minimal form): each actuator's position is an offset plus a linear
// combination of face signals, all SI. Built once; applying it allocates nothing.
class LinearMapping {
 public:
  LinearMapping() = default;
  LinearMapping(std::size_t actuators, std::size_t signals);

  void set_offset(std::size_t actuator, double offset_si) { offsets_[actuator] = offset_si; }
  // Builds the model (may allocate); not for the tick.
  void set_gain(std::size_t actuator, std::size_t signal, double gain_si);
  double gain(std::size_t actuator, std::size_t signal) const { return gains_(actuator, signal); }
  double offset(std::size_t actuator) const { return offsets_[actuator]; }
  std::size_t actuators() const { return gains_.rows(); }
  std::size_t signals() const { return gains_.cols(); }
  bool drives(std::size_t actuator) const;

  void apply(const std::array<double, kMaxFaceSignals>& signals,
             std::array<double, kMaxActuators>& positions) const;

 private:
  // The non-zero gains as well, in (actuator, signal) order: an actuator reads
  // a few of the face's signals, so apply() sums these instead of multiplying
  // the mostly-zero matrix (26 × 41 for the default rig, 47 non-zero).
  struct Term {
    std::size_t actuator;
    std::size_t signal;
    double gain;
  };

  Eigen::MatrixXd gains_;    // actuators x signals
  Eigen::VectorXd offsets_;  // actuators
  std::vector<Term> terms_;
};

}  // namespace facectl
