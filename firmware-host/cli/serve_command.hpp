#pragma once

#include <optional>
#include <string>

namespace facectl {

struct ServeOptions {
  std::string config;                    // runtime file; empty = the shipped default
  std::optional<std::string> listen;     // ADDR:PORT; overrides serve.listen
  bool allow_remote = false;             // with a token: a non-loopback address
  std::optional<std::string> hardware;   // "sim" or "real"
  std::optional<std::string> event_log;  // overrides serve.event_log
  std::optional<std::string> console;    // overrides serve.console
};

// Keeps the head under control until SIGTERM or SIGINT, serving the control
// API and the operator console (docs/API.md). Exit codes: 0 after an orderly
// stop; 2 unusable input, hardware that cannot be opened or an address that
// cannot be bound; 3 when the stop found the head in FAULT or ESTOP.
int serve_command(const ServeOptions& options);

}  // namespace facectl
