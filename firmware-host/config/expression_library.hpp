#pragma once

#include <map>
#include <string>

#include "firmware-host/config/face_pose.hpp"

namespace facectl {

// Named face poses (joy, sadness, ...), loaded from config/expressions/*.yaml:
//   expressions:
//     joy: { muscles: {...}, mandible: {...}, rigid: {...} }
class ExpressionLibrary {
 public:
  static ExpressionLibrary load(const std::string& path, const FaceLayout& layout);

  const FacePose* find(const std::string& name) const;
  const std::map<std::string, FacePose>& all() const { return poses_; }

 private:
  std::map<std::string, FacePose> poses_;
};

}  // namespace facectl
