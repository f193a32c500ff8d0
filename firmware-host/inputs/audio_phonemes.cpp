#include "firmware-host/inputs/audio_phonemes.hpp"

#include <algorithm>
#include <cstdio>

#include "firmware-host/inputs/phone_visemes.hpp"
#include "firmware-host/inputs/phoneme_track_builder.hpp"
#include "firmware-host/inputs/speech_16k.hpp"

namespace facectl {
namespace {

constexpr double kSchwaSeconds = 0.06;

int viseme_of_recognized(const std::string& phone, double seconds) {
  if (phone.size() >= 2 && phone.front() == '+' && phone.back() == '+') return kVisemeNone;
  if (phone == "AH" && seconds < kSchwaSeconds) return viseme_of_phone("AH0");
  return viseme_of_phone(phone);
}

}  // namespace

PhonemeTrack audio_phoneme_track(const std::string& path, const PhoneModel& model) {
  Speech16k speech = read_speech_16k(path, kMaxPhonemeAudioSeconds);
  const std::vector<RecognizedPhone> phones = recognize_phones(speech.samples, model, path);
  speech.samples = {};  // freed before the poses are made

  PhonemeTrackBuilder b(path);
  for (const RecognizedPhone& p : phones) {
    const double start = p.first_frame / kPhoneFramesPerSecond;
    if (start >= speech.seconds) continue;  // the padding of the last partial frame
    const double end = std::min((p.last_frame + 1) / kPhoneFramesPerSecond, speech.seconds);
    const int viseme = viseme_of_recognized(p.phone, end - start);
    b.add(start, end, p.phone, viseme, 0);
  }
  if (b.last_end() == 0.0) b.add(0.0, speech.seconds, "SIL", kVisemeNone, 0);
  PhonemeTrack track = b.finish(speech.seconds);
  track.notes.insert(track.notes.begin(), speech.notes.begin(), speech.notes.end());
  // Counted from the track: the builder may drop a segment too short to keep.
  std::size_t pauses = 0;
  for (const auto& seg : track.segments) pauses += seg.viseme == kVisemeNone;
  char note[200];
  std::snprintf(note, sizeof note,
                "%zu phones recognised (and %zu pauses or noises) in %.1f s of audio at %d Hz by "
                "PocketSphinx allphone with %s",
                track.segments.size() - pauses, pauses, speech.seconds, speech.source_rate,
                model.acoustic_dir.c_str());
  track.notes.push_back(note);
  return track;
}

}  // namespace facectl
