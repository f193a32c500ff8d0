#pragma once

#include <string>
#include <string_view>

#include "firmware-host/inputs/arkit_capture.hpp"

namespace facectl {

// MediaPipe face landmarker blendshapes saved as JSON (its 52 ARKit names
// plus "_neutral", which carries no motion and is skipped). Accepted shapes:
//   - one frame: a list of categories, [{"categoryName": "jawOpen", "score": 0.3}, ...]
//     (the name may be "category_name", as the Python API writes it, or "name" or
//     "label"; the score a number or a number in a string; other keys are ignored);
//   - one frame as an object of scores, {"jawOpen": 0.3, ...};
//   - a list of frames, or {"frames": [...]}; a frame may be an object holding the
//     categories under "blendshapes", "faceBlendshapes", "face_blendshapes" or "people"
//     (a list per face: the first face is taken), and its time under "timestamp_ms",
//     "timestampMs" (ms) or "t", "time" (s).
// Frames without a time are 1/30 s apart (MediaPipe's usual video rate).
// Throws ConfigError naming the file and the JSON path of what is wrong.
ArkitCapture parse_mediapipe_blendshapes(std::string_view text, const std::string& file);

}  // namespace facectl
