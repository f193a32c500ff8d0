#include "firmware-host/config/runtime_config.hpp"

#include "firmware-host/config/config_node.hpp"

namespace facectl {

RuntimeConfig load_runtime_config(const std::string& path) {
  const ConfigNode root = ConfigNode::load_file(path, "");
  root.expect_keys({"runtime", "head", "rig", "expressions", "show", "visemes", "retarget",
                    "hardware", "safety_io", "gamepad", "serve", "fap_stream", "live_link_face",
                    "osc", "mix", "midi", "audio"});
  RuntimeConfig cfg;
  cfg.file = path;
  cfg.head_path = resolve_path(path, root["head"].string());
  cfg.rig_path = resolve_path(path, root["rig"].string());
  cfg.expressions_path = resolve_path(path, root["expressions"].string());
  if (auto show = root.get("show")) cfg.show_path = resolve_path(path, show->string());
  // Beside the runtime file like every other data file, so that --config and
  // an installed /etc/facectl each find their own.
  const auto visemes = root.get("visemes");
  cfg.visemes_path = resolve_path(path, visemes ? visemes->string() : "fap/visemes.yaml");
  // Per head: beside the head file unless the runtime file names another.
  const auto retarget = root.get("retarget");
  cfg.retarget_path = retarget ? resolve_path(path, retarget->string())
                               : resolve_path(cfg.head_path, "retarget.yaml");
  if (auto n = root.get("hardware")) cfg.hardware = parse_hardware_mode(*n);
  if (auto n = root.get("safety_io")) cfg.safety_io = parse_safety_io(*n);
  if (auto n = root.get("gamepad")) cfg.gamepad = parse_gamepad(*n);
  if (auto n = root.get("serve")) cfg.serve = parse_serve_config(*n, path);
  if (auto n = root.get("fap_stream")) cfg.fap_stream = parse_fap_stream_config(*n);
  if (auto n = root.get("live_link_face")) cfg.live_link_face = parse_live_link_face_config(*n);
  if (auto n = root.get("midi")) cfg.midi = parse_midi_config(*n);
  if (auto n = root.get("mix")) cfg.mix = parse_mix_config(*n);
  if (auto n = root.get("osc")) cfg.osc = parse_osc_config(*n);
  if (auto n = root.get("audio")) cfg.audio = parse_audio_config(*n);

  if (auto rt = root.get("runtime")) {
    rt->expect_keys({"rate_hz", "realtime", "input_timeout_ms", "overrun_fault_count",
                     "enable_ramp_s", "stop_timeout_s", "shaping", "telemetry_ring", "show_rate_hz",
                     "jog_speed_fraction"});
    if (auto n = rt->get("rate_hz")) cfg.rate_hz = n->number_in(1.0, 10000.0);
    if (auto r = rt->get("realtime")) {
      r->expect_keys({"priority", "cpu", "lock_memory", "cpu_dma_latency_us"});
      if (auto n = r->get("cpu_dma_latency_us")) {
        cfg.realtime.cpu_dma_latency_us = static_cast<int>(n->integer_in(-1, 1'000'000));
      }
      if (auto n = r->get("priority"))
        cfg.realtime.priority = static_cast<int>(n->integer_in(0, 99));
      if (auto n = r->get("cpu")) cfg.realtime.cpu = static_cast<int>(n->integer_in(-1, 1023));
      if (auto n = r->get("lock_memory")) cfg.realtime.lock_memory = n->boolean();
    }
    if (auto n = rt->get("input_timeout_ms")) cfg.safety.input_timeout_s = n->positive() * 1e-3;
    if (auto n = rt->get("overrun_fault_count")) {
      cfg.safety.overrun_fault_count = static_cast<int>(n->integer_in(1, 100'000));
    }
    if (auto n = rt->get("enable_ramp_s")) cfg.safety.enable_ramp_s = n->number_in(0.0, 60.0);
    if (auto n = rt->get("stop_timeout_s")) cfg.safety.stop_timeout_s = n->number_in(0.1, 60.0);
    if (auto n = rt->get("jog_speed_fraction")) {
      cfg.safety.jog_speed_fraction = n->number_in(0.01, 1.0);
    }
    if (auto s = rt->get("shaping")) {
      s->expect_keys({"activation_ms", "deactivation_ms", "smoothing_ms", "neutral_ease_s"});
      if (auto n = s->get("activation_ms")) {
        cfg.shaping.activation_time_constant_s = n->number_in(0, 1000) * 1e-3;
      }
      if (auto n = s->get("deactivation_ms")) {
        cfg.shaping.deactivation_time_constant_s = n->number_in(0, 1000) * 1e-3;
      }
      if (auto n = s->get("smoothing_ms")) {
        cfg.shaping.smoothing_time_constant_s = n->number_in(0, 1000) * 1e-3;
      }
      if (auto n = s->get("neutral_ease_s")) cfg.shaping.neutral_ease_time_s = n->number_in(0, 60);
    }
    if (auto n = rt->get("telemetry_ring")) {
      // At most 65536 records (about 150 MB, locked in memory).
      cfg.telemetry_ring = static_cast<std::size_t>(n->integer_in(64, 65536));
    }
    if (auto n = rt->get("show_rate_hz")) cfg.show_rate_hz = n->number_in(1.0, 1000.0);
    // The show must refresh the command well inside the input watchdog.
    if (2.0 / cfg.show_rate_hz > cfg.safety.input_timeout_s) {
      const ConfigNode at = rt->get("show_rate_hz") ? (*rt)["show_rate_hz"] : *rt;
      at.fail("show_rate_hz of at least " + std::to_string(2.0 / cfg.safety.input_timeout_s) +
              " Hz (two commands per input_timeout_ms)");
    }
  }
  // The mix, when it has its own rate, stands where the show would; MIDI
  // repeats a held pose at its own.
  const double least_hz = 2.0 / cfg.safety.input_timeout_s;
  const auto slower = [&](double hz) { return hz > 0.0 && hz < least_hz; };
  const std::string per = " Hz (two commands per input_timeout_ms)";
  // The key when written, else its block (a default that no longer fits).
  const auto at = [&root](const char* block, const char* key) {
    const ConfigNode b = root[block];
    return b.get(key).value_or(b);
  };
  if (cfg.mix && slower(cfg.mix->rate_hz)) {
    at("mix", "rate_hz").fail("a rate_hz of at least " + std::to_string(least_hz) + per);
  }
  if (cfg.midi && slower(cfg.midi->rate_hz)) {
    at("midi", "rate_hz").fail("a rate_hz of at least " + std::to_string(least_hz) + per);
  }
  // A source lost while another still sends keeps its groups for stale_ms,
  // unseen by the tick's watchdog: no longer than the watchdog would wait.
  if (cfg.mix && cfg.mix->stale_ms * 1e-3 > cfg.safety.input_timeout_s + 1e-12) {
    at("mix", "stale_ms")
        .fail("a stale_ms of at most input_timeout_ms (" +
              std::to_string(cfg.safety.input_timeout_s * 1e3) + ")");
  }
  return cfg;
}

}  // namespace facectl
