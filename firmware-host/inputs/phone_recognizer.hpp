// Phones recognised in speech by PocketSphinx's allphone search: a phone
// loop weighted by a phone n-gram model, with no words and no dictionary
// (docs/INPUTS.md, "Phonemes from audio").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facectl {

// PocketSphinx's acoustic model and phone language model. The defaults are
// where Debian's pocketsphinx-en-us installs its US English models.
struct PhoneModel {
  std::string acoustic_dir;  // -hmm: mdef, means, variances, ...
  std::string phone_lm;      // -allphone: the phone n-gram model
  static PhoneModel debian_en_us();
};

// The recogniser's frames: 10 ms each (PocketSphinx's default -frate 100).
inline constexpr double kPhoneFramesPerSecond = 100.0;

struct RecognizedPhone {
  std::string phone;  // CMU phone AA..ZH, SIL, or a filler such as +NSN+ (noise)
  int first_frame = 0;
  int last_frame = 0;  // inclusive
};

// Decodes 16 kHz mono samples as one utterance. The settings are Rhubarb
// Lip Sync's for the same model: context-independent phones (-allphone_ci),
// wide beams (-beam, -pbeam 1e-20, as the CMU Sphinx phoneme-recognition
// notes advise), language weight 0.8 (lower flutters, higher freezes the
// mouth), dither with a fixed seed against digital silence (so the result
// is the same every run), no voice-activity cut (-remove_silence no: frame
// times stay those of the file), and batch cepstral mean normalisation over
// the whole file. PocketSphinx's log is silenced; its error messages go
// into the ConfigError. Throws ConfigError naming `audio_path` and the model
// file for a model that is missing (and the Debian package that installs
// it) or that PocketSphinx cannot load, and for a decoding failure.
// Serialised process-wide: PocketSphinx's log callback is global.
std::vector<RecognizedPhone> recognize_phones(const std::vector<std::int16_t>& samples_16k,
                                              const PhoneModel& model,
                                              const std::string& audio_path);

}  // namespace facectl
