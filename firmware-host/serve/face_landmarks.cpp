#include "firmware-host/serve/face_landmarks.hpp"

#include "control/face/reduced_face_model.hpp"

namespace facectl {

struct FaceLandmarks::Work {
  face::ReducedFaceWorkspace workspace;
  std::vector<double> contractions;
  std::vector<double> displacements;
};

FaceLandmarks::FaceLandmarks(std::shared_ptr<const FaceGeometry> geometry)
    : geometry_(std::move(geometry)), work_(std::make_unique<Work>()) {
  work_->workspace = face::make_reduced_workspace(*geometry_->reduced);
  work_->contractions.resize(geometry_->muscle_signals.size());
  work_->displacements.resize(3 * geometry_->points.size());
}

FaceLandmarks::~FaceLandmarks() = default;

std::span<const double> FaceLandmarks::displacements_mm(std::span<const double> face_signals) {
  const FaceGeometry& g = *geometry_;
  for (std::size_t k = 0; k < g.muscle_signals.size(); ++k) {
    work_->contractions[k] = face_signals[g.muscle_signals[k]];
  }
  face::ReducedInput in{work_->contractions, face_signals[g.jaw_pitch], face_signals[g.jaw_yaw],
                        face_signals[g.jaw_protrusion]};
  in.eyelid_closure[0] = face_signals[g.eyelid_closure[0]];
  in.eyelid_closure[1] = face_signals[g.eyelid_closure[1]];
  face::evaluate(*g.reduced, work_->workspace, in, work_->displacements);
  for (double& d : work_->displacements) d *= 1e3;  // m -> mm
  return work_->displacements;
}

}  // namespace facectl
