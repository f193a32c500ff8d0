// Headless CPU rendering of the face: an orthographic z-buffered triangle rasteriser with
// Gouraud-interpolated Lambert shading, 2× supersampled. Draws the skin with eyeballs,
// teeth and a dark mouth cavity, or (muscles view) the skull and the muscle boxes.
#pragma once

#include <vector>

#include "facectl/face/face_model.hpp"
#include "facectl/face/image.hpp"

namespace facectl::face {

enum class View { kFront, kSide, kThreeQuarter };

// kFrontal: one soft light near the camera (flat, even pictures). kRaking: a key light
// from above and to the side at a grazing angle, plus a weak fill and a little specular,
// so that folds, brow bunching and creases shade.
enum class Lighting { kFrontal, kRaking };

struct RenderOptions {
  View view = View::kFront;
  int width = 480, height = 600;
  bool muscles = false;  // skull + muscles instead of the skin
  Lighting lighting = Lighting::kFrontal;
  // When set: one value per skin vertex in mm; the skin is coloured by
  // heat_colour(value / heat_max_mm) (heat_map.hpp) instead of skin tone.
  const std::vector<double>* heat_mm = nullptr;
  double heat_max_mm = 10;
};

// Throws std::invalid_argument for a size outside 16..8192 pixels, a heat map whose
// length is not the skin's vertex count, or a scale that is not positive.
Image render_face(const FaceModel& m, const FaceData& d, const RenderOptions& o);

// Where render_face draws the world point p: x right, y down, in output pixels.
Eigen::Vector2d project_to_image(const FaceModel& m, const RenderOptions& o, const Vec3& p);

}  // namespace facectl::face
