// Shared by the tests of telemetry.csv's number writers (write_g6, write_f6):
// a fast writer's text against its reference's on many values.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace facectl::testing {

// Counts the values compared and reports the first five that differ.
class SameText {
 public:
  void compare(double v, const std::string& fast, const std::string& reference) {
    ++checked_;
    if (fast != reference && ++differ_ <= 5) {
      ADD_FAILURE() << v << ": " << fast << " vs " << reference;
    }
  }
  long checked() const { return checked_; }

 private:
  long checked_ = 0, differ_ = 0;
};

// check(v) on `count` values 10^x, x uniform in [lo, hi), one in
// `negative_one_in` negated.
template <class Check>
void for_random_magnitudes(std::mt19937_64& rng, double lo, double hi, int count,
                           unsigned negative_one_in, Check check) {
  std::uniform_real_distribution<double> exponent(lo, hi);
  for (int i = 0; i < count; ++i) {
    const double v = std::pow(10.0, exponent(rng));
    check(rng() % negative_one_in != 0 ? v : -v);
  }
}

}  // namespace facectl::testing
