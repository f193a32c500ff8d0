// facectl: real-time controller for animatronic faces. Command-line entry point.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "firmware-host/cli/bench_command.hpp"
#include "firmware-host/cli/bus_doctor_command.hpp"
#include "firmware-host/cli/face_cli.hpp"
#include "firmware-host/cli/gamepad_layout_command.hpp"
#include "firmware-host/cli/plot_command.hpp"
#include "firmware-host/cli/run_command.hpp"
#include "firmware-host/cli/serve_command.hpp"
#include "firmware-host/config/config_location.hpp"
#include "firmware-host/simulate/simulate_bench.hpp"
#include "firmware-host/simulate/simulate_command.hpp"
#include "firmware-host/verify/verify_command.hpp"

namespace {

// Each command's options, filled in by CLI11 while it parses, and the exit
// code the chosen command's callback returns.
struct CliOptions {
  facectl::RunOptions run;
  facectl::ServeOptions serve;
  facectl::BenchLoopOptions bench;
  facectl::SimulateBenchOptions bench_sim;
  facectl::PlotOptions plot;
  facectl::VerifyOptions verify;
  facectl::SimulateOptions simulate;
  facectl::BusDoctorOptions doctor;
  facectl::GamepadLayoutOptions gamepad_layout;
  int exit_code = 0;
};

// `facectl run`: the real-time loop.
void add_run_command(CLI::App& app, CliOptions& o) {
  CLI::App* run_cmd = app.add_subcommand(
      "run", "Drive the head from a show, with the real-time loop (simulated hardware by default)");
  run_cmd->add_option("--config", o.run.config,
                      "Runtime config (default: $FACECTL_CONFIG, else the shipped " +
                          facectl::shipped_dirs().config + "/facectl.yaml)");
  run_cmd->add_option("--show", o.run.show, "Show file to play (overrides the config's show)");
  run_cmd->add_option("--duration", o.run.duration_s, "Run this many seconds, looping the show");
  run_cmd->add_option("--rate", o.run.rate_hz, "Loop rate in Hz (default from config: 1000)");
  run_cmd->add_option("--record", o.run.record, "Write per-tick telemetry CSV to this file");
  run_cmd->add_option("--hardware", o.run.hardware,
                      "sim or real: the simulated twins or the rig's buses and GPIO (default "
                      "from config: sim)");
  run_cmd->add_flag("--gamepad", o.run.gamepad,
                    "Puppeteer the face from the runtime config's gamepad instead of a show");
  run_cmd->add_option("--input", o.run.input,
                      "Play an input file instead of the show: FAP, Live Link Face CSV, MediaPipe "
                      "JSON, OpenFace CSV, Rhubarb JSON/TSV, Praat TextGrid, speech audio "
                      "(docs/INPUTS.md)");
  run_cmd->add_option("--format", o.run.format,
                      "The --input file's format (default: detected from its content)");
  run_cmd->add_flag("--fap-stream", o.run.fap_stream,
                    "Play the live MPEG-4 FAP stream over UDP of the runtime config's fap_stream "
                    "block instead of a show (docs/FAP.md)");
  run_cmd->add_flag("--live-link-face", o.run.live_link_face,
                    "Play the Live Link Face app's UDP stream (the runtime config's "
                    "live_link_face block) instead of a show (docs/INPUTS.md)");
  run_cmd->add_flag("--midi", o.run.midi,
                    "Play MIDI controls and notes from the ALSA sequencer by the runtime config's "
                    "midi map (docs/INPUTS.md)");
  run_cmd->add_option("--audio", o.run.audio,
                      "Play this sound through the runtime config's audio device, with --input "
                      "(or the show) timed by it and the face leading it by audio.lead_ms "
                      "(docs/INPUTS.md)");
  run_cmd->add_option("--record-show", o.run.record_show,
                      "With --gamepad, --input, --midi or a stream: write what was "
                      "performed as a show file");
  run_cmd->add_option(
      "--inject", o.run.inject,
      "Rehearse a fault: estop@S, bus_fault:BUS@S, input_loss@S, overrun_storm:MS@S");
  run_cmd->add_flag("--quiet", o.run.quiet, "No live status line");
  run_cmd->callback([&o] { o.exit_code = facectl::run_command(o.run); });
}

// `facectl serve`: the head as a service with the control API and console.
void add_serve_command(CLI::App& app, CliOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "serve",
      "Keep the head under control as a service: HTTP control API and operator console "
      "(docs/API.md); starts IDLE");
  cmd->add_option("--config", o.serve.config,
                  "Runtime config (default: the shipped config/facectl.yaml)");
  cmd->add_option("--listen", o.serve.listen,
                  "ADDR:PORT to listen on (default from config: 127.0.0.1:8080; port 0: any)");
  cmd->add_flag("--allow-remote", o.serve.allow_remote,
                "Allow a non-loopback listen address (needs an access token)");
  cmd->add_option("--hardware", o.serve.hardware, "sim or real (default from config: sim)");
  cmd->add_option("--event-log", o.serve.event_log, "Event log file (JSON lines)");
  cmd->add_option("--console", o.serve.console, "Folder of the operator console's files");
  cmd->callback([&o] { o.exit_code = facectl::serve_command(o.serve); });
}

