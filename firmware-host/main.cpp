// facectl: real-time controller for animatronic faces. Command-line entry point.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "firmware-host/cli/bench_command.hpp"
#include "firmware-host/cli/bus_doctor_command.hpp"
#include "firmware-host/cli/face_cli.hpp"
#include "firmware-host/cli/plot_command.hpp"
#include "firmware-host/cli/run_command.hpp"
#include "firmware-host/simulate/simulate_bench.hpp"
#include "firmware-host/simulate/simulate_command.hpp"
#include "firmware-host/verify/verify_command.hpp"

namespace {

int run_cli(int argc, char** argv) {
  CLI::App app{"facectl: real-time controller for animatronic robot faces"};
  app.require_subcommand(1);
  int exit_code = 0;

  facectl::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand(
      "run", "Drive the head from a show, with the real-time loop (simulated hardware by default)");
  run_cmd->add_option("--config", run.config,
                      "Runtime config (default: the shipped config/facectl.yaml)");
  run_cmd->add_option("--show", run.show, "Show file to play (overrides the config's show)");
  run_cmd->add_option("--duration", run.duration_s, "Run this many seconds, looping the show");
  run_cmd->add_option("--rate", run.rate_hz, "Loop rate in Hz (default from config: 1000)");
  run_cmd->add_option("--record", run.record, "Write per-tick telemetry CSV to this file");
  run_cmd->add_option("--hardware", run.hardware,
                      "sim or real: the simulated twins or the rig's buses and GPIO (default "
                      "from config: sim)");
  run_cmd->add_flag("--gamepad", run.gamepad,
                    "Puppeteer the face from the runtime config's gamepad instead of a show");
  run_cmd->add_option("--record-show", run.record_show,
                      "With --gamepad: write what was performed as a show file");
  run_cmd->add_option(
      "--inject", run.inject,
      "Rehearse a fault: estop@S, bus_fault:BUS@S, input_loss@S, overrun_storm:MS@S");
  run_cmd->add_flag("--quiet", run.quiet, "No live status line");
  run_cmd->callback([&] { exit_code = facectl::run_command(run); });

  facectl::BenchLoopOptions bench;
  CLI::App* bench_cmd = app.add_subcommand("bench", "Benchmarks");
  bench_cmd->require_subcommand(1);
  CLI::App* bench_loop = bench_cmd->add_subcommand(
      "loop", "Full pipeline at the loop rate beside a bare clock_nanosleep loop");
  bench_loop->add_option("--config", bench.config, "Runtime config");
  bench_loop->add_option("--duration", bench.duration_s, "Seconds per variant (default 10)");
  bench_loop->add_option("--chunk", bench.chunk_s, "Interleave chunk in seconds (default 1)");
  bench_loop->add_option("--rate", bench.rate_hz, "Loop rate in Hz");
  bench_loop->callback([&] { exit_code = facectl::bench_loop_command(bench); });
  facectl::SimulateBenchOptions bench_sim;
  CLI::App* bench_simulate = bench_cmd->add_subcommand(
      "simulate", "Offline simulation speed (no render) as a multiple of real time");
  bench_simulate->add_option("--config", bench_sim.config, "Runtime config (its rig and show)");
  bench_simulate->add_option("--rig", bench_sim.rig, "Rig instead of the config's");
  bench_simulate->add_option("--show", bench_sim.show, "Show instead of the config's");
  bench_simulate->add_option("--duration", bench_sim.duration_s,
                             "Simulated seconds per run, the show looping (default 600)");
  bench_simulate->add_option("--runs", bench_sim.runs, "Runs; the median is reported (default 5)");
  bench_simulate->callback([&] { exit_code = facectl::simulate_bench_command(bench_sim); });

  facectl::PlotOptions plot;
  CLI::App* plot_cmd = app.add_subcommand(
      "plot", "Plot each actuator's command and feedback against its limits from telemetry (SVG)");
  plot_cmd->add_option("telemetry", plot.telemetry, "Telemetry CSV from `facectl run --record`")
      ->required();
  plot_cmd->add_option("--config", plot.config, "Runtime config naming the rig");
  plot_cmd->add_option("--actuator", plot.actuators, "Only these actuators (repeatable)");
  plot_cmd->add_option("--out", plot.out_dir, "Output folder (default: .)");
  plot_cmd->callback([&] { exit_code = facectl::plot_command(plot); });

  facectl::VerifyOptions verify;
  CLI::App* verify_cmd = app.add_subcommand(
      "verify", "Prove before power-up that nothing the controller can command breaks the rig");
  verify_cmd->add_option("rig", verify.rig, "Rig YAML to verify")->required();
  verify_cmd->add_option("--config", verify.config, "Runtime config naming the head");
  verify_cmd->add_option("--show", verify.shows, "Show to check offline (repeatable)");
  verify_cmd->add_option("--json", verify.json, "Write the report as JSON to this file");
  verify_cmd->add_option("--plots", verify.plots,
                         "Folder for the show check's telemetry and per-actuator SVG plots");
  verify_cmd->add_option("--ticks", verify.ticks, "Adversarial search length (default 1000000)");
  verify_cmd->add_option("--seed", verify.seed, "Adversarial search seed (default 1)");
  verify_cmd->callback([&] { exit_code = facectl::verify_command(verify); });

  facectl::SimulateOptions simulate;
  CLI::App* simulate_cmd = app.add_subcommand(
      "simulate",
      "Run a show or an MPEG-4 FAP file through the whole pipeline offline, on the rig's "
      "simulated twin; write telemetry, plots, a summary and an HTML report (exit 0 ok, 1 the "
      "head faulted, 2 unusable input)");
  simulate_cmd->add_option("--rig", simulate.rig, "Rig YAML")->required();
  simulate_cmd->add_option("--show", simulate.show, "Show file to play");
  simulate_cmd->add_option("--fap", simulate.fap, "MPEG-4 FAP file to play");
  simulate_cmd->add_option("--out", simulate.out, "Output folder (replaced as a whole)")
      ->required();
  simulate_cmd->add_flag("--render", simulate.render, "Also write the face render frames");
  simulate_cmd->add_option("--config", simulate.config, "Runtime config naming the head");
  simulate_cmd->add_option("--duration", simulate.duration_s,
                           "Simulated seconds (default: the input's length; longer loops it)");
  simulate_cmd->add_option("--telemetry-rate", simulate.telemetry_rate_hz,
                           "Rows per simulated second in telemetry.csv (default 100)");
  simulate_cmd->add_flag("--quiet", simulate.quiet, "No progress bar");
  simulate_cmd->callback([&] { exit_code = facectl::simulate_command(simulate); });

  facectl::BusDoctorOptions doctor;
  CLI::App* bus_cmd = app.add_subcommand("bus", "Bus tools");
  bus_cmd->require_subcommand(1);
  CLI::App* doctor_cmd = bus_cmd->add_subcommand(
      "doctor",
      "Check each bus of a rig: reachable, devices answering, round trips, bad defaults, load "
      "(reads only; exit 0 ok, 1 problems, 2 unusable input)");
  doctor_cmd->add_option("rig", doctor.rig, "Rig file (default: the runtime config's rig)");
  doctor_cmd->add_option("--config", doctor.config, "Runtime config (head, loop rate)");
  doctor_cmd->add_option("--bus", doctor.bus, "Only this bus");
  doctor_cmd->add_option("--samples", doctor.samples, "Modbus reads per board (default 20)");
  doctor_cmd->add_option("--listen", doctor.listen_s, "Seconds to listen on CAN (default 0.5)");
  doctor_cmd->callback([&] { exit_code = facectl::bus_doctor_command(doctor); });

  register_face_commands(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::RuntimeError& e) {
    return e.get_exit_code();  // a command's own exit code (0, 1 or 2)
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;  // usage errors are exit code 2
  }
  return exit_code;
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
