// Phoneme timing from speech audio, for heads lip-synced from a WAV alone:
// the phones PocketSphinx recognises (phone_recognizer.hpp) as a phoneme
// track, which the same coarticulation as a TextGrid's turns into visemes
// (docs/INPUTS.md, "Phonemes from audio").
#pragma once

#include <string>

#include "firmware-host/inputs/phone_recognizer.hpp"
#include "firmware-host/inputs/phoneme_track.hpp"

namespace facectl {

// Phoneme recognition holds the file's 16 kHz samples and decodes them as
// one utterance, about 0.07 s a second of speech here: 30 minutes at most.
inline constexpr double kMaxPhonemeAudioSeconds = 30 * 60.0;

// The phones recognised in the audio file `path`, each a segment labelled
// with its CMU phone (AA..ZH) and its viseme as viseme_of_phone reads
// ARPAbet; SIL and fillers (+NSN+ noise, +SPN+ other speech, any "+...+")
// are rest, viseme 0. An AH shorter than 60 ms is read as a schwa (AH0: the
// e viseme), as Rhubarb Lip Sync does, since the model has no schwa of its
// own. The track lasts the whole file, so a silent file gives one rest
// segment. Notes say what was recognised, and any clamping or resampling.
// Throws ConfigError naming the file (read_speech_16k, recognize_phones).
PhonemeTrack audio_phoneme_track(const std::string& path,
                                 const PhoneModel& model = PhoneModel::debian_en_us());

}  // namespace facectl