// `facectl bench loop` and `facectl bench simulate`.
void add_bench_commands(CLI::App& app, CliOptions& o) {
  CLI::App* bench_cmd = app.add_subcommand("bench", "Benchmarks");
  bench_cmd->require_subcommand(1);
  CLI::App* bench_loop = bench_cmd->add_subcommand(
      "loop", "Full pipeline at the loop rate beside a bare clock_nanosleep loop");
  bench_loop->add_option("--config", o.bench.config, "Runtime config");
  bench_loop->add_option("--duration", o.bench.duration_s, "Seconds per variant (default 10)");
  bench_loop->add_option("--chunk", o.bench.chunk_s, "Interleave chunk in seconds (default 1)");
  bench_loop->add_option("--rate", o.bench.rate_hz, "Loop rate in Hz");
  bench_loop->add_option("--inject", o.bench.inject,
                         "Rehearse a fault, as run --inject (KIND@SECONDS of pipeline time)");
  bench_loop->callback([&o] { o.exit_code = facectl::bench_loop_command(o.bench); });
  CLI::App* bench_simulate = bench_cmd->add_subcommand(
      "simulate", "Offline simulation speed (no render) as a multiple of real time");
  bench_simulate->add_option("--config", o.bench_sim.config, "Runtime config (its rig and show)");
  bench_simulate->add_option("--rig", o.bench_sim.rig, "Rig instead of the config's");
  bench_simulate->add_option("--show", o.bench_sim.show, "Show instead of the config's");
  bench_simulate->add_option("--duration", o.bench_sim.duration_s,
                             "Simulated seconds per run, the show looping (default 600)");
  bench_simulate->add_option("--runs", o.bench_sim.runs,
                             "Runs; the median is reported (default 5)");
  bench_simulate->callback([&o] { o.exit_code = facectl::simulate_bench_command(o.bench_sim); });
}

// `facectl plot`: SVG plots from recorded telemetry.
void add_plot_command(CLI::App& app, CliOptions& o) {
  CLI::App* plot_cmd = app.add_subcommand(
      "plot", "Plot each actuator's command and feedback against its limits from telemetry (SVG)");
  plot_cmd->add_option("telemetry", o.plot.telemetry, "Telemetry CSV from `facectl run --record`")
      ->required();
  plot_cmd->add_option("--config", o.plot.config, "Runtime config naming the rig");
  plot_cmd->add_option("--actuator", o.plot.actuators, "Only these actuators (repeatable)");
  plot_cmd->add_option("--out", o.plot.out_dir, "Output folder (default: .)");
  plot_cmd->callback([&o] { o.exit_code = facectl::plot_command(o.plot); });
}

// `facectl verify`: the pre-power-up proof.
void add_verify_command(CLI::App& app, CliOptions& o) {
  CLI::App* verify_cmd = app.add_subcommand(
      "verify", "Prove before power-up that nothing the controller can command breaks the rig");
  verify_cmd->add_option("rig", o.verify.rig, "Rig YAML to verify")->required();
  verify_cmd->add_option("--config", o.verify.config, "Runtime config naming the head");
  verify_cmd->add_option("--show", o.verify.shows, "Show to check offline (repeatable)");
  verify_cmd->add_option("--json", o.verify.json, "Write the report as JSON to this file");
  verify_cmd->add_option("--plots", o.verify.plots,
                         "Folder for the show check's telemetry and per-actuator SVG plots");
  verify_cmd->add_option("--ticks", o.verify.ticks, "Adversarial search length (default 1000000)");
  verify_cmd->add_option("--seed", o.verify.seed, "Adversarial search seed (default 1)");
  verify_cmd->callback([&o] { o.exit_code = facectl::verify_command(o.verify); });
}

