#pragma once

#include <map>
#include <string>

#include "facectl/face/head_spec.hpp"
#include "facectl/face/points.hpp"
#include "firmware-host/fap/fap_table.hpp"

namespace facectl {

// The head's MPEG-4 feature points at rest (metres, head frame: +x the head's
// left, +y up, +z gaze), keyed by landmark name ("fdp_2_1").
class FeaturePoints {
 public:
  // Evaluates every landmark of the head spec on its skin mesh.
  static FeaturePoints load(const face::HeadSpec& spec);

  void set(const std::string& name, const face::Vec3& p) { points_[name] = p; }
  // Throws ConfigError naming the landmarks file when the head lacks `name`.
  const face::Vec3& at(const std::string& name) const;
  bool has(const std::string& name) const { return points_.count(name) != 0; }

 private:
  std::map<std::string, face::Vec3> points_;
  std::string source_ = "landmarks";
};

// The face animation parameter units of one head: neutral-face distances
// (metres) of which a FAP value is a 1/1024 fraction. AU is 1e-5 rad.
struct Fapu {
  double es0 = 0, ens0 = 0, mns0 = 0, mw0 = 0, irisd0 = 0;
  static constexpr double kAu = 1e-5;

  // Metres (or radians for AU) per FAP unit step.
  double unit(FapUnit u) const;
};

// ES0 = 3.5.x - 3.6.x (pupils); ENS0 = pupils' y - nose base y; MNS0 = nose
// base y - 2.2.y; MW0 = 8.3.x - 8.4.x; IRISD0 = mean of 3.1.y - 3.3.y and
// 3.2.y - 3.4.y. The nose base is the nostrils' midpoint mid(9.1, 9.2): the
// default head's fdp_9_15 sits on the nose bridge, where its muscles need it,
// not at the bottom of the nose where the standard's 9.15 is (docs/FAP.md).
// Throws ConfigError if a point is missing or a distance is not positive.
Fapu compute_fapu(const FeaturePoints& fp);

}  // namespace facectl
