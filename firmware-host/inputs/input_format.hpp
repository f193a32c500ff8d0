#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace facectl {

// The recorded inputs `--input FILE` plays (docs/INPUTS.md).
enum class InputFormat {
  kShow,             // facectl show YAML
  kFap,              // MPEG-4 FAP ASCII
  kLiveLinkFaceCsv,  // Epic's Live Link Face CSV (ARKit blendshapes)
  kMediapipeJson,    // MediaPipe face landmarker blendshapes, saved as JSON
  kOpenFaceCsv,      // OpenFace 2.x FeatureExtraction CSV (action units)
  kRhubarbJson,      // Rhubarb Lip Sync mouth cues, JSON export
  kRhubarbTsv,       // Rhubarb Lip Sync mouth cues, TSV export
  kTextGrid,         // Praat TextGrid with a phones tier (Montreal Forced Aligner)
  kAudio,            // speech audio (WAV, FLAC, Ogg): a jaw from its loudness
  kAudioPhonemes,    // speech audio: lip sync from the phones PocketSphinx hears
};

// The --format names: show, fap, live_link_face, mediapipe, openface, rhubarb_json,
// rhubarb_tsv, textgrid, audio, audio_phonemes. Detection gives audio for
// audio files: phoneme recognition is asked for by name.
std::optional<InputFormat> parse_input_format(std::string_view name);
const char* input_format_name(InputFormat format);
// Every --format name, for messages.
std::string input_format_names();

// How many bytes of a file detection looks at.
inline constexpr std::size_t kDetectBytes = 4096;

// The format of a file from its first bytes; nullopt when none matches.
std::optional<InputFormat> detect_input_format(std::string_view text);

}  // namespace facectl
