#pragma once

#include <array>
#include <cstdint>

#include "control/capacity.hpp"
#include "control/command/face_command.hpp"
#include "control/command/face_layout.hpp"

namespace facectl {

// Step 2 of the tick. A value that is NaN, infinite or outside its signal's
// domain never passes: it is counted, and the last good value is held.
class CommandSanitizer {
 public:
  // Domain values within this of a bound are snapped onto it, so that blended
  // contractions such as 1.0000000001 are not rejected as malformed.
  static constexpr double kDomainSlack = 1e-9;

  explicit CommandSanitizer(const FaceLayout& layout);

  // Starts from a known-good pose (the head's neutral).
  void reset(const std::array<double, kMaxFaceSignals>& good);

  // Sanitises `in` into the held good values; returns how many it rejected.
  std::uint32_t apply(const FaceCommand& in);

  const std::array<double, kMaxFaceSignals>& values() const { return good_; }
  std::uint64_t rejected_total() const { return rejected_total_; }
  std::uint64_t rejected(std::size_t signal) const { return rejected_[signal]; }

 private:
  const FaceLayout& layout_;
  std::array<double, kMaxFaceSignals> good_{};
  std::array<std::uint64_t, kMaxFaceSignals> rejected_{};
  std::uint64_t rejected_total_ = 0;
};

}  // namespace facectl
