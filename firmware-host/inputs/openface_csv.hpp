#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "firmware-host/inputs/pose_track.hpp"
#include "firmware-host/inputs/retarget_table.hpp"

namespace facectl {

// OpenFace 2.x FeatureExtraction CSV: per frame, the action units' intensity
// (AUxx_r, 0..5) and presence (AUxx_c, 0 or 1), with the tracker's confidence
// and success. The header separates names with ", ", rows with ","; columns
// are found by name, so both the 2.0 layout (no face_id) and 2.2's read.
struct OpenFaceFrame {
  double t = 0.0;  // s, the timestamp column, from the first frame
  std::array<double, RetargetTable::kMaxActionUnit + 1> intensity{};  // by AU number
  bool tracked = true;  // success 1 and confidence >= kMinOpenFaceConfidence
};

struct OpenFaceCapture {
  std::vector<OpenFaceFrame> frames;
  std::vector<std::string> notes;
};

// Below this confidence a frame is held, not played (our choice, docs/INPUTS.md):
// a face the tracker is unsure of gives AUs that jump.
inline constexpr double kMinOpenFaceConfidence = 0.8;

// An AU with only a presence column (AU28 in OpenFace 2.x) plays at this
// intensity when present: FACS C, "marked".
inline constexpr double kPresenceOnlyIntensity = 3.0;

bool looks_like_openface_csv(std::string_view text);
// Throws ConfigError naming file:line.
OpenFaceCapture parse_openface_csv(std::string_view text, const std::string& file);

// Face poses: neutral plus the AUs through the retargeting table. A run of
// untracked frames holds the last tracked pose until the next tracked frame.
PoseTrack openface_pose_track(const OpenFaceCapture& capture, const RetargetTable& table,
                              const FaceLayout& layout,
                              const std::array<double, kMaxFaceSignals>& neutral,
                              std::vector<std::string>& notes);

}  // namespace facectl
