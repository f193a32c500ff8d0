#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "control/capacity.hpp"
#include "control/command/face_layout.hpp"
#include "firmware-host/config/expression_library.hpp"
#include "firmware-host/config/midi_config.hpp"

namespace facectl {

// The `midi:` map resolved against the head: signal indices and SI ranges,
// expressions as poses of the library (which must outlive it). Channels are
// 0-based here, as on the wire.
struct MidiFaceMap {
  struct Control {
    std::uint8_t channel = 0;
    std::uint8_t cc = 0;
    std::size_t signal = 0;
    double lo = 0.0;  // SI, at value 0
    double hi = 0.0;  // SI, at value 127
  };
  struct Note {
    std::uint8_t channel = 0;
    std::uint8_t note = 0;
    const FacePose* expression = nullptr;
  };
  std::vector<Control> controls;
  std::vector<Note> notes;
};

// ConfigError at the rule's line: a signal the head lacks, a range beyond
// the signal's domain, an expression the library lacks.
MidiFaceMap resolve_midi_map(const MidiConfig& config, const FaceLayout& layout,
                             const ExpressionLibrary& expressions);

// The face that MIDI holds: neutral, the expression of the last mapped note
// still down at its velocity's weight (legato: letting go of it falls back to
// the one pressed before, if still down), and every mapped controller's last
// value over it. Allocates nothing after construction.
class MidiFaceState {
 public:
  enum class Applied { kControl, kNoteOn, kNoteOff, kUnmapped };

  MidiFaceState(const MidiFaceMap& map, const std::array<double, kMaxFaceSignals>& neutral);

  Applied control(int channel, int cc, int value);       // channel 0..15, value 0..127
  Applied note_on(int channel, int note, int velocity);  // velocity 0 is a note off
  Applied note_off(int channel, int note);
  void reset();          // back to neutral: no note down, no controller moved
  void release_notes();  // no note down; controllers stay
  void pose(std::array<double, kMaxFaceSignals>& out) const;

 private:
  const MidiFaceMap& map_;
  const std::array<double, kMaxFaceSignals> neutral_;
  std::vector<double> control_values_;  // per map control, SI
  std::vector<bool> control_moved_;
  // Mapped notes down, oldest first: index into map_.notes and weight. The
  // oldest falls off when more are down than fit.
  struct Held {
    std::size_t note = 0;
    double weight = 0.0;
  };
  static constexpr std::size_t kMaxHeld = 16;
  std::array<Held, kMaxHeld> held_{};
  std::size_t held_count_ = 0;
  void let_go(std::size_t note);
};

}  // namespace facectl
