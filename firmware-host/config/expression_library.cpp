#include "firmware-host/config/expression_library.hpp"

namespace facectl {

ExpressionLibrary ExpressionLibrary::load(const std::string& path, const FaceLayout& layout) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"expressions", "sequences"});
  ExpressionLibrary lib;
  for (const auto& [name, node] : root["expressions"].entries()) {
    lib.poses_.emplace(name, parse_pose(node, layout, {"description"}));
  }
  // Sequences (e.g. the chewing cycle) name poses of the library.
  if (auto sequences = root.get("sequences")) {
    for (const auto& [name, seq] : sequences->entries()) {
      seq.expect_keys({"period_s", "poses"});
      (void)seq["period_s"].positive();
      for (const ConfigNode& pose : seq["poses"].items()) {
        if (lib.find(pose.string()) == nullptr) {
          pose.fail("a pose of this library", "'" + pose.string() + "'");
        }
      }
    }
  }
  return lib;
}

const FacePose* ExpressionLibrary::find(const std::string& name) const {
  const auto it = poses_.find(name);
  return it == poses_.end() ? nullptr : &it->second;
}

}  // namespace facectl
