#pragma once

#include <array>
#include <cstddef>
#include <optional>

namespace facectl {

// A monotone piecewise-linear calibration curve y(x), e.g. servo command
// against measured face displacement. Fixed capacity so that it lives in the
// const model and evaluates without allocating; outside its points it holds
// the end values (never extrapolates).
class CalibrationCurve {
 public:
  static constexpr std::size_t kMaxPoints = 32;

  // Returns false (and stays empty) unless x is strictly increasing and y is
  // strictly monotone; `error` then says which point breaks it.
  bool set(const double* x, const double* y, std::size_t n, std::size_t* bad_point = nullptr);

  bool empty() const { return n_ == 0; }
  std::size_t size() const { return n_; }
  bool increasing() const { return n_ < 2 || y_[n_ - 1] > y_[0]; }
  double x_min() const { return x_[0]; }
  double x_max() const { return x_[n_ == 0 ? 0 : n_ - 1]; }
  double x(std::size_t i) const { return x_[i]; }
  double y(std::size_t i) const { return y_[i]; }
  double evaluate(double x) const;
  // The x with y(x) = y; nullopt outside the curve's y range.
  std::optional<double> inverse(double y) const;

 private:
  std::array<double, kMaxPoints> x_{};
  std::array<double, kMaxPoints> y_{};
  std::size_t n_ = 0;
};

}  // namespace facectl
