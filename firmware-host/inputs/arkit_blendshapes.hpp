#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string_view>

namespace facectl {

// ARKit's 52 face blendshapes (ARFaceAnchor.BlendShapeLocation), in the order
// Live Link Face writes them in its CSV files and UDP packets.
inline constexpr std::size_t kArkitCount = 52;
extern const std::array<std::string_view, kArkitCount> kArkitNames;  // eyeBlinkLeft, ...

// Finds a blendshape by name, ignoring case: ARKit and MediaPipe write
// eyeBlinkLeft, Live Link Face writes EyeBlinkLeft.
std::optional<std::size_t> find_arkit(std::string_view name);

}  // namespace facectl
