#pragma once

#include <memory>
#include <span>
#include <vector>

#include "firmware-host/serve/face_geometry.hpp"

namespace facectl {

// The reduced face model evaluated for one telemetry stream, on its HTTP thread (never on
// the tick): the control points' displacements (mm, x y z per point, the geometry's order)
// for a frame's face signals (SI: contractions, jaw pitch and yaw in rad, protrusion in m).
// Its workspace is allocated once, here.
class FaceLandmarks {
 public:
  explicit FaceLandmarks(std::shared_ptr<const FaceGeometry> geometry);
  ~FaceLandmarks();
  FaceLandmarks(const FaceLandmarks&) = delete;
  FaceLandmarks& operator=(const FaceLandmarks&) = delete;

  // Valid until the next call.
  std::span<const double> displacements_mm(std::span<const double> face_signals);

 private:
  struct Work;
  std::shared_ptr<const FaceGeometry> geometry_;
  std::unique_ptr<Work> work_;
};

}  // namespace facectl
