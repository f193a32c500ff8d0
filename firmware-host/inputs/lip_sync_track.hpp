#pragma once

#include <array>

#include "firmware-host/fap/viseme_table.hpp"
#include "firmware-host/inputs/coarticulation.hpp"
#include "firmware-host/inputs/pose_track.hpp"

namespace facectl {

// Lip sync as face poses: the coarticulated viseme weights sampled at
// `rate_hz`, each pose the neutral face plus the weighted changes of the
// visemes' mouth poses (config/fap/visemes.yaml) from it. Weights sum to 1,
// so a pose where one viseme dominates fully is that viseme's pose exactly:
// the bilabials close the lips as their viseme does.
PoseTrack lip_sync_pose_track(const VisemeTimeline& timeline, const VisemeTable& visemes,
                              const FaceLayout& layout,
                              const std::array<double, kMaxFaceSignals>& neutral,
                              double rate_hz = 100.0);

}  // namespace facectl
