#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "firmware-host/config/loaded_config.hpp"

namespace facectl::face {
struct ReducedFaceModel;
}

namespace facectl {

// What the console draws the face from (GET /api/v1/face/geometry): the head's reduced
// face model's control points at rest, its skin mesh at rest, and the linear map W that
// carries control-point displacements onto the skin. W is an RBF interpolation (thesis
// §3.4) through the control points and skull-fixed anchors held still: a picture of the
// reduced model, not the full face model. Built once at serve start; no Eigen here, so
// the HTTP side (httplib) can include it.
struct FaceGeometry {
  std::vector<std::string> points;   // the reduced model's control points, its order
  std::vector<double> points_mm;     // at rest, x y z per point (head frame)
  std::vector<std::string> anchors;  // landmarks that stay still in the interpolation
  std::vector<double> anchors_mm;
  std::vector<double> vertices_mm;        // the skin at rest, x y z per vertex
  std::vector<int> triangles;             // 3 vertex indices per triangle
  std::vector<double> weights;            // W: vertices × points, row-major
  std::vector<std::array<int, 2>> edges;  // lip contours and brows, by point index
  std::shared_ptr<const face::ReducedFaceModel> reduced;
  // Face signal index of each of the reduced model's muscles, and of the jaw's.
  std::vector<std::size_t> muscle_signals;
  std::size_t jaw_pitch = 0, jaw_yaw = 0, jaw_protrusion = 0;
  std::size_t eyelid_closure[2] = {0, 0};  // left, right
};

// The geometry, or why the head has none (no reduced_face.txt, files that do not load).
struct FaceGeometryLoad {
  std::shared_ptr<const FaceGeometry> geometry;
  std::string why_not;
};

FaceGeometryLoad load_face_geometry(const LoadedConfig& config);

}  // namespace facectl
