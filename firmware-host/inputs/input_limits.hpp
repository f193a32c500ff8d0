// Upper bounds on what one input file may ask for (docs/SHOWS.md, "Limits"),
// checked while reading it: one number must not buy unbounded work or disk.
#pragma once

namespace facectl {

// The last keyframe of a show, or the last frame of a FAP file, at most a day
// in: a longer run is several files, and `simulate` writes each second.
inline constexpr double kMaxShowSeconds = 86400.0;

}  // namespace facectl
