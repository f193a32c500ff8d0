#include "firmware-host/config/head_config.hpp"

#include <numbers>
#include <set>

#include "control/units.hpp"
#include "firmware-host/config/face_pose.hpp"

namespace facectl {
namespace {

Range parse_range(const ConfigNode& node, double scale) {
  node.expect_keys({"min", "max"});
  const double lo = node["min"].number();
  const double hi = node["max"].number();
  if (!(lo <= hi))
    node.fail("min <= max", "min " + std::to_string(lo) + " > max " + std::to_string(hi));
  return {lo * scale, hi * scale};
}

}  // namespace

EnvelopeSpec parse_envelope(const ConfigNode& node) {
  node.expect_keys({"pitch_deg", "yaw_deg", "protrusion_mm", "widen_override"});
  EnvelopeSpec spec;
  spec.where = node.where();
  if (auto n = node.get("widen_override")) spec.widen_override = n->boolean();
  const MandibleEnvelope design = MandibleEnvelope::design_default();
  auto axis = [&](const char* key, double scale, const Range& limit, const char* text) {
    std::optional<Range> r;
    if (auto n = node.get(key)) {
      r = parse_range(*n, scale);
      if (!limit.contains(*r) && !spec.widen_override) {
        n->fail(std::string("a range inside the design envelope ") + text +
                    " (widening needs `widen_override: true`)",
                "[" + std::to_string(r->min / scale) + ", " + std::to_string(r->max / scale) + "]");
      }
    }
    return r;
  };
  spec.pitch = axis("pitch_deg", kDeg, design.pitch, "-4..18 deg");
  spec.yaw = axis("yaw_deg", kDeg, design.yaw, "-5..5 deg");
  spec.protrusion = axis("protrusion_mm", 1e-3, design.protrusion, "0..8 mm");
  return spec;
}

HeadConfig load_head_config(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"head"});
  const ConfigNode head = root["head"];
  head.expect_keys({"name", "muscles", "passive_muscles", "rigid", "mandible_envelope", "neutral",
                    "antagonists"});

  HeadConfig cfg;
  cfg.file = path;
  cfg.name = head["name"].string();
  std::set<std::string> seen;
  for (const ConfigNode& m : head["muscles"].items()) {
    std::string name;
    std::vector<int> aus;
    if (m.is_map()) {
      m.expect_keys({"name", "facs"});
      name = m["name"].string();
      if (auto facs = m.get("facs")) {
        for (const auto& au : facs->items()) {
          const long n = au.integer();
          if (n < 1 || n > 99) au.fail("a FACS action unit number 1..99", std::to_string(n));
          aus.push_back(static_cast<int>(n));
        }
      }
    } else {
      name = m.string();
    }
    if (name.empty()) m.fail("a muscle name", "an empty name");
    if (!seen.insert(name).second) m.fail("a unique muscle name", "duplicate '" + name + "'");
    cfg.muscles.push_back(name);
    cfg.muscle_facs.push_back(std::move(aus));
    cfg.muscle_where.push_back(m.where());
  }
  if (cfg.muscles.empty()) head["muscles"].fail("at least one muscle", "an empty list");
  if (auto p = head.get("passive_muscles")) cfg.passive_muscles = p->string_list();

  if (auto rigid = head.get("rigid")) {
    // Each range applies to both sides where the signal has them.
    const std::vector<std::pair<std::string, std::vector<std::string>>> known = {
        {"eye_yaw_deg", {"eye_yaw_l", "eye_yaw_r"}},
        {"eye_pitch_deg", {"eye_pitch_l", "eye_pitch_r"}},
        {"eyelid_closure", {"eyelid_closure_l", "eyelid_closure_r"}},
        {"neck_pan_deg", {"neck_pan"}},
        {"neck_tilt_deg", {"neck_tilt"}},
        {"neck_roll_deg", {"neck_roll"}},
    };
    std::vector<std::string> allowed;
    allowed.reserve(known.size());
    for (const auto& k : known) allowed.push_back(k.first);
    rigid->expect_keys(allowed);
    for (const auto& [key, signals] : known) {
      if (auto n = rigid->get(key)) {
        const double scale = key.ends_with("_deg") ? kDeg : 1.0;
        const Range r = parse_range(*n, scale);
        const FaceLayout rigid_layout({});
        for (const auto& s : signals) {
          const SignalInfo& info = rigid_layout.signal(*rigid_layout.find(s));
          if (r.min < info.domain_min || r.max > info.domain_max) {
            n->fail("a range inside the signal's domain [" +
                    std::to_string(info.domain_min / scale) + ", " +
                    std::to_string(info.domain_max / scale) + "]");
          }
          cfg.rigid_ranges[s] = r;
        }
      }
    }
  }
  if (auto env = head.get("mandible_envelope")) cfg.envelope = parse_envelope(*env);
  cfg.layout = FaceLayout(cfg.muscles);
  cfg.neutral_where = head.where();
  if (auto neutral = head.get("neutral")) {
    parse_pose(*neutral, cfg.layout).apply_to(cfg.neutral);
    cfg.neutral_where = neutral->where();
  }
  if (auto pairs = head.get("antagonists")) {
    for (const ConfigNode& p : pairs->items()) {
      p.expect_keys({"muscles", "max_sum"});
      const auto names = p["muscles"].items();
      if (names.size() != 2) p["muscles"].fail("two muscle names", std::to_string(names.size()));
      AntagonistPair pair;
      pair.where = p.where();
      std::size_t* slots[2] = {&pair.a, &pair.b};
      for (std::size_t k = 0; k < 2; ++k) {
        const auto index = cfg.layout.find(names[k].string());
        if (!index || *index >= cfg.layout.muscle_count()) names[k].fail("a muscle of this head");
        *slots[k] = *index;
      }
      if (auto m = p.get("max_sum")) pair.max_sum = m->number_in(0.0, 2.0);
      cfg.antagonists.push_back(pair);
    }
  }
  return cfg;
}

}  // namespace facectl
