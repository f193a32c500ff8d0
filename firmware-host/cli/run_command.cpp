#include "firmware-host/cli/run_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "control/controller.hpp"
#include "control/realtime/loop_timer.hpp"
#include "drivers/hid/hid_gamepad.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/fap/fap_udp_stream.hpp"
#include "firmware-host/inputs/audio_playback.hpp"
#include "firmware-host/inputs/gamepad_puppeteer.hpp"
#include "firmware-host/inputs/input_mix.hpp"
#include "firmware-host/inputs/live_link_face_stream.hpp"
#include "firmware-host/inputs/midi_input.hpp"
#include "firmware-host/inputs/recorded_input.hpp"
#include "firmware-host/inputs/retarget_table.hpp"
#include "firmware-host/inputs/show_player.hpp"
#include "firmware-host/inputs/text_lines.hpp"
#include "firmware-host/run/fault_injection.hpp"
#include "firmware-host/run/head_runtime.hpp"
#include "firmware-host/run/run_summary.hpp"
#include "firmware-host/run/status_line.hpp"

namespace facectl {
namespace {

std::atomic<int> g_signal{0};
std::atomic<int> g_signal_count{0};
extern "C" void on_signal(int sig) {
  g_signal.store(sig);
  g_signal_count.fetch_add(1);
}

// How long the loop keeps ticking (and recording) after FAULT or ESTOP.
constexpr double kFaultLingerSeconds = 0.5;

// Everything one run owns: the head, then its inputs. Members are destroyed
// in reverse, so each input thread stops before the mailbox it feeds.
struct RunSession {
  std::vector<Injection> injections;
  HeadRuntime head;
  std::optional<RecordedInput> input;       // --input, when it is not a show
  std::optional<Show> input_show;           // --input, when it is
  std::unique_ptr<ShowRecorder> recorder;   // before its writers: they stop first
  std::optional<InputMixPlan> mix_plan;     // several sources at once (mix:)
  std::unique_ptr<InputMixer> mixer;        // before the sources that publish into it
  std::unique_ptr<FapMapping> fap_mapping;  // --fap-stream: outlives the stream
  std::unique_ptr<FapUdpStream> fap_stream;
  std::unique_ptr<RetargetTable> retarget;  // --live-link-face: outlives the stream
  std::unique_ptr<LiveLinkFaceStream> live_link_face;
  std::unique_ptr<MidiFaceMap> midi_map;  // --midi: outlives the input
  std::unique_ptr<MidiInput> midi;
  std::unique_ptr<AudioPlayback> audio;    // --audio: outlives the player that follows it
  std::unique_ptr<ShowPlayer> player;      // --input's, else the show's
  std::unique_ptr<ShowPlayer> mixed_show;  // the show, when mixed with --input
  std::unique_ptr<HidGamepad> pad;
  std::unique_ptr<GamepadPuppeteer> puppeteer;
  double end_s = 1e300;
  bool live = false;  // a gamepad or a stream: the run lasts until a signal or --duration
  std::function<void()> silence_input;  // --inject input_loss: what feeds the tick goes quiet

