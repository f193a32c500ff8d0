#pragma once

#include <array>
#include <string>
#include <vector>

#include "firmware-host/inputs/arkit_blendshapes.hpp"
#include "firmware-host/inputs/pose_track.hpp"
#include "firmware-host/inputs/retarget_table.hpp"

namespace facectl {

// A recorded ARKit performance (Live Link Face CSV, MediaPipe blendshape
// JSON): per frame, the 52 blendshape weights and, where the producer gives
// them, the head's rotation.
struct ArkitFrame {
  double t = 0.0;                             // s from the first frame
  std::array<double, kArkitCount> weights{};  // 0..1
  bool has_head = false;
  double head_yaw = 0, head_pitch = 0, head_roll = 0;  // rad
};

struct ArkitCapture {
  std::string producer;  // "Live Link Face CSV", "MediaPipe blendshapes JSON"
  std::vector<ArkitFrame> frames;
  std::vector<std::string> notes;  // what was read leniently: clamps, dropped rows
};

// One frame's face pose: the head's neutral pose plus the retargeted
// blendshapes and, when the frame has it, the head rotation on the neck
// signals the head has. Returns how many signals were clamped.
int arkit_frame_pose(const ArkitFrame& frame, const RetargetTable& table, const FaceLayout& layout,
                     const std::array<double, kMaxFaceSignals>& neutral,
                     std::array<double, kMaxFaceSignals>& pose);

// Face poses: the head's neutral pose plus the retargeted blendshapes, and
// the head rotation on the neck (yaw -> neck_pan, pitch -> neck_tilt, roll ->
// neck_roll) when the capture has it. Clamps are counted into `notes`.
PoseTrack arkit_pose_track(const ArkitCapture& capture, const RetargetTable& table,
                           const FaceLayout& layout,
                           const std::array<double, kMaxFaceSignals>& neutral,
                           std::vector<std::string>& notes);

}  // namespace facectl
