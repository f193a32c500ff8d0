#include "firmware-host/serve/access_control.hpp"

#include <arpa/inet.h>
#include <openssl/crypto.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

#include "firmware-host/config/ipv4_cidr.hpp"

namespace facectl {

bool is_loopback_name(const std::string& host) {
  std::string h = host;
  std::transform(h.begin(), h.end(), h.begin(), [](unsigned char c) { return std::tolower(c); });
  in6_addr v6{};
  if (h == "localhost") return true;
  if (const auto v4 = parse_ipv4_address(h)) return kIpv4Loopback.contains(*v4);
  return inet_pton(AF_INET6, h.c_str(), &v6) == 1 && IN6_IS_ADDR_LOOPBACK(&v6);
}

namespace {

// "host:port", "[v6]:port" or "host" -> host.
std::string host_of(const std::string& authority) {
  if (!authority.empty() && authority.front() == '[') {
    const auto close = authority.find(']');
    return close == std::string::npos ? authority : authority.substr(1, close - 1);
  }
  const auto colon = authority.rfind(':');
  return colon == std::string::npos ? authority : authority.substr(0, colon);
}

bool same_text_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

}  // namespace

std::optional<std::string> loopback_request_refusal(const std::string& host_header,
                                                    const std::string& origin_header) {
  if (!host_header.empty() && !is_loopback_name(host_of(host_header))) {
    return "Host " + host_header +
           " does not name this computer's loopback: a tokenless controller answers only "
           "requests to localhost, 127.0.0.1 or [::1] (a page that rebinds its own name to "
           "127.0.0.1 cannot reach it); configure a token to be reached by another name";
  }
  if (origin_header.empty()) return std::nullopt;
  std::string_view origin = origin_header;
  for (std::string_view scheme : {"http://", "https://"}) {
    if (origin.starts_with(scheme)) origin.remove_prefix(scheme.size());
  }
  if (host_header.empty() || !same_text_ignoring_case(origin, host_header)) {
    return "Origin " + origin_header + " is not this server (" + host_header +
           "): a tokenless controller refuses requests from another site's pages";
  }
  return std::nullopt;
}

ListenAddress parse_listen_address(const std::string& text) {
  ListenAddress a;
  std::string port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string::npos || close + 1 >= text.size() || text[close + 1] != ':') {
      throw std::invalid_argument("expected [IPv6]:PORT, found '" + text + "'");
    }
    a.host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0) {
      throw std::invalid_argument("expected ADDR:PORT, found '" + text + "'");
    }
    a.host = text.substr(0, colon);
    port = text.substr(colon + 1);
  }
  char* end = nullptr;
  const long p = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || p < 0 || p > 65535) {
    throw std::invalid_argument("expected a port in 0..65535 (0: any free port), found '" + port +
                                "'");
  }
  a.port = static_cast<int>(p);
  in_addr v4{};
  in6_addr v6{};
  if (a.host == "localhost") {
    a.host = "127.0.0.1";
  } else if (inet_pton(AF_INET, a.host.c_str(), &v4) != 1 &&
             inet_pton(AF_INET6, a.host.c_str(), &v6) != 1) {
    throw std::invalid_argument("expected an IPv4 or [IPv6] address, found '" + a.host + "'");
  }
  a.loopback = is_loopback_name(a.host);
  return a;
}

std::string load_access_token(const std::string& token_env, const std::string& token_file) {
  std::string token;
  std::string from;
  if (!token_env.empty()) {
    const char* v = std::getenv(token_env.c_str());
    if (v == nullptr) throw std::runtime_error("serve.token_env: $" + token_env + " is not set");
    token = v;
    from = "$" + token_env;
  } else if (!token_file.empty()) {
    std::ifstream in(token_file);
    if (!in || !std::getline(in, token)) {
      throw std::runtime_error("serve.token_file: cannot read a token from " + token_file);
    }
    from = token_file;
  } else {
    return {};
  }
  while (!token.empty() && (token.back() == '\r' || token.back() == ' ' || token.back() == '\t')) {
    token.pop_back();
  }
  if (token.size() < 16) {
    throw std::runtime_error("access token in " + from +
                             ": expected at least 16 characters, found " +
                             std::to_string(token.size()));
  }
  return token;
}

bool token_matches(const std::string& expected, const std::string& given) {
  // OpenSSL's comparison reads every byte whatever they hold; only the
  // length, which is not secret, decides early.
  return expected.size() == given.size() &&
         CRYPTO_memcmp(expected.data(), given.data(), expected.size()) == 0;
}

std::optional<std::string> bearer_token(const std::string& authorization_header,
                                        const std::string& access_token_param) {
  // The scheme's name is case-insensitive (RFC 7235, 2.1).
  constexpr std::string_view kScheme = "bearer ";
  const std::string_view h = authorization_header;
  if (h.size() > kScheme.size() &&
      std::equal(kScheme.begin(), kScheme.end(), h.begin(),
                 [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); })) {
    return authorization_header.substr(kScheme.size());
  }
  if (!access_token_param.empty()) return access_token_param;
  return std::nullopt;
}

}  // namespace facectl
