#include "firmware-host/inputs/lip_sync_track.hpp"

#include <cmath>

namespace facectl {

PoseTrack lip_sync_pose_track(const VisemeTimeline& timeline, const VisemeTable& visemes,
                              const FaceLayout& layout,
                              const std::array<double, kMaxFaceSignals>& neutral, double rate_hz) {
  // Each viseme as its change from neutral: unset signals do not move.
  std::array<std::array<double, kMaxFaceSignals>, VisemeTable::kCount> delta{};
  for (int v = 0; v < VisemeTable::kCount; ++v) {
    const FacePose& p = visemes.pose(v);
    for (std::size_t i = 0; i < layout.size(); ++i) {
      if (p.set.test(i)) delta[static_cast<std::size_t>(v)][i] = p.values[i] - neutral[i];
    }
  }
  const auto samples = static_cast<std::size_t>(std::ceil(timeline.duration() * rate_hz)) + 1;
  PoseTrack track(layout.size());
  track.reserve(samples);
  std::array<double, VisemeTable::kCount> w{};
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / rate_hz;
    timeline.weights(t, w);
    std::array<double, kMaxFaceSignals> pose = neutral;
    for (int v = 0; v < VisemeTable::kCount; ++v) {
      const double wv = w[static_cast<std::size_t>(v)];
      if (wv == 0.0) continue;
      for (std::size_t i = 0; i < layout.size(); ++i)
        pose[i] += wv * delta[static_cast<std::size_t>(v)][i];
    }
    track.add(t, pose);
  }
  return track;
}

}  // namespace facectl
