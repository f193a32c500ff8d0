#include "firmware-host/inputs/phone_recognizer.hpp"

#include <pocketsphinx.h>
#include <sphinxbase/err.h>

#include <array>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include "firmware-host/config/config_node.hpp"

#ifndef FACECTL_POCKETSPHINX_MODELDIR
#define FACECTL_POCKETSPHINX_MODELDIR "/usr/share/pocketsphinx/model"
#endif

namespace facectl {
namespace {

constexpr const char* kPackage = "Debian's pocketsphinx-en-us (scripts/setup.sh installs it)";

// PocketSphinx's error messages during one decode; the rest of its log
// (several hundred lines of INFO per model load) is dropped.
std::string g_errors;

// A fatal error: PocketSphinx would call exit() after logging it (a damaged
// model file does that), so the log callback throws this instead. Debian
// builds sphinxbase and pocketsphinx with unwind tables (every function has
// an .eh_frame entry), so it unwinds through their C frames; what they had
// allocated leaks, once, on the way to an error that ends the command.
struct PocketSphinxFatal {
  std::string message;
};

void collect_errors(void* /*user*/, err_lvl_t level, const char* fmt, ...) {
  if (level < ERR_ERROR) return;
  std::array<char, 512> buf{};
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf.data(), buf.size(), fmt, ap);
  va_end(ap);
  std::string msg(buf.data());
  while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
  if (level == ERR_FATAL) throw PocketSphinxFatal{msg};
  if (!msg.empty()) g_errors += (g_errors.empty() ? "" : "; ") + msg;
}

// Routes PocketSphinx's log into collect_errors while it lives.
class QuietLog {
 public:
  QuietLog() {
    g_errors.clear();
    // No log file first (the settings table is written to it directly), then
    // the callback; setting the file later is ignored once a callback is set.
    err_set_logfp(nullptr);
    err_set_callback(collect_errors, nullptr);
  }
  ~QuietLog() {
    err_set_callback(collect_errors, nullptr);  // stays quiet between decodes
  }
  QuietLog(const QuietLog&) = delete;
  QuietLog& operator=(const QuietLog&) = delete;
  static bool any() { return !g_errors.empty(); }
  static std::string said() { return g_errors.empty() ? "no message" : g_errors; }
};

void check_model(const PhoneModel& model, const std::string& audio_path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto missing = [&](const std::string& what, const std::string& path) {
    throw ConfigError(audio_path + ": phoneme recognition needs PocketSphinx's " + what + " " +
                      path + ", found nothing there; install " + kPackage);
  };
  if (!fs::is_directory(model.acoustic_dir, ec)) missing("acoustic model", model.acoustic_dir);
  for (const char* f : {"mdef", "means", "variances", "transition_matrices", "noisedict"}) {
    const fs::path p = fs::path(model.acoustic_dir) / f;
    if (!fs::is_regular_file(p, ec)) missing("acoustic model file", p.string());
  }
  const fs::path dir(model.acoustic_dir);
  if (!fs::is_regular_file(dir / "sendump", ec) &&
      !fs::is_regular_file(dir / "mixture_weights", ec)) {
    missing("acoustic model file", (dir / "sendump").string());
  }
  if (!fs::is_regular_file(model.phone_lm, ec)) missing("phone language model", model.phone_lm);
}

}  // namespace

PhoneModel PhoneModel::debian_en_us() {
  const std::string dir = FACECTL_POCKETSPHINX_MODELDIR "/en-us";
  return {dir + "/en-us", dir + "/en-us-phone.lm.bin"};
}

std::vector<RecognizedPhone> recognize_phones(const std::vector<std::int16_t>& samples_16k,
                                              const PhoneModel& model,
                                              const std::string& audio_path) {
  check_model(model, audio_path);
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  const QuietLog quiet;
  const std::string where = audio_path + ": phoneme recognition with " + model.acoustic_dir +
                            " and " + model.phone_lm + ": ";

  std::vector<RecognizedPhone> phones;
  try {
    const std::unique_ptr<cmd_ln_t, int (*)(cmd_ln_t*)> config(
        cmd_ln_init(nullptr, ps_args(), TRUE,                  //
                    "-hmm", model.acoustic_dir.c_str(),        //
                    "-allphone", model.phone_lm.c_str(),       //
                    "-allphone_ci", "yes",                     //
                    "-lw", "0.8",                              //
                    "-beam", "1e-20", "-pbeam", "1e-20",       //
                    "-dither", "yes", "-seed", "1",            //
                    "-remove_silence", "no", "-cmn", "batch",  //
                    static_cast<const char*>(nullptr)),
        cmd_ln_free_r);
    if (!config) throw ConfigError(where + "the settings were refused: " + QuietLog::said());
    const std::unique_ptr<ps_decoder_t, int (*)(ps_decoder_t*)> ps(ps_init(config.get()), ps_free);
    // An error while loading is a failure even where PocketSphinx carries on:
    // a phone model it cannot read leaves an unweighted phone loop.
    if (!ps || QuietLog::any())
      throw ConfigError(where + "the model did not load: " + QuietLog::said());

    if (ps_start_utt(ps.get()) < 0) throw ConfigError(where + "starting: " + QuietLog::said());
    // One call with the whole file: full_utt lets batch CMN see all of it.
    if (!samples_16k.empty() &&
        ps_process_raw(ps.get(), samples_16k.data(), samples_16k.size(), FALSE, TRUE) < 0) {
      throw ConfigError(where + "decoding: " + QuietLog::said());
    }
    if (ps_end_utt(ps.get()) < 0) throw ConfigError(where + "ending: " + QuietLog::said());
    for (ps_seg_t* seg = ps_seg_iter(ps.get()); seg != nullptr; seg = ps_seg_next(seg)) {
      RecognizedPhone p;
      p.phone = ps_seg_word(seg);
      ps_seg_frames(seg, &p.first_frame, &p.last_frame);
      phones.push_back(std::move(p));
    }
  } catch (const PocketSphinxFatal& e) {
    throw ConfigError(where + "PocketSphinx stopped: " + e.message +
                      "; is the model damaged? Reinstall " + kPackage);
  }
  return phones;
}

}  // namespace facectl
