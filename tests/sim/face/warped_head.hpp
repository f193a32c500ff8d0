// A second head for the motion-cloning tests: the default head under a smooth,
// non-uniform warp of space (a wider lower face, a shorter face, cheek bulges), same
// topology, so landmarks.yaml's vertex ids stay valid. Offsets that place points off the
// skin (landmark offset_mm, muscle corner offset_mm) go through the same warp:
// offset' = warp(p + offset) − warp(p), p the point they are measured from.
#pragma once

#include <string>

#include "facectl/face/points.hpp"

namespace facectl::face::testing {

// The warp, in the head's frame (m): +x the head's left, +y up, +z the gaze.
Vec3 warp_head_point(const Vec3& p);

// Writes the warped copy of the head folder `from` into `to` (created; files replaced).
// The copy has no reduced_face.txt (it would describe the unwarped head).
void write_warped_head(const std::string& from, const std::string& to);

}  // namespace facectl::face::testing
