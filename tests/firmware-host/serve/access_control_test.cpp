// Who may talk to `facectl serve`: the listen address and the bearer token.
#include "firmware-host/serve/access_control.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <stdexcept>

#include "tests/firmware-host/serve/served_head.hpp"

namespace facectl {
namespace {

TEST(ListenAddress, TellsLoopbackFromTheRest) {
  EXPECT_TRUE(parse_listen_address("127.0.0.1:8080").loopback);
  EXPECT_TRUE(parse_listen_address("127.1.2.3:80").loopback);
  EXPECT_TRUE(parse_listen_address("localhost:8080").loopback);
  EXPECT_TRUE(parse_listen_address("[::1]:8080").loopback);
  EXPECT_FALSE(parse_listen_address("0.0.0.0:8080").loopback);
  EXPECT_FALSE(parse_listen_address("192.168.1.20:8080").loopback);
  EXPECT_FALSE(parse_listen_address("[::]:8080").loopback);
  const ListenAddress a = parse_listen_address("[::1]:9000");
  EXPECT_EQ(a.host, "::1");
  EXPECT_EQ(a.port, 9000);
}

TEST(ListenAddress, RefusesWhatIsNotAnAddressAndPort) {
  for (const char* bad : {"", "8080", ":8080", "127.0.0.1", "127.0.0.1:", "127.0.0.1:65536",
                          "127.0.0.1:-1", "127.0.0.1:80x", "example.com:80", "[::1]8080"}) {
    EXPECT_THROW(parse_listen_address(bad), std::invalid_argument) << bad;
  }
}

TEST(LoopbackRequest, PassesLoopbackHostsAndTheirOwnOrigin) {
  for (const char* host :
       {"127.0.0.1:8080", "localhost:8080", "LOCALHOST", "[::1]:8080", "127.1.2.3:80", ""}) {
    EXPECT_EQ(loopback_request_refusal(host, ""), std::nullopt) << host;
  }
  EXPECT_EQ(loopback_request_refusal("127.0.0.1:8080", "http://127.0.0.1:8080"), std::nullopt);
  EXPECT_EQ(loopback_request_refusal("localhost:8443", "https://localhost:8443"), std::nullopt);
}

TEST(LoopbackRequest, RefusesARebindingHostAndAnotherSitesOrigin) {
  // DNS rebinding: the page's own name, resolved to 127.0.0.1.
  const auto rebound = loopback_request_refusal("attacker.example:8080", "");
  ASSERT_TRUE(rebound);
  EXPECT_NE(rebound->find("Host attacker.example:8080"), std::string::npos) << *rebound;
  EXPECT_TRUE(loopback_request_refusal("192.168.1.20:8080", ""));
  // A cross-site form or fetch from a page in the controller's browser.
  for (const char* origin :
       {"http://attacker.example", "http://127.0.0.1:9999", "null", "http://localhost:8080"}) {
    const auto refused = loopback_request_refusal("127.0.0.1:8080", origin);
    ASSERT_TRUE(refused) << origin;
    EXPECT_NE(refused->find(std::string("Origin ") + origin), std::string::npos) << *refused;
  }
}

TEST(AccessToken, ComparesWholeTokensOnly) {
  EXPECT_TRUE(token_matches("0123456789abcdef", "0123456789abcdef"));
  EXPECT_FALSE(token_matches("0123456789abcdef", "0123456789abcdeF"));
  EXPECT_FALSE(token_matches("0123456789abcdef", "0123456789abcde"));
  EXPECT_FALSE(token_matches("0123456789abcdef", "0123456789abcdef0"));
  EXPECT_FALSE(token_matches("0123456789abcdef", ""));
}

TEST(AccessToken, ComesFromTheHeaderOrTheQueryParameter) {
  EXPECT_EQ(bearer_token("Bearer abc", ""), "abc");
  EXPECT_EQ(bearer_token("bearer abc", ""), "abc");  // the scheme is case-insensitive
  EXPECT_EQ(bearer_token("", "abc"), "abc");
  EXPECT_EQ(bearer_token("Bearer abc", "def"), "abc");
  EXPECT_EQ(bearer_token("Basic abc", ""), std::nullopt);
  EXPECT_EQ(bearer_token("", ""), std::nullopt);
}

TEST(AccessToken, LoadsFromTheEnvironmentOrAFileAndRefusesShortOnes) {
  EXPECT_EQ(load_access_token("", ""), "");
  setenv("FACECTL_TEST_TOKEN", "0123456789abcdef", 1);
  EXPECT_EQ(load_access_token("FACECTL_TEST_TOKEN", ""), "0123456789abcdef");
  setenv("FACECTL_TEST_TOKEN", "short", 1);
  EXPECT_THROW(load_access_token("FACECTL_TEST_TOKEN", ""), std::runtime_error);
  unsetenv("FACECTL_TEST_TOKEN");
  EXPECT_THROW(load_access_token("FACECTL_TEST_TOKEN", ""), std::runtime_error);

  testing::TempDir dir;
  dir.write("token", "fedcba9876543210xyz \n");
  EXPECT_EQ(load_access_token("", dir.file("token")), "fedcba9876543210xyz");
  EXPECT_THROW(load_access_token("", dir.file("absent")), std::runtime_error);
}

}  // namespace
}  // namespace facectl
