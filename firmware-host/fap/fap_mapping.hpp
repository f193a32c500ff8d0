#pragma once

#include <array>
#include <string>
#include <vector>

#include "control/capacity.hpp"
#include "control/envelope/mandible_envelope.hpp"
#include "control/face/mandible.hpp"
#include "facectl/face/reduced_model_fit.hpp"
#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fapu.hpp"
#include "firmware-host/fap/viseme_table.hpp"

namespace facectl {

// The FAP values in force: a FAP a frame does not transmit keeps the value it
// last had (0, the neutral face, before it is first sent).
struct FapState {
  std::array<double, kFapCount> values{};
  VisemeParams viseme;
  ExpressionParams expression;
  void apply(const FapFrame& frame);
};

// One value that left the face envelope and was clamped.
struct FapClamp {
  long frame = 0;
  int fap = 0;             // the FAP that drove the signal (1 or 2 for the high-level ones)
  std::string signal;      // face signal name, or the FAP's name for a negative unidirectional FAP
  double requested = 0.0;  // SI (rad, m, contraction) or FAP units for a FAP
  double applied = 0.0;
  std::string unit;  // how describe() prints it: "deg", "mm", "" or "FAP units"
};
std::string describe(const FapClamp& c);

// Where a FAP goes, for the docs and `describe_routes()`.
struct FapRouteInfo {
  int fap = 0;
  std::string target;  // e.g. "jaw_pitch (geometry)", "+ risorius_l / - orbicularis_oris"
  std::string gain;    // e.g. "0.0137 deg/unit at rest", "c=1 moves fdp_8_3 by 4.2 mm"
};

// FAPs -> face signals for one head (docs/FAP.md): the jaw FAPs through the
// mandible's geometry, lip, brow, cheek and nose FAPs through muscles whose
// response comes from the reduced face model, eyelids, eyeballs and head
// rotation directly; FAP 1 through the viseme table and FAP 2 through the
// expression library. Built once; map() does not allocate unless it reports.
class FapMapping {
 public:
  static FapMapping build(const HeadConfig& head, const FeaturePoints& points,
                          const face::ReducedFaceModel& reduced,
                          const ExpressionLibrary& expressions, const VisemeTable& visemes);

  // The pose (SI, layout order) for the FAP values in force, clamped to the
  // envelope; each clamp is appended to `clamps` (if given) tagged with `frame`.
  void map(const FapState& state, long frame, std::array<double, kMaxFaceSignals>& out,
           std::vector<FapClamp>* clamps) const;

  const Fapu& fapu() const { return fapu_; }
  const FaceLayout& layout() const { return layout_; }
  // FAPs that move something on this head.
  const FapMask& supported() const { return supported_; }
  std::vector<FapRouteInfo> describe_routes() const;

  // Jaw geometry, exposed for reports: pitch (rad) that lowers the chin
  // (fdp_2_1) by `open_jaw` MNS units, and whether the head can reach it.
  double pitch_for_open_jaw(double open_jaw, bool* reachable = nullptr) const;

 private:
  struct Response {  // one muscle group's displacement of a point along the FAP's direction
    std::vector<std::size_t> muscles;
    std::array<double, 11> along{};  // m at c = 0, 0.1, .., 1
  };
  struct MuscleRoute {
    int fap = 0;
    std::string point;
    Response positive, negative;  // negative.muscles may be empty
  };
  double contraction_for(const Response& r, double displacement) const;

  FaceLayout layout_{{}};
  Fapu fapu_;
  FapMask supported_;
  face::MandibleAxes axes_;
  face::Vec3 chin_ = face::Vec3::Zero();
  MandibleEnvelope envelope_;
  std::array<double, kMaxFaceSignals> neutral_{};
  std::array<double, kMaxFaceSignals> lo_{}, hi_{};
  std::vector<MuscleRoute> muscle_routes_;
  std::array<FacePose, 7> expressions_{};  // index 1..6: joy .. surprise
  std::array<FacePose, VisemeTable::kCount> visemes_{};
  std::size_t eyelid_l_ = 0, eyelid_r_ = 0, eye_yaw_l_ = 0, eye_yaw_r_ = 0, eye_pitch_l_ = 0,
              eye_pitch_r_ = 0, neck_pan_ = 0, neck_tilt_ = 0, neck_roll_ = 0;
};

// Builds the mapping for a loaded head: its feature points and reduced face
// model from the head's folder (face.yaml, landmarks.yaml, reduced_face.txt).
FapMapping load_fap_mapping(const HeadConfig& head, const ExpressionLibrary& expressions,
                            const std::string& visemes_path);

}  // namespace facectl
