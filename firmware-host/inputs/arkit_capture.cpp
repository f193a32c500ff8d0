#include "firmware-host/inputs/arkit_capture.hpp"

#include <algorithm>
#include <utility>

namespace facectl {

int arkit_frame_pose(const ArkitFrame& frame, const RetargetTable& table, const FaceLayout& layout,
                     const std::array<double, kMaxFaceSignals>& neutral,
                     std::array<double, kMaxFaceSignals>& pose) {
  pose = neutral;
  if (frame.has_head) {
    const std::pair<const char*, double> turns[] = {{"neck_pan", frame.head_yaw},
                                                    {"neck_tilt", frame.head_pitch},
                                                    {"neck_roll", frame.head_roll}};
    for (const auto& [name, angle] : turns) {
      if (const auto i = layout.find(name)) pose[*i] += angle;
    }
  }
  return table.add_arkit(frame.weights, pose);
}

PoseTrack arkit_pose_track(const ArkitCapture& capture, const RetargetTable& table,
                           const FaceLayout& layout,
                           const std::array<double, kMaxFaceSignals>& neutral,
                           std::vector<std::string>& notes) {
  PoseTrack track(layout.size());
  track.reserve(capture.frames.size());
  long clamped = 0;
  std::array<double, kMaxFaceSignals> pose{};
  for (const ArkitFrame& f : capture.frames) {
    clamped += arkit_frame_pose(f, table, layout, neutral, pose);
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
