#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <map>
#include <span>
#include <string>

#include "control/capacity.hpp"
#include "firmware-host/config/head_config.hpp"
#include "firmware-host/inputs/arkit_blendshapes.hpp"

namespace facectl {

// The head's retargeting table (config/heads/<head>/retarget.yaml, format in
// docs/INPUTS.md): FACS action units and ARKit's blendshapes, each as the
// change from the rest pose it makes at full strength. Performance capture
// (Live Link Face, MediaPipe, OpenFace) becomes face poses through it.
class RetargetTable {
 public:
  static constexpr int kMaxActionUnit = 99;
  static constexpr double kMaxAuIntensity = 5.0;  // FACS E; OpenFace's AUxx_r scale

  // Throws ConfigError naming file:line:column: an unknown AU, blendshape,
  // muscle or signal; a `facs` reference to an AU the table lacks; a
  // blendshape neither mapped nor listed as unmapped; and a disagreement with
  // head.yaml's `facs` lists in either direction.
  static RetargetTable load(const std::string& path, const HeadConfig& head);

  bool has_action_unit(int au) const { return au_set_.test(static_cast<std::size_t>(au)); }
  bool has_arkit(std::size_t k) const { return arkit_set_.test(k); }
  // The change from rest of AU `au` at intensity 5, and of blendshape k at 1.
  const std::array<double, kMaxFaceSignals>& action_unit(int au) const {
    return au_[static_cast<std::size_t>(au)];
  }
  const std::array<double, kMaxFaceSignals>& arkit(std::size_t k) const { return arkit_[k]; }
  // Why the head cannot show an AU ("AU05") or blendshape, from `unmapped`.
  const std::map<std::string, std::string>& unmapped() const { return unmapped_; }

  // pose += sum of weight_k * arkit(k) (weights 0..1), then clamped to each
  // signal's domain. Returns how many signals were clamped.
  int add_arkit(std::span<const double, kArkitCount> weights,
                std::array<double, kMaxFaceSignals>& pose) const;
  // pose += sum of intensity_a / 5 * action_unit(a) (index = AU number,
  // intensities 0..5), then clamped. Returns how many signals were clamped.
  int add_action_units(std::span<const double, kMaxActionUnit + 1> intensities,
                       std::array<double, kMaxFaceSignals>& pose) const;

 private:
  int clamp(std::array<double, kMaxFaceSignals>& pose) const;

  FaceLayout layout_{{}};
  std::array<std::array<double, kMaxFaceSignals>, kMaxActionUnit + 1> au_{};
  std::bitset<kMaxActionUnit + 1> au_set_;
  std::array<std::array<double, kMaxFaceSignals>, kArkitCount> arkit_{};
  std::bitset<kArkitCount> arkit_set_;
  std::map<std::string, std::string> unmapped_;
};

// "AU12" -> 12; -1 when `key` is not AU followed by one or two digits.
int parse_action_unit_key(std::string_view key);

}  // namespace facectl
