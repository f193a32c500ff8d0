// Other tools' recordings (docs/INPUTS.md): format detection, then the parser
// of the detected format, or with an unrecognised input the one its first
// byte picks, so that every parser sees every shape. The only allowed failure
// is ConfigError (file:line: expected ..., found ...).
#include <cstdint>
#include <cstdlib>

#include "firmware-host/config/config_node.hpp"
#include "firmware-host/inputs/input_format.hpp"
#include "firmware-host/inputs/live_link_face_csv.hpp"
#include "firmware-host/inputs/mediapipe_blendshapes.hpp"
#include "firmware-host/inputs/openface_csv.hpp"
#include "firmware-host/inputs/phoneme_track.hpp"

namespace {

using facectl::InputFormat;

// What the pose tracks built from a capture need: times from 0, increasing.
template <typename Frames>
void check_times(const Frames& frames) {
  double prev = -1;
  for (const auto& f : frames) {
    if (!(f.t > prev) || !(f.t >= 0)) std::abort();
    prev = f.t;
  }
}

void parse(InputFormat f, std::string_view text) {
  switch (f) {
    case InputFormat::kLiveLinkFaceCsv:
      check_times(facectl::parse_live_link_face_csv(text, "fuzz.csv").frames);
      break;
    case InputFormat::kMediapipeJson:
      check_times(facectl::parse_mediapipe_blendshapes(text, "fuzz.json").frames);
      break;
    case InputFormat::kOpenFaceCsv:
      check_times(facectl::parse_openface_csv(text, "fuzz.csv").frames);
      break;
    case InputFormat::kRhubarbJson:
      facectl::parse_rhubarb_json(text, "fuzz.json");
      break;
    case InputFormat::kRhubarbTsv:
      facectl::parse_rhubarb_tsv(text, "fuzz.tsv");
      break;
    case InputFormat::kTextGrid:
      facectl::parse_textgrid(text, "fuzz.TextGrid", "");
      break;
    default:  // shows, FAP files and audio have their own targets and readers
      break;
  }
}

constexpr InputFormat kParsers[] = {InputFormat::kLiveLinkFaceCsv, InputFormat::kMediapipeJson,
                                    InputFormat::kOpenFaceCsv,     InputFormat::kRhubarbJson,
                                    InputFormat::kRhubarbTsv,      InputFormat::kTextGrid};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const auto detected = facectl::detect_input_format(text);
  const InputFormat f = detected ? *detected : kParsers[size == 0 ? 0 : data[0] % 6];
  try {
    parse(f, text);
  } catch (const facectl::ConfigError&) {
    return 0;
  }
  return 0;
}
