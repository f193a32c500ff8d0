#include "firmware-host/inputs/show_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace facectl {

namespace {
constexpr double kMaxSpanS = 1.0;
}  // namespace

ShowRecorder::ShowRecorder(const FaceLayout& layout,
                           const std::array<double, kMaxFaceSignals>& neutral)
    : layout_(layout), neutral_(neutral) {
  for (std::size_t i = 0; i < layout_.size(); ++i) {
    switch (layout_.signal(i).kind) {
      case SignalKind::kAngle:
        tolerance_[i] = 1e-4;  // rad, 0.006 degree
        break;
      case SignalKind::kLength:
        tolerance_[i] = 1e-5;  // m
        break;
      default:
        tolerance_[i] = 1e-3;
        break;
    }
  }
}

// True when the segment a -> c reproduces every sample of the window.
bool ShowRecorder::reproduces(const Frame& a, const Frame& c) const {
  if (c.t - a.t > kMaxSpanS) return false;
  for (const Frame& p : window_) {
    const double w = (p.t - a.t) / (c.t - a.t);
    for (std::size_t i = 0; i < layout_.size(); ++i) {
      const double v = a.values[i] + w * (c.values[i] - a.values[i]);
      if (std::fabs(v - p.values[i]) > tolerance_[i]) return false;
    }
  }
  return true;
}

void ShowRecorder::add(double t_s, const std::array<double, kMaxFaceSignals>& pose) {
  Frame f{t_s, pose};
  for (std::size_t i = 0; i < layout_.size(); ++i) {
    const SignalInfo& s = layout_.signal(i);
    f.values[i] = std::clamp(f.values[i], s.domain_min, s.domain_max);
  }
  if (frames_.empty()) {
    frames_.push_back(f);
    return;
  }
  const double last_t = window_.empty() ? frames_.back().t : window_.back().t;
  if (t_s - last_t < 1e-3) return;
  if (!window_.empty() && !reproduces(frames_.back(), f)) {
    frames_.push_back(window_.back());  // the tentative end becomes a keyframe
    window_.clear();
  }
  window_.push_back(f);
}

std::string ShowRecorder::to_yaml(const std::string& name) const {
  std::vector<Frame> all = frames_;
  if (!window_.empty()) all.push_back(window_.back());
  std::string out =
      "# Recorded by facectl run --record-show: one keyframe per change, in the\n"
      "# signals' YAML units; signals not listed are at the neutral pose.\n"
      "show:\n  name: " +
      name + "\n  keyframes:\n";
  char buf[96];
  const double t0 = all.empty() ? 0.0 : all.front().t;
  for (const Frame& f : all) {
    std::snprintf(buf, sizeof buf, "    - { t: %.4f, ease: linear", f.t - t0);
    out += buf;
    std::string muscles, mandible, rigid;
    for (std::size_t i = 0; i < layout_.size(); ++i) {
      if (f.values[i] == neutral_[i]) continue;
      const SignalInfo& s = layout_.signal(i);
      std::snprintf(buf, sizeof buf, "%.9g", f.values[i] / yaml_to_si(s.kind));
      std::string& group = i < layout_.muscle_count()      ? muscles
                           : i <= layout_.jaw_protrusion() ? mandible
                                                           : rigid;
      std::string key = i < layout_.muscle_count() ? s.name : yaml_key(s);
      if (i == layout_.jaw_pitch()) key = "pitch_deg";
      if (i == layout_.jaw_yaw()) key = "yaw_deg";
      if (i == layout_.jaw_protrusion()) key = "protrusion_mm";
      group += (group.empty() ? "" : ", ") + key + ": " + buf;
    }
    if (!muscles.empty()) out += ", muscles: { " + muscles + " }";
    if (!mandible.empty()) out += ", mandible: { " + mandible + " }";
    if (!rigid.empty()) out += ", rigid: { " + rigid + " }";
    out += " }\n";
  }
  return out;
}

void ShowRecorder::write(const std::string& path, const std::string& name) const {
  std::ofstream out(path);
  out << to_yaml(name);
  if (!out) throw std::runtime_error(path + ": cannot write the recorded show");
}

}  // namespace facectl
