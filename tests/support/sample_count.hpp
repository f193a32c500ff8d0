// How many samples, ticks or trials a long randomised test draws.
#pragma once

#include <algorithm>

namespace facectl::testing {

// True in a sanitizer build (FACECTL_SANITIZE or FACECTL_FUZZ).
#ifdef FACECTL_SANITIZED
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

// The full count in the ordinary build, a tenth (at least `minimum`) in a
// sanitizer build. The sanitizer run looks for memory errors, races and
// undefined behaviour on the paths the samples take, which a tenth of them
// still takes, and makes each sample 5-20 times slower; the ordinary suite,
// which checks the statistics, draws them all (docs/FUZZING.md).
constexpr long sample_count(long full, long minimum = 1) {
  return kSanitized ? std::max(full / 10, minimum) : full;
}

}  // namespace facectl::testing
