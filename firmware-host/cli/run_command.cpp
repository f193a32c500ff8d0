#include "firmware-host/cli/run_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include "control/controller.hpp"
#include "control/realtime/loop_timer.hpp"
#include "drivers/hid/hid_gamepad.hpp"
#include "firmware-host/config/loaded_config.hpp"
#include "firmware-host/inputs/gamepad_puppeteer.hpp"
#include "firmware-host/inputs/show_player.hpp"
#include "firmware-host/model/sim_twin.hpp"
#include "firmware-host/run/fault_injection.hpp"
#include "firmware-host/run/real_hardware.hpp"
#include "firmware-host/run/realtime_loop.hpp"
#include "firmware-host/run/realtime_thread.hpp"
#include "firmware-host/run/run_summary.hpp"
#include "firmware-host/run/status_line.hpp"
#include "firmware-host/run/telemetry_writer.hpp"

namespace facectl {
namespace {

std::atomic<int> g_signal{0};
extern "C" void on_signal(int sig) {
  g_signal.store(sig);
}

// How long the loop keeps ticking (and recording) after FAULT or ESTOP.
constexpr double kFaultLingerSeconds = 0.5;

void print_event(const TransitionEvent& ev) {
  std::fprintf(stderr, "[%9.3f s, tick %llu] %s -> %s: %s%s%s\n", ev.time_s,
               static_cast<unsigned long long>(ev.tick), std::string(to_string(ev.from)).c_str(),
               std::string(to_string(ev.to)).c_str(), std::string(to_string(ev.reason)).c_str(),
               ev.detail[0] != '\0' ? " — " : "", ev.detail);
}

}  // namespace

int run_command(const RunOptions& options) {
  // 1. Everything is loaded and validated before anything is enabled.
  ConfigOverrides overrides;
  overrides.show_path = options.show;
  overrides.rate_hz = options.rate_hz;
  if (options.hardware) {
    if (*options.hardware == "sim") {
      overrides.hardware = HardwareMode::kSim;
    } else if (*options.hardware == "real") {
      overrides.hardware = HardwareMode::kReal;
    } else {
      std::fprintf(stderr, "facectl run: --hardware: expected sim or real, found '%s'\n",
                   options.hardware->c_str());
      return 2;
    }
  }
  std::vector<Injection> injections;
  std::unique_ptr<LoadedConfig> cfg;
  try {
    for (const auto& text : options.inject) injections.push_back(parse_injection(text));
    const std::string path = options.config.empty() ? default_config_path() : options.config;
    cfg = std::make_unique<LoadedConfig>(load_config(path, overrides));
    for (const auto& inj : injections) {
      if (inj.kind == Injection::Kind::kBusFault &&
          cfg->rig.buses.end() ==
              std::find_if(cfg->rig.buses.begin(), cfg->rig.buses.end(),
                           [&](const BusConfig& b) { return b.name == inj.bus; })) {
        throw ConfigError("--inject bus_fault:" + inj.bus + ": expected a bus of rig '" +
                          cfg->rig.name + "', found no such bus");
      }
    }
    if (cfg->runtime.hardware == HardwareMode::kReal && !injections.empty()) {
      throw ConfigError(
          "--inject: expected simulated hardware (fault rehearsal), found "
          "hardware: real");
    }
    if (options.gamepad && !cfg->runtime.gamepad) {
      throw ConfigError("--gamepad: expected a gamepad block in " + cfg->runtime.file +
                        ", found none");
    }
    if (options.record_show && !options.gamepad) {
      throw ConfigError("--record-show: expected --gamepad (it records the puppeteering)");
    }
    if (options.duration_s && !(*options.duration_s > 0.0)) {
      throw ConfigError("--duration: expected a number of seconds > 0");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl run: %s\n", e.what());
    return 2;
  }
  const ControllerModel& model = cfg->built.model;
  for (const auto& w : cfg->built.warnings) std::fprintf(stderr, "%s\n", w.c_str());

  // Threads started from here on stay off the loop's CPU.
  RealtimeReport rt;
  keep_off_realtime_cpu(cfg->runtime.realtime, rt);

  // 2. Hardware (simulated twins, or the real buses and GPIO), channels and the controller.
  std::unique_ptr<SimHardware> sim;
  std::unique_ptr<RealHardware> real;
  if (cfg->runtime.hardware == HardwareMode::kReal) {
    try {
      real = make_real_hardware(model, *cfg);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "facectl run: real hardware: %s\n", e.what());
      return 2;
    }
    for (const auto& note : real->notes) std::fprintf(stderr, "%s\n", note.c_str());
  } else {
    sim = make_sim_hardware(model, cfg->rig);
  }
  const std::vector<ActuatorBus*>& seams = real ? real->seams : sim->seams;
  SafetyIo& io = real ? real->io() : static_cast<SafetyIo&>(sim->io);
  LatestValueMailbox<FaceCommand> mailbox;
  SpscRing<TransitionEvent> events(256);
  std::unique_ptr<SpscRing<TelemetryRecord>> telemetry;
  std::unique_ptr<TelemetryWriter> writer;
  try {
    if (options.record) {
      telemetry = std::make_unique<SpscRing<TelemetryRecord>>(cfg->runtime.telemetry_ring);
      writer = std::make_unique<TelemetryWriter>(model, *telemetry, *options.record);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl run: %s\n", e.what());
    return 2;
  }
  Controller controller(model, seams, io, {&mailbox, telemetry.get(), &events});

  // 3. Input: the gamepad (puppeteering), or the show, looping when a duration is given.
  std::unique_ptr<ShowPlayer> player;
  std::unique_ptr<HidGamepad> pad;
  std::unique_ptr<ShowRecorder> recorder;
  std::unique_ptr<GamepadPuppeteer> puppeteer;
  if (options.gamepad) {
    const GamepadConfig& g = *cfg->runtime.gamepad;
    try {
      pad = std::make_unique<HidGamepad>(g.selector, g.layout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "facectl run: gamepad: %s\n", e.what());
      return 2;
    }
    if (options.record_show) recorder = std::make_unique<ShowRecorder>(model.layout, model.neutral);
    puppeteer = std::make_unique<GamepadPuppeteer>(
        [p = pad.get()](GamepadState& s) { return p->latest(s); }, GamepadMapping(g.terms),
        model.neutral, mailbox, g.rate_hz, recorder.get());
    std::fprintf(
        stderr, "facectl run: puppeteering from gamepad %s; Ctrl-C ends the run\n",
        g.selector.path.empty()
            ? (std::to_string(g.selector.vendor) + ":" + std::to_string(g.selector.product)).c_str()
            : g.selector.path.c_str());
  } else if (cfg->show) {
    player = std::make_unique<ShowPlayer>(*cfg->show, mailbox, cfg->runtime.show_rate_hz,
                                          options.duration_s.has_value());
  }
  const double end_s = options.duration_s ? *options.duration_s
                       : (player)         ? cfg->show->duration()
                                          : 1e300;

  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);

  // 4. Start: logger, input, then the real-time loop.
  if (writer) writer->start();
  if (player) player->start();
  if (puppeteer) puppeteer->start();
  LoopStats stats;
  RealtimeLoop loop(controller, model.rate_hz, stats);
  std::atomic<bool> stop{false};
  std::thread rt_thread = start_realtime_thread(
      cfg->runtime.realtime, [&] { loop.run(stop); }, rt);
  for (const auto& w : rt.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  controller.request_enable();

  const bool tty = !options.quiet && isatty(STDOUT_FILENO) != 0;
  const std::int64_t t0 = monotonic_ns();
  bool shutdown = false;
  std::optional<double> fault_at;
  const char* fault_text = "";
  auto last_status = t0;
  while (true) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const double t = static_cast<double>(monotonic_ns() - t0) * 1e-9;
    while (const TransitionEvent* ev = events.front()) {
      if (tty) std::fputs("\r\033[K", stdout), std::fflush(stdout);
      print_event(*ev);
      if (ev->to == SafetyState::kFault || ev->to == SafetyState::kEstop) {
        fault_text = ev->to == SafetyState::kFault ? "FAULT" : "ESTOP";
      }
      events.pop();
    }
    for (auto& inj : injections) {
      if (inj.done || t < inj.at_s) continue;
      inj.done = true;
      switch (inj.kind) {
        case Injection::Kind::kEstop:
          sim->io.press_estop();
          break;
        case Injection::Kind::kBusFault:
          sim->find(inj.bus)->inject_fault("injected bus fault");
          break;
        case Injection::Kind::kInputLoss:
          if (player) player->go_silent();
          break;
        case Injection::Kind::kOverrunStorm:
          loop.stall_until(monotonic_ns() + static_cast<std::int64_t>(inj.stall_ms * 1e6));
          break;
      }
    }
    const SafetyState state = controller.state();
    if (!shutdown && (g_signal.load() != 0 || t >= end_s ||
                      (!options.duration_s && player && player->finished()))) {
      shutdown = true;
      controller.request_shutdown();
      if (g_signal.load() != 0) {
        std::fprintf(stderr, "\nfacectl run: signal %d: easing to rest\n", g_signal.load());
      }
    }
    if ((state == SafetyState::kFault || state == SafetyState::kEstop) && !fault_at) fault_at = t;
    // While FAULT holds or rests actuators the loop keeps commanding them,
    // until the run ends (duration, signal).
    if (fault_at && t - *fault_at >= kFaultLingerSeconds && !controller.fault_holding()) break;
    if (shutdown && (state == SafetyState::kIdle || state == SafetyState::kFault)) break;
    if (tty && monotonic_ns() - last_status > 100'000'000) {
      last_status = monotonic_ns();
      std::printf("\r\033[K%s", format_status(stats, state, t, fault_text).c_str());
      std::fflush(stdout);
    }
  }
  stop.store(true);
  rt_thread.join();
  controller.release_outputs();  // nothing holds once the loop has stopped
  if (player) player->stop();
  if (puppeteer) puppeteer->stop();
  if (writer) writer->finish();
  while (const TransitionEvent* ev = events.front()) {
    print_event(*ev);
    events.pop();
  }
  if (tty) std::fputs("\r\033[K", stdout);

  RunSummaryInput in{model,          controller,    stats,          rt,
                     writer.get(),   cfg->rig.name, cfg->head.name, events.dropped(),
                     real != nullptr};
  int rc = print_run_summary(in);
  if (recorder) {
    if (recorder->keyframes() == 0) {
      std::fprintf(stderr,
                   "facectl run: --record-show: the gamepad sent nothing; no show written\n");
      rc = std::max(rc, 1);
    } else {
      try {
        recorder->write(*options.record_show, "recorded");
        std::printf("  recorded %zu keyframes to %s\n", recorder->keyframes(),
                    options.record_show->c_str());
      } catch (const std::exception& e) {
        std::fprintf(stderr, "facectl run: --record-show: %s\n", e.what());
        rc = std::max(rc, 1);
      }
    }
  }
  return rc;
}

}  // namespace facectl
