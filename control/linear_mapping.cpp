#include "control/linear_mapping.hpp"

namespace facectl {

LinearMapping::LinearMapping(std::size_t actuators, std::size_t signals)
    : gains_(Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(actuators),
                                   static_cast<Eigen::Index>(signals))),
      offsets_(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(actuators))) {}

bool LinearMapping::drives(std::size_t actuator) const {
  return gains_.row(static_cast<Eigen::Index>(actuator)).cwiseAbs().maxCoeff() > 0.0;
}

void LinearMapping::apply(const std::array<double, kMaxFaceSignals>& signals,
                          std::array<double, kMaxActuators>& positions) const {
  const Eigen::Map<const Eigen::VectorXd> x(signals.data(), gains_.cols());
  Eigen::Map<Eigen::VectorXd> y(positions.data(), gains_.rows());
  y = offsets_;
  y.noalias() += gains_ * x;
}

}  // namespace facectl
