#include "firmware-host/inputs/recorded_input.hpp"

#include <filesystem>

#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"
#include "firmware-host/fap/fap_show.hpp"
#include "firmware-host/fap/viseme_table.hpp"
#include "firmware-host/inputs/arkit_capture.hpp"
#include "firmware-host/inputs/audio_phonemes.hpp"
#include "firmware-host/inputs/coarticulation.hpp"
#include "firmware-host/inputs/input_limits.hpp"
#include "firmware-host/inputs/lip_sync_track.hpp"
#include "firmware-host/inputs/live_link_face_csv.hpp"
#include "firmware-host/inputs/mediapipe_blendshapes.hpp"
#include "firmware-host/inputs/openface_csv.hpp"
#include "firmware-host/inputs/phoneme_track.hpp"
#include "firmware-host/inputs/retarget_table.hpp"
#include "firmware-host/inputs/speech_envelope.hpp"
#include "firmware-host/inputs/text_lines.hpp"

namespace facectl {
namespace {

RecordedInput from_arkit(const LoadedConfig& cfg, const ArkitCapture& capture) {
  const RetargetTable table = RetargetTable::load(cfg.runtime.retarget_path, cfg.head);
  RecordedInput in;
  in.notes = capture.notes;
  in.track = arkit_pose_track(capture, table, cfg.head.layout, cfg.head.neutral, in.notes);
  return in;
}

RecordedInput from_phonemes(const LoadedConfig& cfg, const PhonemeTrack& phonemes,
                            const std::string& path) {
  if (phonemes.segments.empty()) {
    throw ConfigError(path + ": expected at least one phoneme or mouth shape, found none");
  }
  // Sampled every 10 ms into poses: the length bounds the memory.
  if (phonemes.duration_s > kMaxAudioSeconds) {
    throw ConfigError(path + ": expected lip sync of at most " +
                      std::to_string(static_cast<int>(kMaxAudioSeconds)) + " s, found " +
                      std::to_string(phonemes.duration_s) + " s");
  }
  const VisemeTable visemes = VisemeTable::load(cfg.runtime.visemes_path, cfg.head.layout);
  const VisemeTimeline timeline = VisemeTimeline::build(phonemes, CoarticulationParams{});
  RecordedInput in;
  in.notes = phonemes.notes;
  in.track = lip_sync_pose_track(timeline, visemes, cfg.head.layout, cfg.head.neutral);
  return in;
}

// `text` with each byte that is not part of valid UTF-8 replaced by '?'.
std::string valid_utf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = c < 0x80           ? 1
                          : (c >> 5) == 0x6  ? 2
                          : (c >> 4) == 0xE  ? 3
                          : (c >> 3) == 0x1E ? 4
                                             : 0;
    bool ok = n > 0 && i + n <= text.size();
    for (std::size_t k = 1; ok && k < n; ++k)
      ok = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (ok) {
      out.append(text, i, n);
      i += n;
    } else {
      out.push_back('?');
      ++i;
    }
  }
  return out;
}

}  // namespace

InputFormat resolve_input_format(const std::string& path, const std::string& text,
                                 std::optional<InputFormat> format) {
  if (format) return *format;
  if (auto f = detect_input_format(text)) return *f;
  throw ConfigError(path + ": expected a file in one of the formats " + input_format_names() +
                    " (docs/INPUTS.md), found none recognised; name it with --format");
}

RecordedInput load_recorded_input(const LoadedConfig& cfg, const std::string& path,
                                  std::optional<InputFormat> format) {
  const InputFormat f = resolve_input_format(path, read_file_head(path, kDetectBytes), format);
  RecordedInput in;
  if (f == InputFormat::kAudio) {
    in.track = speech_envelope_track(path, cfg.head.layout, cfg.head.neutral,
                                     SpeechEnvelopeParams{}, in.notes);
    in.name = std::filesystem::path(path).filename().string();
    in.format = f;
    return in;
  }
  if (f == InputFormat::kAudioPhonemes) {
    in = from_phonemes(cfg, audio_phoneme_track(path), path);
    in.name = std::filesystem::path(path).filename().string();
    in.format = f;
    return in;
  }
  const std::string text =
      read_input_file(path, f == InputFormat::kFap ? "FAP file" : "input file");
  switch (f) {
    case InputFormat::kAudio:  // read above: they are not text
    case InputFormat::kAudioPhonemes:
      break;
    case InputFormat::kShow:
      throw std::logic_error("load_recorded_input: a show is read by Show::load");
    case InputFormat::kFap: {
      const FapShow show =
          FapShow::build(parse_fap_text(text, path),
                         load_fap_mapping(cfg.head, cfg.expressions, cfg.runtime.visemes_path));
      in.name = show.name();  // the FAP header's name
      in.track = show.track();
      in.notes = show.report();
      break;
    }
    case InputFormat::kLiveLinkFaceCsv:
      in = from_arkit(cfg, parse_live_link_face_csv(text, path));
      break;
    case InputFormat::kMediapipeJson:
      in = from_arkit(cfg, parse_mediapipe_blendshapes(text, path));
      break;
    case InputFormat::kOpenFaceCsv: {
      const OpenFaceCapture capture = parse_openface_csv(text, path);
      const RetargetTable table = RetargetTable::load(cfg.runtime.retarget_path, cfg.head);
      in.notes = capture.notes;
      in.track = openface_pose_track(capture, table, cfg.head.layout, cfg.head.neutral, in.notes);
      break;
    }
    case InputFormat::kRhubarbJson:
      in = from_phonemes(cfg, parse_rhubarb_json(text, path), path);
      break;
    case InputFormat::kRhubarbTsv:
      in = from_phonemes(cfg, parse_rhubarb_tsv(text, path), path);
      break;
    case InputFormat::kTextGrid:
      in = from_phonemes(cfg, parse_textgrid(text, path, ""), path);
      break;
  }
  if (in.name.empty()) in.name = std::filesystem::path(path).filename().string();
  // Notes quote the file; they go into summary.json, which must be valid UTF-8.
  for (std::string& note : in.notes) note = valid_utf8(note);
  in.format = f;
  return in;
}

}  // namespace facectl
