#pragma once

#include <string>

#include "firmware-host/config/config_node.hpp"

namespace facectl {

// The runtime file's `serve:` block: what `facectl serve` listens on, who may
// talk to it and where it keeps its files (docs/API.md, "Configuration").
struct ServeConfig {
  std::string listen = "127.0.0.1:8080";
  bool allow_remote = false;     // a non-loopback listen address needs this and a token
  std::string token_env;         // environment variable holding the bearer token
  std::string token_file;        // or a file holding it (absolute or relative to the runtime file)
  std::string tls_cert;          // PEM certificate (chain): serve HTTPS; with tls_key, or neither
  std::string tls_key;           // its PEM private key
  std::string shows_dir;         // the shows the API may play, by name; empty = next to `show:`
  std::string console_dir;       // the operator console's files; empty = the built-in default
  std::string event_log;         // empty = $LOGS_DIRECTORY/events.jsonl, else the XDG state dir
  long event_log_max_kb = 1024;  // rotate when the file passes this size
  long event_log_keep = 5;       // rotated files kept (events.jsonl.1 .. .N)
  long max_streams = 16;         // concurrent telemetry streams
};

ServeConfig parse_serve_config(const ConfigNode& node, const std::string& runtime_file);

}  // namespace facectl