  const ControllerModel& model() const { return head.model(); }
};

// The sources the options name, as the mix: block names them.
std::vector<MixSource> run_sources(const RunOptions& options) {
  std::vector<MixSource> out;
  if (options.show) out.push_back(MixSource::kShow);
  if (options.input) out.push_back(MixSource::kInput);
  if (options.gamepad) out.push_back(MixSource::kGamepad);
  if (options.fap_stream) out.push_back(MixSource::kFapStream);
  if (options.live_link_face) out.push_back(MixSource::kLiveLinkFace);
  if (options.midi) out.push_back(MixSource::kMidi);
  return out;
}

// Stage 1. Everything is loaded and validated before anything is enabled.
// Throws ConfigError (or another exception) naming what is wrong.
void load(const RunOptions& options, RunSession& s) {
  ConfigOverrides overrides;
  overrides.show_path = options.show;
  overrides.rate_hz = options.rate_hz;
  overrides.hardware = parse_hardware_option(options.hardware);
  for (const auto& text : options.inject) s.injections.push_back(parse_injection(text));
  const std::string path = options.config.empty() ? default_config_path() : options.config;
  s.head.cfg = std::make_unique<LoadedConfig>(load_config(path, overrides));
  const LoadedConfig& cfg = *s.head.cfg;
  check_injection_buses(s.injections, cfg.rig);
  if (cfg.runtime.hardware == HardwareMode::kReal && !s.injections.empty()) {
    throw ConfigError(
        "--inject: expected simulated hardware (fault rehearsal), found "
        "hardware: real");
  }
  if (options.gamepad && !cfg.runtime.gamepad) {
    throw ConfigError("--gamepad: expected a gamepad block in " + cfg.runtime.file +
                      ", found none");
  }
  if (options.record_show && !options.gamepad && !options.input && !options.fap_stream &&
      !options.live_link_face && !options.midi) {
    throw ConfigError(
        "--record-show: expected --gamepad, --input, --midi, --fap-stream or --live-link-face (it "
        "records what they perform)");
  }
  if (options.midi) {
    if (!cfg.runtime.midi) {
      throw ConfigError("--midi: expected a midi block in " + cfg.runtime.file + ", found none");
    }
    s.midi_map = std::make_unique<MidiFaceMap>(
        resolve_midi_map(*cfg.runtime.midi, cfg.head.layout, cfg.expressions));
  }
  const std::vector<MixSource> sources = run_sources(options);
  const bool live_alone =
      sources.size() == 1 && sources[0] != MixSource::kShow && sources[0] != MixSource::kInput;
  for (const Injection& inj : s.injections) {
    if (inj.kind == Injection::Kind::kInputLoss && live_alone) {
      throw ConfigError(
          "--inject input_loss: expected a show or --input to silence, or several sources "
          "(mixed); to rehearse losing a gamepad or stream, stop its sender");
    }
  }
  if (sources.size() > 1) {
    if (!cfg.runtime.mix) {
      throw ConfigError(
          "expected at most one of --show, --input, --gamepad, --fap-stream, --live-link-face and "
          "--midi, or a mix: block in " +
          cfg.runtime.file + " to play several at once (docs/INPUTS.md)");
    }
    s.mix_plan =
        resolve_input_mix(*cfg.runtime.mix, cfg.head.layout, sources, cfg.runtime.show_rate_hz);
  }
  if (options.live_link_face) {
    if (!cfg.runtime.live_link_face) {
      throw ConfigError("--live-link-face: expected a live_link_face block in " + cfg.runtime.file +
                        ", found none");
    }
    s.retarget =
        std::make_unique<RetargetTable>(RetargetTable::load(cfg.runtime.retarget_path, cfg.head));
  }
  if (options.fap_stream) {
    if (!cfg.runtime.fap_stream) {
      throw ConfigError("--fap-stream: expected a fap_stream block in " + cfg.runtime.file +
                        ", found none");
    }
    s.fap_mapping = std::make_unique<FapMapping>(
        load_fap_mapping(cfg.head, cfg.expressions, cfg.runtime.visemes_path));
  }
  if (options.format && !options.input)
    throw ConfigError("--format: expected --input FILE with it");
  if (options.input) {
    std::optional<InputFormat> format;
    if (options.format) {
      format = parse_input_format(*options.format);
      if (!format) {
        throw ConfigError("--format: expected one of " + input_format_names() + ", found '" +
                          *options.format + "'");
      }
    }
    const std::string head = read_file_head(*options.input, kDetectBytes);
    format = resolve_input_format(*options.input, head, format);  // detected once
    if (*format == InputFormat::kShow) {
      s.input_show = Show::load(*options.input, cfg.head.layout, cfg.head.neutral, cfg.expressions);
    } else {
      s.input = load_recorded_input(cfg, *options.input, format);
    }
  }
  if (options.duration_s && !(*options.duration_s > 0.0)) {
    throw ConfigError("--duration: expected a number of seconds > 0");
  }
  // What plays by the sound's clock: the input, else the show, which plays
  // only when named or when nothing live does.
  const bool live = options.gamepad || options.fap_stream || options.live_link_face || options.midi;
  if (options.audio && !options.input && !(cfg.show && (options.show || !live))) {
    throw ConfigError(
        "--audio: expected --input or --show to time by the sound (a live source has no "
        "timeline)");
  }
}

// Stage 2. The hardware, the telemetry recording and the controller.
void open_hardware(const RunOptions& options, RunSession& s) {
  open_head(s.head, options.record, false);
}

// Stage 3. Input: the gamepad (puppeteering), a stream, a recorded input or
// the show, looping when a duration is given; with a mix: block, several of
// them, each into the mixer. Throws when the gamepad or a socket cannot be opened.
void open_input(const RunOptions& options, RunSession& s) {
  const ControllerModel& model = s.model();
  // Whatever plays records into it (load() checked there is a source): the
  // mix when there is one, else the single source.
  if (options.record_show) {
    s.recorder = std::make_unique<ShowRecorder>(model.layout, model.neutral);
  }
  if (s.mix_plan) {
    s.mixer = std::make_unique<InputMixer>(std::move(*s.mix_plan), model.neutral, s.head.mailbox,
                                           s.recorder.get());
  }
  const auto mailbox = [&s](MixSource src) {
    return s.mixer ? &s.mixer->input(src) : &s.head.mailbox;
  };
  ShowRecorder* const recorder = s.mixer ? nullptr : s.recorder.get();
  if (options.gamepad) {
    const GamepadConfig& g = *s.head.cfg->runtime.gamepad;
    try {
      s.pad = std::make_unique<HidGamepad>(g.selector, g.layout);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("gamepad: ") + e.what());
    }
    s.puppeteer = std::make_unique<GamepadPuppeteer>(
        [p = s.pad.get()](GamepadState& st) { return p->latest(st); }, GamepadMapping(g.terms),
        model.neutral, *mailbox(MixSource::kGamepad), g.rate_hz, recorder);
    std::fprintf(
        stderr, "facectl run: puppeteering from gamepad %s; Ctrl-C ends the run\n",
        g.selector.path.empty()
            ? (std::to_string(g.selector.vendor) + ":" + std::to_string(g.selector.product)).c_str()
            : g.selector.path.c_str());
  }
  if (options.fap_stream) {
    // Binding may fail (port in use, address): before anything is enabled.
    s.fap_stream = std::make_unique<FapUdpStream>(*s.fap_mapping, *s.head.cfg->runtime.fap_stream,
                                                  mailbox(MixSource::kFapStream), recorder);
    std::fprintf(stderr, "facectl run: FAP stream listening on UDP port %u; Ctrl-C ends the run\n",
                 static_cast<unsigned>(s.fap_stream->port()));
  }
  if (options.live_link_face) {
    s.live_link_face = std::make_unique<LiveLinkFaceStream>(
        *s.retarget, model.layout, model.neutral, *s.head.cfg->runtime.live_link_face,
        mailbox(MixSource::kLiveLinkFace), recorder);
    std::fprintf(stderr,
                 "facectl run: Live Link Face stream listening on UDP port %u; Ctrl-C ends the "
                 "run\n",
                 static_cast<unsigned>(s.live_link_face->port()));
  }
  if (options.midi) {
    s.midi = std::make_unique<MidiInput>(*s.midi_map, model.neutral, *s.head.cfg->runtime.midi,
                                         mailbox(MixSource::kMidi), recorder);
    std::fprintf(stderr,
                 "facectl run: MIDI in on ALSA sequencer port %s (client '%s'); Ctrl-C ends the "
                 "run\n",
                 s.midi->address().c_str(), s.head.cfg->runtime.midi->client.c_str());
  }
  s.live = options.gamepad || options.fap_stream || options.live_link_face || options.midi;

