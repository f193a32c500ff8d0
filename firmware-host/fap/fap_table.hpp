#pragma once

#include <array>
#include <string_view>

namespace facectl {

// The units a FAP is expressed in (ISO/IEC 14496-2 FAPU). Lengths are fractions
// (1/1024) of distances on the neutral face; AU is 1e-5 rad.
enum class FapUnit { kNone, kMNS, kMW, kENS, kES, kIRISD, kAU };

// Positive direction of a FAP in head coordinates: +x the head's left, +y up,
// +z the gaze direction (the MPEG-4 neutral face).
enum class FapDirection { kNone, kUp, kDown, kLeft, kRight, kForward, kGrowing };

struct FapInfo {
  int number = 0;  // 1..68
  std::string_view name;
  FapUnit unit = FapUnit::kNone;
  bool bidirectional = true;  // false: only values >= 0 mean anything
  FapDirection direction = FapDirection::kNone;
  std::string_view feature_point;  // FDP the FAP moves, e.g. "2.1"
};

inline constexpr int kFapCount = 68;

// The 68 FAPs of ISO/IEC 14496-2 (Annex C), in number order.
const std::array<FapInfo, kFapCount>& fap_table();
const FapInfo& fap_info(int number);  // 1..68
std::string_view fap_unit_name(FapUnit unit);

}  // namespace facectl
