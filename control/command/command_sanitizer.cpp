#include "control/command/command_sanitizer.hpp"

#include <algorithm>
#include <cmath>

namespace facectl {

CommandSanitizer::CommandSanitizer(const FaceLayout& layout) : layout_(layout) {}

void CommandSanitizer::reset(const std::array<double, kMaxFaceSignals>& good) {
  good_ = good;
}

std::uint32_t CommandSanitizer::apply(const FaceCommand& in) {
  std::uint32_t rejected_now = 0;
  for (std::size_t i = 0; i < layout_.size(); ++i) {
    const SignalInfo& info = layout_.signal(i);
    const double v = in.values[i];
    // std::isfinite is false for NaN and both infinities.
    if (!std::isfinite(v) || v < info.domain_min - kDomainSlack ||
        v > info.domain_max + kDomainSlack) {
      ++rejected_[i];
      ++rejected_now;
      continue;
    }
    // v is finite here: min/max inline, where fmin/fmax (NaN rules) are libm calls.
    good_[i] = std::min(std::max(v, info.domain_min), info.domain_max);
  }
  rejected_total_ += rejected_now;
  return rejected_now;
}

}  // namespace facectl
