#include "firmware-host/inputs/recorded_input.hpp"

#include <filesystem>

#include "firmware-host/fap/fap_file.hpp"
#include "firmware-host/fap/fap_mapping.hpp"
#include "firmware-host/fap/fap_show.hpp"
#include "firmware-host/fap/viseme_table.hpp"
#include "firmware-host/inputs/arkit_capture.hpp"
#include "firmware-host/inputs/coarticulation.hpp"
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

RecordedInput from_phonemes(const LoadedConfig& cfg, const PhonemeTrack& phonemes) {
  if (phonemes.segments.empty()) throw ConfigError("expected at least one phoneme, found none");
  const VisemeTable visemes = VisemeTable::load(cfg.runtime.visemes_path, cfg.head.layout);
  const VisemeTimeline timeline = VisemeTimeline::build(phonemes, CoarticulationParams{});
  RecordedInput in;
  in.notes = phonemes.notes;
  in.track = lip_sync_pose_track(timeline, visemes, cfg.head.layout, cfg.head.neutral);
  return in;
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
  const std::string text =
      read_input_file(path, f == InputFormat::kFap ? "FAP file" : "input file");
  switch (f) {
    case InputFormat::kAudio:  // read above: it is not text
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
      in = from_phonemes(cfg, parse_rhubarb_json(text, path));
      break;
    case InputFormat::kRhubarbTsv:
      in = from_phonemes(cfg, parse_rhubarb_tsv(text, path));
      break;
    case InputFormat::kTextGrid:
      in = from_phonemes(cfg, parse_textgrid(text, path, ""));
      break;
  }
  if (in.name.empty()) in.name = std::filesystem::path(path).filename().string();
  in.format = f;
  return in;
}

}  // namespace facectl
