#include "firmware-host/inputs/midi_face.hpp"

#include <algorithm>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

MidiFaceMap resolve_midi_map(const MidiConfig& config, const FaceLayout& layout,
                             const ExpressionLibrary& expressions) {
  MidiFaceMap map;
  for (const MidiControlRule& r : config.controls) {
    const auto i = layout.find_yaml_key(r.signal);
    if (!i) {
      throw ConfigError(r.where +
                        ".signal: expected a signal key of the head (jaw_pitch_deg, "
                        "zygomaticus_major_l), found '" +
                        r.signal + "'");
    }
    const SignalInfo& s = layout.signal(*i);
    const double k = yaml_to_si(s.kind);
    for (const double v : {r.min, r.max}) {
      if (v * k < s.domain_min - 1e-12 || v * k > s.domain_max + 1e-12) {
        throw ConfigError(r.where + ": expected min and max within " + r.signal + "'s domain " +
                          std::to_string(s.domain_min / k) + ".." +
                          std::to_string(s.domain_max / k) + ", found " + std::to_string(v));
      }
    }
    map.controls.push_back({static_cast<std::uint8_t>(r.channel - 1),
                            static_cast<std::uint8_t>(r.cc), *i, r.min * k, r.max * k});
  }
  for (const MidiNoteRule& r : config.notes) {
    const FacePose* pose = expressions.find(r.expression);
    if (pose == nullptr) {
      throw ConfigError(r.where + ".expression: expected an expression of the library, found '" +
                        r.expression + "'");
    }
    map.notes.push_back(
        {static_cast<std::uint8_t>(r.channel - 1), static_cast<std::uint8_t>(r.note), pose});
  }
  return map;
}

MidiFaceState::MidiFaceState(const MidiFaceMap& map,
                             const std::array<double, kMaxFaceSignals>& neutral)
    : map_(map),
      neutral_(neutral),
      control_values_(map.controls.size(), 0.0),
      control_moved_(map.controls.size(), false) {}

MidiFaceState::Applied MidiFaceState::control(int channel, int cc, int value) {
  Applied applied = Applied::kUnmapped;
  for (std::size_t i = 0; i < map_.controls.size(); ++i) {
    const MidiFaceMap::Control& c = map_.controls[i];
    if (c.channel != channel || c.cc != cc) continue;
    const double t = std::clamp(value, 0, 127) / 127.0;
    control_values_[i] = c.lo + t * (c.hi - c.lo);
    control_moved_[i] = true;
    applied = Applied::kControl;
  }
  return applied;
}

MidiFaceState::Applied MidiFaceState::note_on(int channel, int note, int velocity) {
  if (velocity == 0) return note_off(channel, note);
  for (std::size_t i = 0; i < map_.notes.size(); ++i) {
    if (map_.notes[i].channel == channel && map_.notes[i].note == note) {
      let_go(i);  // pressed again: it moves to the top
      if (held_count_ == kMaxHeld) let_go(held_[0].note);
      held_[held_count_++] = {i, std::clamp(velocity, 1, 127) / 127.0};
      return Applied::kNoteOn;
    }
  }
  return Applied::kUnmapped;
}

MidiFaceState::Applied MidiFaceState::note_off(int channel, int note) {
  for (std::size_t i = 0; i < map_.notes.size(); ++i) {
    if (map_.notes[i].channel == channel && map_.notes[i].note == note) {
      let_go(i);
      return Applied::kNoteOff;
    }
  }
  return Applied::kUnmapped;
}

void MidiFaceState::let_go(std::size_t note) {
  const auto end = held_.begin() + static_cast<std::ptrdiff_t>(held_count_);
  const auto at =
      std::find_if(held_.begin(), end, [note](const Held& h) { return h.note == note; });
  if (at == end) return;
  std::copy(at + 1, end, at);
  --held_count_;
}

void MidiFaceState::release_notes() {
  held_count_ = 0;
}

void MidiFaceState::reset() {
  held_count_ = 0;
  std::fill(control_moved_.begin(), control_moved_.end(), false);
}

void MidiFaceState::pose(std::array<double, kMaxFaceSignals>& out) const {
  out = neutral_;
  if (held_count_ > 0) {
    const Held& top = held_[held_count_ - 1];
    map_.notes[top.note].expression->blend_into(out, top.weight);
  }
  for (std::size_t i = 0; i < map_.controls.size(); ++i) {
    if (control_moved_[i]) out[map_.controls[i].signal] = control_values_[i];
  }
}

}  // namespace facectl
