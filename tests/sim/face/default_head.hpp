// Shared by the face tests: the default head's spec and models built once per binary.
#pragma once

#include "facectl/face/expression_library.hpp"
#include "facectl/face/face_model.hpp"

namespace facectl::face::testing {

const HeadSpec& default_spec();
const FaceModel& default_model();            // base 468-vertex skin
const ExpressionLibrary& default_library();  // config/expressions/library.yaml

}  // namespace facectl::face::testing