// `facectl simulate`: a show, FAP or other input file offline on the rig's simulated twin.
void add_simulate_command(CLI::App& app, CliOptions& o) {
  CLI::App* simulate_cmd = app.add_subcommand(
      "simulate",
      "Run a show, an MPEG-4 FAP file or another input through the whole pipeline offline, on the "
      "rig's "
      "simulated twin; write telemetry, plots, a summary and an HTML report (exit 0 ok, 1 the "
      "head faulted, 2 unusable input)");
  simulate_cmd->add_option("--rig", o.simulate.rig, "Rig YAML")->required();
  simulate_cmd->add_option("--show", o.simulate.show, "Show file to play");
  simulate_cmd->add_option("--fap", o.simulate.fap, "MPEG-4 FAP file to play");
  simulate_cmd->add_option("--input", o.simulate.input,
                           "Any input file to play: show, FAP, Live Link Face CSV, MediaPipe "
                           "JSON, OpenFace CSV, Rhubarb JSON/TSV, Praat TextGrid, speech audio "
                           "(docs/INPUTS.md)");
  simulate_cmd->add_option("--format", o.simulate.format,
                           "The --input file's format (default: detected from its content)");
  simulate_cmd->add_option("--out", o.simulate.out, "Output folder (replaced as a whole)")
      ->required();
  simulate_cmd->add_flag("--render", o.simulate.render, "Also write the face render frames");
  simulate_cmd->add_option("--config", o.simulate.config, "Runtime config naming the head");
  simulate_cmd->add_option("--duration", o.simulate.duration_s,
                           "Simulated seconds (default: the input's length; longer loops it)");
  simulate_cmd->add_option("--telemetry-rate", o.simulate.telemetry_rate_hz,
                           "Rows per simulated second in telemetry.csv (default 100)");
  simulate_cmd->add_option("--max-output-mb", o.simulate.max_output_mb,
                           "Refuse a run whose outputs could exceed this many MB (default 1024)");
  simulate_cmd->add_flag("--quiet", o.simulate.quiet, "No progress bar");
  simulate_cmd->callback([&o] { o.exit_code = facectl::simulate_command(o.simulate); });
}

// `facectl bus doctor`.
void add_bus_commands(CLI::App& app, CliOptions& o) {
  CLI::App* bus_cmd = app.add_subcommand("bus", "Bus tools");
  bus_cmd->require_subcommand(1);
  CLI::App* doctor_cmd = bus_cmd->add_subcommand(
      "doctor",
      "Check each bus of a rig: reachable, devices answering, round trips, bad defaults, load "
      "(reads only; exit 0 ok, 1 problems, 2 unusable input)");
  doctor_cmd->add_option("rig", o.doctor.rig, "Rig file (default: the runtime config's rig)");
  doctor_cmd->add_option("--config", o.doctor.config, "Runtime config (head, loop rate)");
  doctor_cmd->add_option("--bus", o.doctor.bus, "Only this bus");
  doctor_cmd->add_option("--samples", o.doctor.samples, "Modbus reads per board (default 20)");
  doctor_cmd->add_option("--listen", o.doctor.listen_s, "Seconds to listen on CAN (default 0.5)");
  doctor_cmd->callback([&o] { o.exit_code = facectl::bus_doctor_command(o.doctor); });
}

// `facectl gamepad layout`.
void add_gamepad_command(CLI::App& app, CliOptions& o) {
  CLI::App* gamepad_cmd = app.add_subcommand("gamepad", "Gamepad tools");
  gamepad_cmd->require_subcommand(1);
  CLI::App* layout_cmd = gamepad_cmd->add_subcommand(
      "layout", "Print the axes and buttons a gamepad's HID report descriptor declares");
  layout_cmd->add_option("--device", o.gamepad_layout.device,
                         "The gamepad: /dev/hidrawN, or VENDOR:PRODUCT in hex");
  layout_cmd->add_option("--descriptor", o.gamepad_layout.descriptor,
                         "Or a report descriptor file (binary, or hex bytes)");
  layout_cmd->callback([&o] { o.exit_code = facectl::gamepad_layout_command(o.gamepad_layout); });
}

int run_cli(int argc, char** argv) {
  CLI::App app{"facectl: real-time controller for animatronic robot faces"};
  app.require_subcommand(1);
  CliOptions o;
  add_run_command(app, o);
  add_serve_command(app, o);
  add_bench_commands(app, o);
  add_plot_command(app, o);
  add_verify_command(app, o);
  add_simulate_command(app, o);
  add_bus_commands(app, o);
  add_gamepad_command(app, o);
  register_face_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own exit code (0, 1 or 2)
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;  // usage errors are exit code 2
  }
  return o.exit_code;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_cli(argc, argv);
  } catch (const std::exception& e) {
    // Anything unforeseen (e.g. a thread that cannot start): say so, never abort silently.
    std::fprintf(stderr, "facectl: %s\n", e.what());
    return 2;
  }
}
