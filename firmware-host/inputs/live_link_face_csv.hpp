#pragma once

#include <string>
#include <string_view>

#include "firmware-host/inputs/arkit_capture.hpp"

namespace facectl {

// Live Link Face's CSV recordings (Epic Games' iPhone app):
//   Timecode,BlendShapeCount,EyeBlinkLeft,...,TongueOut,HeadYaw,HeadPitch,HeadRoll,LeftEyeYaw,...
//   20:48:16:30.908,61,0.0712,...
// Columns are found by name, so their order and extra columns do not matter;
// all 52 blendshapes must be there. The timecode is HH:MM:SS:FF[.sub]; its
// frame rate is 60 (the app's), or in a file that crosses a whole second, the
// smallest of 24, 25, 30, 48, 50, 60 above every FF in it. Rows with BlendShapeCount 0 (no face)
// and rows repeating the previous timecode are dropped and counted in the notes; weights a little
// outside 0..1 are clamped and counted. Throws ConfigError naming file:line for anything else.
ArkitCapture parse_live_link_face_csv(std::string_view text, const std::string& file);

// True when `text` starts like a Live Link Face CSV (for format detection).
bool looks_like_live_link_face_csv(std::string_view text);

}  // namespace facectl
