#include "firmware-host/inputs/arkit_capture.hpp"

#include <algorithm>

namespace facectl {

PoseTrack arkit_pose_track(const ArkitCapture& capture, const RetargetTable& table,
                           const FaceLayout& layout,
                           const std::array<double, kMaxFaceSignals>& neutral,
                           std::vector<std::string>& notes) {
  PoseTrack track(layout.size());
  track.reserve(capture.frames.size());
  const auto pan = layout.find("neck_pan");
  const auto tilt = layout.find("neck_tilt");
  const auto roll = layout.find("neck_roll");
  long clamped = 0;
  for (const ArkitFrame& f : capture.frames) {
    std::array<double, kMaxFaceSignals> pose = neutral;
    if (f.has_head) {
      pose[*pan] += f.head_yaw;
      pose[*tilt] += f.head_pitch;
      pose[*roll] += f.head_roll;
    }
    clamped += table.add_arkit(f.weights, pose);
    track.add(f.t, pose);
  }
  if (clamped > 0) {
    notes.push_back("clamped: " + std::to_string(clamped) +
                    " signal values summed past their range by the retargeting table");
  }
  std::string unmapped;
  for (std::size_t k = 0; k < kArkitCount; ++k) {
    if (table.has_arkit(k)) continue;
    const bool used = std::any_of(capture.frames.begin(), capture.frames.end(),
                                  [k](const ArkitFrame& f) { return f.weights[k] > 0.0; });
    if (used) unmapped += (unmapped.empty() ? "" : ", ") + std::string(kArkitNames[k]);
  }
  if (!unmapped.empty())
    notes.push_back("not shown by this head (retarget.yaml unmapped): " + unmapped);
  return track;
}

}  // namespace facectl
