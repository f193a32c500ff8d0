#include "control/mapping/linear_mapping.hpp"

namespace facectl {

LinearMapping::LinearMapping(std::size_t actuators, std::size_t signals)
    : gains_(Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(actuators),
                                   static_cast<Eigen::Index>(signals))),
      offsets_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(actuators))) {}

void LinearMapping::set_gain(std::size_t actuator, std::size_t signal, double gain_si) {
  gains_(static_cast<Eigen::Index>(actuator), static_cast<Eigen::Index>(signal)) = gain_si;
  terms_.clear();
  for (Eigen::Index a = 0; a < gains_.rows(); ++a) {
    for (Eigen::Index k = 0; k < gains_.cols(); ++k) {
      if (gains_(a, k) != 0.0) {
        terms_.push_back({static_cast<std::size_t>(a), static_cast<std::size_t>(k), gains_(a, k)});
      }
    }
  }
}

bool LinearMapping::drives(std::size_t actuator) const {
  return gains_.row(static_cast<Eigen::Index>(actuator)).cwiseAbs().maxCoeff() > 0.0;
}

void LinearMapping::apply(const std::array<double, kMaxFaceSignals>& signals,
                          std::array<double, kMaxActuators>& positions) const {
  for (Eigen::Index a = 0; a < offsets_.size(); ++a) {
    positions[static_cast<std::size_t>(a)] = offsets_[a];
  }
  // terms_ is in (actuator, signal) order: each actuator's sum stays in a
  // register, added in the same order as one term at a time into positions.
  for (auto t = terms_.begin(); t != terms_.end();) {
    const std::size_t a = t->actuator;
    double sum = positions[a];
    for (; t != terms_.end() && t->actuator == a; ++t) sum += t->gain * signals[t->signal];
    positions[a] = sum;
  }
}

}  // namespace facectl
