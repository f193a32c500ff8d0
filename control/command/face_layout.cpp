#include "control/command/face_layout.hpp"

#include <numbers>
#include <stdexcept>

#include "control/capacity.hpp"
#include "control/units.hpp"

namespace facectl {
namespace {

// Rigid DOFs every head has. The domain is what can be meant at all; the
// tighter admissible range is the head's envelope (mandible_envelope.hpp).
struct RigidSignal {
  std::string_view name;
  SignalKind kind;
  double domain_min;
  double domain_max;
};
constexpr RigidSignal kRigidSignals[] = {
    {FaceLayout::kJawPitch, SignalKind::kAngle, -90 * kDeg, 90 * kDeg},
    {FaceLayout::kJawYaw, SignalKind::kAngle, -90 * kDeg, 90 * kDeg},
    {FaceLayout::kJawProtrusion, SignalKind::kLength, -0.1, 0.1},
    {"eye_yaw_l", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {"eye_yaw_r", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {"eye_pitch_l", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {"eye_pitch_r", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {FaceLayout::kEyelidClosureLeft, SignalKind::kFraction, 0.0, 1.0},
    {FaceLayout::kEyelidClosureRight, SignalKind::kFraction, 0.0, 1.0},
    {"neck_pan", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {"neck_tilt", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
    {"neck_roll", SignalKind::kAngle, -180 * kDeg, 180 * kDeg},
};

}  // namespace

double yaml_to_si(SignalKind kind) {
  switch (kind) {
    case SignalKind::kAngle:
      return kDeg;
    case SignalKind::kLength:
      return 1e-3;
    default:
      return 1.0;
  }
}

std::string_view yaml_unit(SignalKind kind) {
  switch (kind) {
    case SignalKind::kAngle:
      return "deg";
    case SignalKind::kLength:
      return "mm";
    default:
      return "";
  }
}

FaceLayout::FaceLayout(const std::vector<std::string>& muscle_names)
    : muscle_count_(muscle_names.size()) {
  if (muscle_names.size() + std::size(kRigidSignals) > kMaxFaceSignals) {
    throw std::length_error("face layout: more signals than kMaxFaceSignals");
  }
  for (const auto& name : muscle_names) {
    signals_.push_back({name, SignalKind::kContraction, 0.0, 1.0});
  }
  for (const auto& rigid : kRigidSignals) {
    signals_.push_back({std::string(rigid.name), rigid.kind, rigid.domain_min, rigid.domain_max});
  }
  eyelid_closure_[0] = *find(kEyelidClosureLeft);
  eyelid_closure_[1] = *find(kEyelidClosureRight);
}

std::string yaml_key(const SignalInfo& info) {
  const std::string_view unit = yaml_unit(info.kind);
  return unit.empty() ? info.name : info.name + "_" + std::string(unit);
}

std::optional<std::size_t> FaceLayout::find_yaml_key(std::string_view key) const {
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    if (yaml_key(signals_[i]) == key) return i;
  }
  return std::nullopt;
}

std::optional<std::size_t> FaceLayout::find(std::string_view name) const {
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    if (signals_[i].name == name) return i;
  }
  return std::nullopt;
}

}  // namespace facectl
