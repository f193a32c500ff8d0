#pragma once

#include <string>
#include <vector>

#include "control/command/face_layout.hpp"
#include "firmware-host/inputs/pose_track.hpp"

namespace facectl {

// A speech-driven jaw for heads without phoneme timing: the jaw opens with
// the loudness of the voice in an audio file (WAV, or any format libsndfile
// reads). Loudness is the RMS of 20 ms windows every 10 ms, in dB; the
// file's own 10th and 95th percentiles (its pauses and its loud vowels) map
// to closed and `open_deg`, so the recording level does not matter. The
// opening follows rises in `attack_s` and falls in `release_s` (the jaw
// closes more slowly than it opens; both one-pole), and leads the sound by
// `lead_s` (the jaw moves before the sound it shapes is heard).
struct SpeechEnvelopeParams {
  double open_deg = 12.0;  // jaw pitch at the loud end (the envelope still applies)
  double range_db = 30.0;  // at most this far below the loud end counts as voice
  double attack_s = 0.015;
  double release_s = 0.06;
  double lead_s = 0.0;
  double rate_hz = 100.0;  // poses per second
};

// Throws ConfigError naming the file for a file libsndfile cannot read, no
// samples, a sample rate outside 1..768 kHz, or more than kMaxAudioSeconds.
// Samples that are not finite or beyond full scale (a float file can hold
// them) are clamped (NaN as silence) and counted in the notes.
PoseTrack speech_envelope_track(const std::string& path, const FaceLayout& layout,
                                const std::array<double, kMaxFaceSignals>& neutral,
                                const SpeechEnvelopeParams& params,
                                std::vector<std::string>& notes);

// The openness 0..1 at each step of 1/rate_hz, from mono samples; what
// speech_envelope_track turns into jaw pitch (exposed for tests).
std::vector<double> speech_openness(const std::vector<float>& mono, double sample_rate,
                                    const SpeechEnvelopeParams& params);

}  // namespace facectl
