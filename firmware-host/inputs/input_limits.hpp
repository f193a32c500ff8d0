// Upper bounds on what one input file may ask for (docs/SHOWS.md, "Limits"),
// checked while reading it: one number must not buy unbounded work or disk.
#pragma once

#include <cstddef>

namespace facectl {

// The last keyframe of a show, or the last frame of a FAP file, at most a day
// in: a longer run is several files, and `simulate` writes each second.
inline constexpr double kMaxShowSeconds = 86400.0;

// The most frames a capture file (Live Link Face, MediaPipe, OpenFace) may
// hold: 2.3 hours at 60 frames a second, about 0.4 GB parsed and retargeted.
// A 64 MiB file of tiny rows would otherwise cost tens of GB.
inline constexpr std::size_t kMaxCaptureFrames = 500'000;

// The longest speech audio the speech-driven jaw reads (its poses are kept,
// 100 a second), and the sample rates it takes.
inline constexpr double kMaxAudioSeconds = 2 * 3600.0;  // 0.24 GB of default-head poses
inline constexpr int kMinAudioRate = 1000;
inline constexpr int kMaxAudioRate = 768000;

}  // namespace facectl
