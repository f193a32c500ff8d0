#pragma once

#include <optional>
#include <string>

namespace facectl {

// Where `facectl serve` listens, parsed from ADDR:PORT (IPv4 dotted quad,
// `localhost`, or [IPv6]).
struct ListenAddress {
  std::string host;
  int port = 0;
  bool loopback = false;  // 127.0.0.0/8, ::1 or localhost
};

// Throws std::invalid_argument saying what is wrong.
ListenAddress parse_listen_address(const std::string& text);

// localhost, 127.0.0.0/8 or ::1 (no brackets).
bool is_loopback_name(const std::string& host);

// For a listener without a token, which only loopback may reach: why a
// request that a web page could have sent is refused, or nullopt. Its Host
// header must name loopback (a DNS-rebinding page's request names the page's
// own domain), and an Origin header, when present, must be that same host
// and port (a cross-site form or fetch carries the other site's). Clients
// that send neither (curl, scripts) pass.
std::optional<std::string> loopback_request_refusal(const std::string& host_header,
                                                    const std::string& origin_header);

// The bearer token from the `serve:` block: the environment variable it
// names, else the file it names (first line, trailing whitespace removed).
// Empty when neither is set; throws naming the variable or file when it is
// set but empty, unreadable or shorter than 16 characters.
std::string load_access_token(const std::string& token_env, const std::string& token_file);

// Compares in time that depends only on the lengths, not on where the first
// difference is (OpenSSL's CRYPTO_memcmp), so a client cannot find the token
// byte by byte.
bool token_matches(const std::string& expected, const std::string& given);

// The token a request carries: "Authorization: Bearer X", else the
// access_token query parameter (RFC 6750, 2.1 and 2.3).
std::optional<std::string> bearer_token(const std::string& authorization_header,
                                        const std::string& access_token_param);

}  // namespace facectl
