#include "control/mapping/calibration_curve.hpp"

#include <algorithm>

namespace facectl {

bool CalibrationCurve::set(const double* x, const double* y, std::size_t n,
                           std::size_t* bad_point) {
  n_ = 0;
  if (n < 2 || n > kMaxPoints) {
    if (bad_point != nullptr) *bad_point = n < 2 ? n : kMaxPoints;
    return false;
  }
  const bool up = y[1] > y[0];
  for (std::size_t i = 1; i < n; ++i) {
    const bool ok = x[i] > x[i - 1] && (up ? y[i] > y[i - 1] : y[i] < y[i - 1]);
    if (!ok) {
      if (bad_point != nullptr) *bad_point = i;
      return false;
    }
  }
  std::copy_n(x, n, x_.begin());
  std::copy_n(y, n, y_.begin());
  n_ = n;
  return true;
}

double CalibrationCurve::evaluate(double x) const {
  if (n_ == 0) return x;
  if (x <= x_[0]) return y_[0];
  if (x >= x_[n_ - 1]) return y_[n_ - 1];
  const auto it = std::upper_bound(x_.begin(), x_.begin() + static_cast<std::ptrdiff_t>(n_), x);
  const std::size_t i = static_cast<std::size_t>(it - x_.begin());
  const double u = (x - x_[i - 1]) / (x_[i] - x_[i - 1]);
  return y_[i - 1] + u * (y_[i] - y_[i - 1]);
}

std::optional<double> CalibrationCurve::inverse(double y) const {
  if (n_ == 0) return y;
  const bool up = increasing();
  const double lo = up ? y_[0] : y_[n_ - 1];
  const double hi = up ? y_[n_ - 1] : y_[0];
  if (y < lo || y > hi) return std::nullopt;
  for (std::size_t i = 1; i < n_; ++i) {
    const double a = y_[i - 1];
    const double b = y_[i];
    if ((y >= std::min(a, b)) && (y <= std::max(a, b))) {
      const double u = (y - a) / (b - a);
      return x_[i - 1] + u * (x_[i] - x_[i - 1]);
    }
  }
  return std::nullopt;
}

}  // namespace facectl
