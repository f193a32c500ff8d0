// Shared by the face tests: the default head's spec and models built once per binary.
#pragma once

#include "facectl/face/face_model.hpp"

namespace facectl::face::testing {

const HeadSpec& default_spec();
const FaceModel& default_model();  // base 468-vertex skin

}  // namespace facectl::face::testing
