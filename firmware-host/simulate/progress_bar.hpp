#pragma once

#include <cstdio>

namespace facectl {

// A progress bar on stderr for long simulations: drawn only when stderr is a
// terminal (isatty), redrawn at most once per percent; silent otherwise, so
// logs and pipes stay clean.
class ProgressBar {
 public:
  // `total`: the amount at 100 % (simulated seconds).
  explicit ProgressBar(double total, bool enabled);
  static bool stderr_is_terminal();

  void update(double done) {
    if (enabled_ && done >= next_) draw(done);
  }
  void finish();

 private:
  void draw(double done);

  double total_;
  bool enabled_;
  double next_ = 0.0;
};

}  // namespace facectl
