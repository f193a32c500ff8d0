// The skin anchors' targets (internal header): where each skin vertex's anchor particle q
// sits this frame, in the frame of its support on a muscle or on the skull.
#pragma once

#include "facectl/face/face_model.hpp"

namespace facectl::face {

// Every frame: the targets (and support normals) of the anchors whose support can move,
// FaceModel::anchors_on_muscles and anchors_on_jaw.
void update_moving_anchor_targets(const FaceModel& m, FaceData& d);
// Once, at reset: the anchors on the skull away from the jaw (anchors_on_fixed_skull),
// whose support never moves.
void set_fixed_anchor_targets(const FaceModel& m, FaceData& d);

}  // namespace facectl::face
