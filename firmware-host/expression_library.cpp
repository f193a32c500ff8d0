#include "firmware-host/expression_library.hpp"

namespace facectl {

ExpressionLibrary ExpressionLibrary::load(const std::string& path, const FaceLayout& layout) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"expressions"});
  ExpressionLibrary lib;
  for (const auto& [name, node] : root["expressions"].entries()) {
    lib.poses_.emplace(name, parse_pose(node, layout, {"description"}));
  }
  return lib;
}

const FacePose* ExpressionLibrary::find(const std::string& name) const {
  const auto it = poses_.find(name);
  return it == poses_.end() ? nullptr : &it->second;
}

}  // namespace facectl
