#include "firmware-host/inputs/show.hpp"

#include <algorithm>

#include "firmware-host/inputs/input_limits.hpp"

namespace facectl {

double ease(Ease curve, double u) {
  u = std::clamp(u, 0.0, 1.0);
  switch (curve) {
    case Ease::kLinear:
      return u;
    case Ease::kEaseIn:
      return u * u * u;
    case Ease::kEaseOut:
      return 1.0 - (1.0 - u) * (1.0 - u) * (1.0 - u);
    case Ease::kEaseInOut:
      return u < 0.5 ? 4.0 * u * u * u : 1.0 - 4.0 * (1.0 - u) * (1.0 - u) * (1.0 - u);
    case Ease::kStep:
      return u < 1.0 ? 0.0 : 1.0;
  }
  return u;
}

namespace {

Ease parse_ease(const ConfigNode& node) {
  const std::string s = node.string();
  if (s == "linear") return Ease::kLinear;
  if (s == "ease_in") return Ease::kEaseIn;
  if (s == "ease_out") return Ease::kEaseOut;
  if (s == "ease_in_out") return Ease::kEaseInOut;
  if (s == "step") return Ease::kStep;
  node.fail("one of: linear, ease_in, ease_out, ease_in_out, step");
}

}  // namespace

Show Show::load(const std::string& path, const FaceLayout& layout,
                const std::array<double, kMaxFaceSignals>& neutral,
                const ExpressionLibrary& expressions) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"show"});
  const ConfigNode show = root["show"];
  show.expect_keys({"name", "keyframes"});
  Show out;
  out.name_ = show["name"].string();
  out.signal_count_ = layout.size();
  for (const ConfigNode& k : show["keyframes"].items()) {
    Keyframe kf;
    kf.t = k["t"].number_in(0.0, kMaxShowSeconds);
    if (!out.keyframes_.empty() && kf.t <= out.keyframes_.back().t) {
      k["t"].fail("a time after the previous keyframe's " +
                  std::to_string(out.keyframes_.back().t) + " s");
    }
    if (auto e = k.get("ease")) kf.ease = parse_ease(*e);
    kf.values = neutral;
    const FacePose pose = parse_pose(k, layout, {"t", "ease", "expression", "weight"});
    if (auto name = k.get("expression")) {
      const FacePose* expr = expressions.find(name->string());
      if (expr == nullptr) name->fail("an expression of the library", "'" + name->string() + "'");
      const double weight = k.get("weight") ? k["weight"].number_in(0.0, 1.0) : 1.0;
      expr->blend_into(kf.values, weight);
    } else if (k.has("weight")) {
      k["weight"].fail("weight only together with an expression", "a weight without one");
    }
    pose.apply_to(kf.values);
    out.keyframes_.push_back(kf);
  }
  if (out.keyframes_.empty()) show["keyframes"].fail("at least one keyframe", "an empty list");
  return out;
}

void Show::evaluate(double t, std::array<double, kMaxFaceSignals>& out) const {
  if (t <= keyframes_.front().t) {
    out = keyframes_.front().values;
    return;
  }
  if (t >= keyframes_.back().t) {
    out = keyframes_.back().values;
    return;
  }
  const auto next = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                     [](double v, const Keyframe& k) { return v < k.t; });
  const Keyframe& b = *next;
  const Keyframe& a = *(next - 1);
  const double w = ease(b.ease, (t - a.t) / (b.t - a.t));
  for (std::size_t i = 0; i < signal_count_; ++i)
    out[i] = a.values[i] + w * (b.values[i] - a.values[i]);
}

}  // namespace facectl
