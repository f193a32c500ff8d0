#include "default_head.hpp"

namespace facectl::face::testing {

const HeadSpec& default_spec() {
  static const HeadSpec spec = load_head_spec(FACECTL_DEFAULT_HEAD_DIR);
  return spec;
}

const FaceModel& default_model() {
  static const FaceModel model = build_face_model(default_spec());
  return model;
}

const ExpressionLibrary& default_library() {
  static const ExpressionLibrary lib =
      load_expression_library(FACECTL_CONFIG_DIR "/expressions/library.yaml", default_spec());
  return lib;
}

}  // namespace facectl::face::testing
