#include "firmware-host/cli/serve_command.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <thread>

#include "firmware-host/config/config_location.hpp"
#include "firmware-host/serve/http_api.hpp"
#include "firmware-host/serve/serve_session.hpp"
#include "firmware-host/serve/systemd_notify.hpp"

namespace facectl {
namespace {

std::atomic<int> g_signal{0};
extern "C" void on_serve_signal(int sig) {
  g_signal.store(sig);
}

// The console's files: --console, serve.console, else the shipped folder
// (the source tree's from the build tree, else the installed one).
std::string console_folder(const ServeOptions& options, const ServeConfig& serve) {
  if (options.console) return *options.console;
  if (!serve.console_dir.empty()) return serve.console_dir;
  return shipped_dirs().console;
}

// The session and its HTTP side; the server stops before the session.
struct Served {
  ServeSession session;
  std::unique_ptr<HttpApi> api;
  std::thread http;
};

// Loads and checks everything, binds the address; nothing is started yet.
void prepare(const ServeOptions& options, Served& s) {
  ConfigOverrides overrides;
  overrides.hardware = parse_hardware_option(options.hardware);
  const std::string path = options.config.empty() ? default_config_path() : options.config;
  s.session.head.cfg = std::make_unique<LoadedConfig>(load_config(path, overrides));
  const ServeConfig& serve = s.session.head.cfg->runtime.serve;

  HttpApi::Options api;
  const std::string listen = options.listen.value_or(serve.listen);
  try {
    api.listen = parse_listen_address(listen);
  } catch (const std::invalid_argument& e) {
    throw ConfigError("listen address: " + std::string(e.what()));
  }
  api.token = load_access_token(serve.token_env, serve.token_file);
  if (!api.listen.loopback) {
    if (!(options.allow_remote || serve.allow_remote)) {
      throw ConfigError("listen address " + listen +
                        " is not loopback: it needs --allow-remote (or serve.allow_remote: true) "
                        "and an access token (serve.token_env or serve.token_file)");
    }
    if (api.token.empty()) {
      throw ConfigError("listen address " + listen +
                        " is not loopback: it needs an access token (serve.token_env or "
                        "serve.token_file in " +
                        s.session.head.cfg->runtime.file + ")");
    }
  }
  api.tls_cert = serve.tls_cert;
  api.tls_key = serve.tls_key;
  if (!api.listen.loopback && api.tls_cert.empty()) {
    std::fprintf(stderr,
                 "facectl serve: warning: plain HTTP beyond loopback: the access token and "
                 "every command cross the network readable; set serve.tls_cert and "
                 "serve.tls_key (docs/API.md, \"Access\")\n");
  }
  api.console_dir = console_folder(options, serve);
  api.max_streams = serve.max_streams;

  const std::string log_path = options.event_log.value_or(
      serve.event_log.empty() ? EventLog::default_path() : serve.event_log);
  open_serve_session(s.session, log_path);
  s.api = std::make_unique<HttpApi>(*s.session.service, api);
  s.api->bind();
}

// Waits for SIGTERM or SIGINT, then eases the head to rest the way `run`
// does: IDLE, or a FAULT whose held actuators have stopped, or the state
// machine's own stop timeout plus a second.
void serve_until_signal(Served& s) {
  while (g_signal.load() == 0) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  notify_stopping();
  s.session.service->begin_shutdown("signal " + std::to_string(g_signal.load()));
  const auto limit =
      std::chrono::steady_clock::now() +
      std::chrono::duration<double>(s.session.head.model().safety.stop_timeout_s + 1.0);
  while (std::chrono::steady_clock::now() < limit) {
    const SafetyState st = s.session.head.controller->state();
    if (st == SafetyState::kIdle || st == SafetyState::kEstop) break;
    if (st == SafetyState::kFault && !s.session.head.controller->fault_moving()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace

int serve_command(const ServeOptions& options) {
  Served s;
  try {
    prepare(options, s);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "facectl serve: %s\n", e.what());
    return 2;
  }
  for (const auto& w : s.session.head.cfg->built.warnings) std::fprintf(stderr, "%s\n", w.c_str());
  std::signal(SIGINT, on_serve_signal);
  std::signal(SIGTERM, on_serve_signal);
  std::signal(SIGPIPE, SIG_IGN);  // a client that goes away fails its socket, not the process

  start_serve_session(s.session);
  s.http = std::thread([&s] { s.api->serve(); });
  s.api->wait_until_serving();  // a stop() before that would be lost
  const std::string where = s.api->url();
  s.session.log->add("service", "serve",
                     "listening on " + where + ", head IDLE, event log " + s.session.log->path());
  if (s.session.osc) {
    s.session.log->add("service", "osc", "OSC control on udp " + s.session.osc->bound());
  }
  notify_ready("IDLE, listening on " + where);

  serve_until_signal(s);
  s.api->stop();
  s.http.join();
  stop_serve_session(s.session);
  if (s.session.osc) s.session.log->add("service", "osc", describe(s.session.osc->stats()));
  const SafetyState end = s.session.head.controller->state();
  s.session.log->add("service", "serve", "stopped in " + std::string(to_string(end)));
  return end == SafetyState::kFault || end == SafetyState::kEstop ? 3 : 0;
}

}  // namespace facectl