  if (options.audio) {
    s.audio = std::make_unique<AudioPlayback>(*options.audio, s.head.cfg->runtime.audio);
  }
  const double rate = s.head.cfg->runtime.show_rate_hz;
  if (s.input || s.input_show) {
    ShowPlayer::PoseSource source;
    if (s.input) {
      source = [track = &s.input->track](double t, std::array<double, kMaxFaceSignals>& out) {
        track->evaluate(t, out);
      };
    } else {
      source = [show = &*s.input_show](double t, std::array<double, kMaxFaceSignals>& out) {
        show->evaluate(t, out);
      };
    }
    const double duration = s.input ? s.input->track.duration() : s.input_show->duration();
    // Mixed, an input plays once and then gives its signals to the next source.
    s.player =
        std::make_unique<ShowPlayer>(std::move(source), duration, *mailbox(MixSource::kInput), rate,
                                     options.duration_s.has_value() && !s.mixer, recorder);
    if (s.mixer) s.player->give_way_when_finished();
    if (s.input) {
      for (const std::string& note : s.input->notes) {
        std::fprintf(stderr, "facectl run: %s: %s\n", options.input->c_str(), note.c_str());
      }
    }
  }
  // The show plays when named, or alone when nothing else is.
  if (s.head.cfg->show && (options.show || (!s.player && !s.live))) {
    (s.player ? s.mixed_show : s.player) = std::make_unique<ShowPlayer>(
        *s.head.cfg->show, *mailbox(MixSource::kShow), rate, options.duration_s.has_value());
  }
  // The sound is the clock: the face shows second t of its track when second
  // t - lead of the sound is heard.
  if (s.audio && s.player) {
    s.player->follow([a = s.audio.get(), lead = s.head.cfg->runtime.audio.lead_s](
                         std::int64_t now) { return a->clock().at(now) + lead; });
  }
  if (s.mixer) {
    s.silence_input = [m = s.mixer.get()] { m->go_silent(); };
  } else if (s.player) {
    s.silence_input = [p = s.player.get()] { p->go_silent(); };
  }
  if (options.duration_s) {
    s.end_s = *options.duration_s;
  } else if (s.audio) {              // when the sound and its track have played out
  } else if (!s.live && s.player) {  // until what plays has played; with nothing, a signal
    s.end_s = s.input ? s.input->track.duration() : s.input_show ? s.input_show->duration() : 0.0;
    if (s.mixed_show || (s.player && !s.input && !s.input_show)) {
      s.end_s = std::max(s.end_s, s.head.cfg->show->duration());
    }
  }
}

// Stage 4. Start: input, logger and the real-time loop, and ask to enable.
void start(RunSession& s) {
  if (s.mixer) s.mixer->start();
  if (s.player) s.player->start();
  if (s.mixed_show) s.mixed_show->start();
  if (s.fap_stream) s.fap_stream->start();
  if (s.live_link_face) s.live_link_face->start();
  if (s.midi) s.midi->start();
  if (s.puppeteer) s.puppeteer->start();
  start_head_loop(s.head);
  s.head.controller->request_enable();
}

// Prints the state machine's transitions; remembers the last FAULT or ESTOP
// for the status line.
void drain_events(RunSession& s, bool tty, const char*& fault_text) {
  while (const TransitionEvent* ev = s.head.events.front()) {
    if (tty) std::fputs("\r\033[K", stdout), std::fflush(stdout);
    print_transition(*ev);
    if (ev->to == SafetyState::kFault || ev->to == SafetyState::kEstop) {
      fault_text = ev->to == SafetyState::kFault ? "FAULT" : "ESTOP";
    }
    s.head.events.pop();
  }
}

// Stage 5. Watches the running loop from this (non-real-time) thread until
// the run ends: the show or duration is over or a signal asked to stop, and
// the head has eased to rest; or a FAULT or ESTOP has lingered and nothing
// holds any more.
void supervise(const RunOptions& options, RunSession& s, bool tty) {
  const std::int64_t t0 = monotonic_ns();
  bool shutdown = false;
  std::optional<double> fault_at;
  const char* fault_text = "";
  bool audio_started = false;
  auto last_status = t0;
  while (true) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const double t = static_cast<double>(monotonic_ns() - t0) * 1e-9;
    drain_events(s, tty, fault_text);
    fire_due_injections(s.injections, t, s.head.sim.get(), s.silence_input, s.head.loop.get());
    const SafetyState state = s.head.controller->state();
    if ((state == SafetyState::kFault || state == SafetyState::kEstop) && !fault_at) fault_at = t;
    // The sound starts with the head's motion, not during the enable ramp;
    // until then its player holds the track's first pose.
    if (s.audio && state == SafetyState::kRunning && !audio_started) {
      s.audio->start();
      audio_started = true;
    }
    const bool played_out = !options.duration_s && !s.live && s.player && s.player->finished() &&
                            (!s.mixed_show || s.mixed_show->finished()) &&
                            (!s.audio || s.audio->stats().finished);
    // A head that faulted or stopped before it ran never starts the sound, and
    // the track follows the sound: the run would wait for them for ever.
    const bool never_played =
        !options.duration_s && s.audio && !audio_started && fault_at.has_value();
    if (!shutdown && (g_signal.load() != 0 || t >= s.end_s || played_out || never_played)) {
      shutdown = true;
      s.head.controller->request_shutdown();
      if (g_signal.load() != 0) {
        std::fprintf(stderr, "\nfacectl run: signal %d: easing to rest\n", g_signal.load());
      }
    }
    // While FAULT holds or rests actuators the loop keeps commanding them,
    // until the run ends (duration, signal); even then it lets a moving one
    // come to a stop before the outputs are released (a second signal
    // releases at once).
    if (fault_at && t - *fault_at >= kFaultLingerSeconds && !s.head.controller->fault_holding())
      break;
    if (shutdown && state == SafetyState::kIdle) break;
    if (shutdown && state == SafetyState::kFault &&
        (!s.head.controller->fault_moving() || g_signal_count.load() > 1)) {
      if (s.head.controller->fault_moving()) {
        std::fprintf(stderr, "\nfacectl run: second signal: releasing a moving held actuator\n");
      }
      break;
    }
    if (tty && monotonic_ns() - last_status > 100'000'000) {
      last_status = monotonic_ns();
      std::printf("\r\033[K%s", format_status(s.head.stats, state, t, fault_text).c_str());
      std::fflush(stdout);
    }
  }
}

