#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace facectl {

// What a face signal measures, which fixes its SI unit and its YAML unit.
enum class SignalKind {
  kContraction,  // muscle contraction, 1 (0..1)
  kFraction,     // eyelid closure, 1 (0..1)
  kAngle,        // rad in code, deg in YAML
  kLength,       // m in code, mm in YAML
};

struct SignalInfo {
  std::string name;
  SignalKind kind = SignalKind::kContraction;
  // Domain: values outside it are malformed and rejected by the sanitiser.
  double domain_min = 0.0;
  double domain_max = 1.0;
};

// The YAML key of a signal: its name, plus "_deg" or "_mm" where the unit is not SI.
std::string yaml_key(const SignalInfo& info);

// Factor from the YAML unit of a kind to SI (deg -> rad, mm -> m, else 1).
double yaml_to_si(SignalKind kind);
// The YAML unit suffix of a kind: "deg", "mm" or "" for dimensionless.
std::string_view yaml_unit(SignalKind kind);

// The named signals of a face command, in a fixed order: the head's muscles
// first, then the mandible, then the rigid degrees of freedom. Built once from
// the head config; the tick only uses indices.
class FaceLayout {
 public:
  // Fixed names of the non-muscle signals.
  static constexpr std::string_view kJawPitch = "jaw_pitch";
  static constexpr std::string_view kJawYaw = "jaw_yaw";
  static constexpr std::string_view kJawProtrusion = "jaw_protrusion";
  static constexpr std::string_view kEyelidClosureLeft = "eyelid_closure_l";
  static constexpr std::string_view kEyelidClosureRight = "eyelid_closure_r";

  explicit FaceLayout(const std::vector<std::string>& muscle_names);

  std::size_t size() const { return signals_.size(); }
  std::size_t muscle_count() const { return muscle_count_; }
  const SignalInfo& signal(std::size_t i) const { return signals_[i]; }
  std::optional<std::size_t> find(std::string_view name) const;
  // Finds a signal by its YAML key: the name plus its unit suffix
  // (zygomaticus_major_l, jaw_pitch_deg, jaw_protrusion_mm, eyelid_closure_l).
  std::optional<std::size_t> find_yaml_key(std::string_view key) const;

  std::size_t jaw_pitch() const { return muscle_count_; }
  std::size_t jaw_yaw() const { return muscle_count_ + 1; }
  std::size_t jaw_protrusion() const { return muscle_count_ + 2; }
  // The eyelid closure of `side`: 0 left, 1 right.
  std::size_t eyelid_closure(int side) const { return eyelid_closure_[side]; }

 private:
  std::vector<SignalInfo> signals_;
  std::size_t muscle_count_;
  std::size_t eyelid_closure_[2] = {0, 0};
};

}  // namespace facectl
