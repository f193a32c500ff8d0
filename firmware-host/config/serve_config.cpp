#include "firmware-host/config/serve_config.hpp"

namespace facectl {

ServeConfig parse_serve_config(const ConfigNode& node, const std::string& runtime_file) {
  node.expect_keys({"listen", "allow_remote", "token_env", "token_file", "tls_cert", "tls_key",
                    "shows", "console", "event_log", "event_log_max_kb", "event_log_keep",
                    "max_streams"});
  ServeConfig cfg;
  if (auto n = node.get("listen")) cfg.listen = n->string();
  if (auto n = node.get("allow_remote")) cfg.allow_remote = n->boolean();
  if (auto n = node.get("token_env")) cfg.token_env = n->string();
  if (auto n = node.get("token_file")) cfg.token_file = resolve_path(runtime_file, n->string());
  const auto cert = node.get("tls_cert"), key = node.get("tls_key");
  if (cert && !key) cert->fail("tls_cert together with tls_key", "tls_cert alone");
  if (key && !cert) key->fail("tls_key together with tls_cert", "tls_key alone");
  if (cert) cfg.tls_cert = resolve_path(runtime_file, cert->string());
  if (key) cfg.tls_key = resolve_path(runtime_file, key->string());
  if (auto n = node.get("shows")) cfg.shows_dir = resolve_path(runtime_file, n->string());
  if (auto n = node.get("console")) cfg.console_dir = resolve_path(runtime_file, n->string());
  if (auto n = node.get("event_log")) cfg.event_log = resolve_path(runtime_file, n->string());
  if (auto n = node.get("event_log_max_kb")) cfg.event_log_max_kb = n->integer_in(16, 1 << 20);
  if (auto n = node.get("event_log_keep")) cfg.event_log_keep = n->integer_in(1, 100);
  if (auto n = node.get("max_streams")) cfg.max_streams = n->integer_in(1, 64);
  return cfg;
}

}  // namespace facectl