// Stage 6. Stops the loop, then releases the outputs, stops the inputs and
// flushes the logger.
void stop(RunSession& s, bool tty) {
  stop_head_loop(s.head);  // nothing holds once the loop has stopped
  if (s.player) s.player->stop();
  if (s.audio) s.audio->stop();
  if (s.mixed_show) s.mixed_show->stop();
  if (s.puppeteer) s.puppeteer->stop();
  if (s.fap_stream) s.fap_stream->stop();
  if (s.live_link_face) s.live_link_face->stop();
  if (s.midi) s.midi->stop();
  if (s.mixer) s.mixer->stop();  // after its sources
  if (s.head.writer) {
    // A slow file must not hold the exit: the drain has a budget, and a
    // signal from here on cuts it short (the rows left are counted lost).
    const int signals = g_signal_count.load();
    s.head.writer->finish(TelemetryWriter::kDrainBudgetSeconds,
                          [signals] { return g_signal_count.load() > signals; });
  }
  while (const TransitionEvent* ev = s.head.events.front()) {
    print_transition(*ev);
    s.head.events.pop();
  }
  if (tty) std::fputs("\r\033[K", stdout);
}

// Writes what was puppeteered as a show file; 1 when there is none to write.
int write_recorded_show(const RunOptions& options, const ShowRecorder& recorder) {
  if (recorder.keyframes() == 0) {
    std::fprintf(stderr, "facectl run: --record-show: the %s sent nothing; no show written\n",
                 run_sources(options).size() > 1 ? "mix"
                 : options.gamepad               ? "gamepad"
                 : options.input                 ? "input"
                 : options.midi                  ? "MIDI input"
                                                 : "stream");
    return 1;
  }
  try {
    recorder.write(*options.record_show, "recorded");
    std::printf("  recorded %zu keyframes to %s\n", recorder.keyframes(),
                options.record_show->c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl run: --record-show: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int run_command(const RunOptions& options) {
  RunSession s;
  try {
    load(options, s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl run: %s\n", e.what());
    return 2;
  }
  for (const auto& w : s.head.cfg->built.warnings) std::fprintf(stderr, "%s\n", w.c_str());

  // Threads started from here on stay off the loop's CPU.
  keep_off_realtime_cpu(s.head.cfg->runtime.realtime, s.head.rt);
  try {
    open_hardware(options, s);
    open_input(options, s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl run: %s\n", e.what());
    return 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // A telemetry reader that goes away must fail the file, not kill the
  // process while it drives the head.
  std::signal(SIGPIPE, SIG_IGN);

  start(s);
  const bool tty = !options.quiet && isatty(STDOUT_FILENO) != 0;
  supervise(options, s, tty);
  stop(s, tty);

  RunSummaryInput in{s.model(),
                     *s.head.controller,
                     s.head.stats,
                     s.head.rt,
                     s.head.writer.get(),
                     s.head.cfg->rig.name,
                     s.head.cfg->head.name,
                     s.head.events.dropped(),
                     s.head.real != nullptr};
  int rc = print_run_summary(in);
  if (s.fap_stream) {
    const FapUdpStats st = s.fap_stream->stats();
    std::printf(
        "  FAP stream: %llu datagrams, %llu frames played, %llu malformed, %llu out of "
        "bounds, %llu from refused senders, %llu dropped by the kernel\n",
        static_cast<unsigned long long>(st.datagrams), static_cast<unsigned long long>(st.frames),
        static_cast<unsigned long long>(st.malformed),
        static_cast<unsigned long long>(st.out_of_bounds),
        static_cast<unsigned long long>(st.refused_senders),
        static_cast<unsigned long long>(st.kernel_drops));
    if (!st.last_error.empty())
      std::printf("  FAP stream: last error: %s\n", st.last_error.c_str());
  }
  if (s.live_link_face) {
    const LiveLinkFaceStats st = s.live_link_face->stats();
    std::printf(
        "  Live Link Face stream: %llu datagrams, %llu frames played, %llu without a face, "
        "%llu malformed, %llu held back, %llu from refused senders, %llu dropped by the "
        "kernel, %llu values clamped\n",
        static_cast<unsigned long long>(st.datagrams), static_cast<unsigned long long>(st.frames),
        static_cast<unsigned long long>(st.no_face), static_cast<unsigned long long>(st.malformed),
        static_cast<unsigned long long>(st.held_back),
        static_cast<unsigned long long>(st.refused_senders),
        static_cast<unsigned long long>(st.kernel_drops),
        static_cast<unsigned long long>(st.clamps));
    if (!st.subject.empty()) {
      std::printf("  Live Link Face stream: subject '%s', device %s\n", st.subject.c_str(),
                  st.device_id.c_str());
    }
    if (!st.last_error.empty())
      std::printf("  Live Link Face stream: last error: %s\n", st.last_error.c_str());
  }
  if (s.midi) {
    const MidiStats st = s.midi->stats();
    std::printf(
        "  MIDI: %llu events, %llu controls and %llu notes played, %llu not in the map, at most "
        "%d senders connected, %llu overruns\n",
        static_cast<unsigned long long>(st.events), static_cast<unsigned long long>(st.controls),
        static_cast<unsigned long long>(st.notes), static_cast<unsigned long long>(st.unmapped),
        st.most_senders, static_cast<unsigned long long>(st.overruns));
    if (!st.last_error.empty()) std::printf("  MIDI: last error: %s\n", st.last_error.c_str());
  }
  if (s.audio) {
    const AudioStats st = s.audio->stats();
    std::printf("  audio: %.2f of %.2f s played on '%s', the face %.0f ms ahead, %llu underruns\n",
                st.played_s, st.file_s, s.head.cfg->runtime.audio.device.c_str(),
                s.head.cfg->runtime.audio.lead_s * 1e3,
                static_cast<unsigned long long>(st.underruns));
    if (st.started_ns != 0) {
      std::printf("  audio: second 0 of the sound heard at CLOCK_MONOTONIC %.6f s\n",
                  static_cast<double>(st.started_ns) * 1e-9);
    }
    if (!st.last_error.empty()) std::printf("  audio: last error: %s\n", st.last_error.c_str());
  }
  if (s.mixer) std::printf("  mix: %s\n", s.mixer->describe().c_str());
  if (s.recorder) rc = std::max(rc, write_recorded_show(options, *s.recorder));
  return rc;
}

}  // namespace facectl
