#include "firmware-host/simulate/progress_bar.hpp"

#include <unistd.h>

#include <algorithm>

namespace facectl {

ProgressBar::ProgressBar(double total, bool enabled)
    : total_(std::max(total, 1e-9)), enabled_(enabled) {}

bool ProgressBar::stderr_is_terminal() {
  return isatty(STDERR_FILENO) == 1;
}

void ProgressBar::draw(double done) {
  constexpr int kWidth = 40;
  const double u = std::clamp(done / total_, 0.0, 1.0);
  const int filled = static_cast<int>(u * kWidth);
  char bar[kWidth + 1];
  for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '.';
  bar[kWidth] = '\0';
  std::fprintf(stderr, "\rsimulating [%s] %3d%%  %.1f / %.1f s", bar, static_cast<int>(u * 100.0),
               done, total_);
  std::fflush(stderr);
  next_ = done + total_ / 100.0;
}

void ProgressBar::finish() {
  if (!enabled_) return;
  draw(total_);
  std::fputc('\n', stderr);
}

}  // namespace facectl
