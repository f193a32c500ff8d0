// Headless CPU rendering of the face: an orthographic z-buffered triangle rasteriser with
// Gouraud-interpolated Lambert shading, 2× supersampled. Draws the skin with eyeballs,
// teeth and a dark mouth cavity, or (muscles view) the skull and the muscle boxes.
#pragma once

#include "facectl/face/face_model.hpp"
#include "facectl/face/image.hpp"

namespace facectl::face {

enum class View { kFront, kSide, kThreeQuarter };

struct RenderOptions {
  View view = View::kFront;
  int width = 480, height = 600;
  bool muscles = false;  // skull + muscles instead of the skin
};

Image render_face(const FaceModel& m, const FaceData& d, const RenderOptions& o);

}  // namespace facectl::face
