#include "firmware-host/config/mix_config.hpp"

#include <algorithm>

namespace facectl {
namespace {

std::vector<std::string> source_list(const ConfigNode& node) {
  std::vector<std::string> out;
  for (const ConfigNode& item : node.items()) {
    const std::string name = item.string();
    const auto& known = mix_source_names();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      item.fail("one of show, input, gamepad, fap_stream, live_link_face, midi");
    }
    if (std::find(out.begin(), out.end(), name) != out.end()) item.fail("each source once");
    out.push_back(name);
  }
  if (out.empty()) node.fail("at least one source");
  return out;
}

}  // namespace

const std::vector<std::string>& mix_source_names() {
  static const std::vector<std::string> names = {"show",       "input",          "gamepad",
                                                 "fap_stream", "live_link_face", "midi"};
  return names;
}

MixConfig parse_mix_config(const ConfigNode& node) {
  node.expect_keys({"groups", "others", "stale_ms", "fade_ms", "rate_hz"});
  MixConfig c;
  if (auto n = node.get("stale_ms")) c.stale_ms = n->number_in(1.0, 10000.0);
  if (auto n = node.get("fade_ms")) c.fade_ms = n->number_in(0.0, 10000.0);
  if (auto n = node.get("rate_hz")) c.rate_hz = n->number_in(1.0, 10000.0);
  c.others = source_list(node["others"]);
  if (auto groups = node.get("groups")) {
    for (const auto& [name, g] : groups->entries()) {
      g.expect_keys({"signals", "sources"});
      MixGroupConfig group;
      group.name = name;
      const ConfigNode signals = g["signals"];
      for (const ConfigNode& item : signals.items()) {
        group.signals.push_back(item.string());
        group.signals_where.push_back(item.where() + ": " + item.path());
      }
      if (group.signals.empty()) signals.fail("at least one signal key or pattern");
      group.sources = source_list(g["sources"]);
      c.groups.push_back(std::move(group));
    }
  }
  return c;
}

}  // namespace facectl
