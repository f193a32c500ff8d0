#include "firmware-host/fap/viseme_table.hpp"

#include "firmware-host/config/config_node.hpp"

namespace facectl {

VisemeTable VisemeTable::load(const std::string& path, const FaceLayout& layout) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"visemes"});
  VisemeTable table;
  std::array<bool, kCount> seen{};
  for (const auto& [name, node] : root["visemes"].entries()) {
    const auto index = static_cast<std::size_t>(node["index"].integer_in(0, kCount - 1));
    if (seen[index]) {
      node["index"].fail("a viseme index not used before",
                         "index " + std::to_string(index) + " again");
    }
    seen[index] = true;
    table.names_[index] = name;
    table.poses_[index] = parse_pose(node, layout, {"index", "phonemes"});
  }
  for (std::size_t i = 0; i < kCount; ++i) {
    if (!seen[i]) {
      root["visemes"].fail("all 15 MPEG-4 visemes (index 0..14)",
                           "none with index " + std::to_string(i));
    }
  }
  return table;
}

}  // namespace facectl
