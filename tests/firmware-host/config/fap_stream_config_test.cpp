// The runtime file's `fap_stream:` block and the IPv4 networks of its allow
// list: beyond loopback only with allow_remote, every error at its line.
#include <gtest/gtest.h>

#include <string>

#include "firmware-host/config/ipv4_cidr.hpp"
#include "firmware-host/config/runtime_config.hpp"
#include "firmware-host/config/udp_sender_rule.hpp"
#include "tests/support/temp_file.hpp"

namespace facectl {
namespace {

using testing::TempFile;

const std::string kRequired = "head: h\nrig: r\nexpressions: e\n";

// The error loading a runtime file of kRequired + `block`, with its path as FILE.
std::string error_of(const std::string& block) {
  TempFile f(kRequired + block);
  try {
    load_runtime_config(f.path());
  } catch (const ConfigError& e) {
    std::string msg = e.what();
    if (const auto at = msg.find(f.path()); at != std::string::npos) {
      msg.replace(at, f.path().size(), "FILE");
    }
    return msg;
  }
  return "no error";
}

TEST(Ipv4Cidr, ParsesAddressesAndNetworks) {
  EXPECT_EQ(parse_ipv4_cidr("127.0.0.1"), (Ipv4Cidr{0x7F000001u, 32}));
  EXPECT_EQ(parse_ipv4_cidr("10.1.2.3/8"), (Ipv4Cidr{0x0A000000u, 8}));
  EXPECT_EQ(parse_ipv4_cidr("10.1.2.3/8")->text(), "10.0.0.0/8");
  EXPECT_TRUE(parse_ipv4_cidr("0.0.0.0/0")->contains(0xC0A80101u));
  EXPECT_TRUE(kIpv4Loopback.contains(0x7F010203u));
  EXPECT_FALSE(kIpv4Loopback.contains(0x00000000u)) << "0.0.0.0 is not loopback";
  EXPECT_TRUE(parse_ipv4_cidr("127.0.0.2/31")->within(kIpv4Loopback));
  EXPECT_FALSE(parse_ipv4_cidr("127.0.0.0/7")->within(kIpv4Loopback));
  for (const char* bad :
       {"", "x", "1.2.3", "1.2.3.4/", "1.2.3.4/33", "1.2.3.4/-1", "1.2.3.4/8x", "::1"}) {
    EXPECT_FALSE(parse_ipv4_cidr(bad)) << bad;
  }
}

// A port pins the one sender: every local process sends from 127.0.0.1.
TEST(UdpSenderRule, ParsesAnOptionalPort) {
  const Ipv4Cidr host{0x7F000001u, 32};
  EXPECT_EQ(parse_udp_sender_rule("127.0.0.1"), (UdpSenderRule{host, 0}));
  EXPECT_EQ(parse_udp_sender_rule("127.0.0.1:5005"), (UdpSenderRule{host, 5005}));
  EXPECT_EQ(parse_udp_sender_rule("10.1.2.3/24:65535"),
            (UdpSenderRule{Ipv4Cidr{0x0A010200u, 24}, 65535}));
  EXPECT_EQ(parse_udp_sender_rule("10.1.2.3/24:65535")->text(), "10.1.2.0/24:65535");
  const UdpSenderRule pinned = *parse_udp_sender_rule("127.0.0.1:5005");
  EXPECT_TRUE(pinned.admits(0x7F000001u, 5005));
  EXPECT_FALSE(pinned.admits(0x7F000001u, 5006)) << "another local process";
  EXPECT_FALSE(pinned.admits(0x7F000002u, 5005));
  EXPECT_TRUE(parse_udp_sender_rule("127.0.0.0/8")->admits(0x7F000002u, 5006));
  for (const char* bad : {"127.0.0.1:", "127.0.0.1:0", "127.0.0.1:65536", "127.0.0.1:-1",
                          "127.0.0.1:5x", "127.0.0.1:5005:1", "127.0.0.1/33:5", ":5005"}) {
    EXPECT_FALSE(parse_udp_sender_rule(bad)) << bad;
  }
}

TEST(FapStreamConfig, DefaultsToLoopbackOnly) {
  TempFile f(kRequired + "fap_stream: { port: 5005 }\n");
  const RuntimeConfig cfg = load_runtime_config(f.path());
  ASSERT_TRUE(cfg.fap_stream);
  EXPECT_EQ(cfg.fap_stream->bind_address, "127.0.0.1");
  EXPECT_EQ(cfg.fap_stream->port, 5005);
  EXPECT_FALSE(cfg.fap_stream->allow_remote);
  EXPECT_EQ(cfg.fap_stream->allow, (std::vector<UdpSenderRule>{{kIpv4Loopback, 0}}));
  TempFile none(kRequired);
  EXPECT_FALSE(load_runtime_config(none.path()).fap_stream);
}

TEST(FapStreamConfig, ABindBeyondLoopbackNeedsAllowRemote) {
  EXPECT_EQ(error_of("fap_stream:\n  bind: 0.0.0.0\n"),
            "FILE:5:9: fap_stream.bind: expected a loopback address (127.0.0.0/8), or "
            "allow_remote: true to go beyond loopback, found '0.0.0.0'");
  EXPECT_EQ(error_of("fap_stream:\n  bind: localhost\n"),
            "FILE:5:9: fap_stream.bind: expected an IPv4 address to bind to, found 'localhost'");
  TempFile f(kRequired +
             "fap_stream:\n  bind: 0.0.0.0\n  allow_remote: true\n  allow: [192.168.1.0/24]\n");
  const RuntimeConfig cfg = load_runtime_config(f.path());
  ASSERT_TRUE(cfg.fap_stream);
  EXPECT_EQ(cfg.fap_stream->bind_address, "0.0.0.0");
  EXPECT_EQ(cfg.fap_stream->allow,
            std::vector<UdpSenderRule>{*parse_udp_sender_rule("192.168.1.0/24")});
}

TEST(FapStreamConfig, AllowedSendersAreCheckedAtTheirLine) {
  EXPECT_EQ(error_of("fap_stream:\n  allow:\n    - 127.0.0.1\n    - 10.0.0.0/8\n"),
            "FILE:7:7: fap_stream.allow[1]: expected senders within loopback (127.0.0.0/8), or "
            "allow_remote: true to go beyond loopback, found '10.0.0.0/8'");
  EXPECT_EQ(error_of("fap_stream:\n  allow: [127.0.0.1/33]\n"),
            "FILE:5:11: fap_stream.allow[0]: expected an IPv4 address or network, optionally "
            "with a port (a.b.c.d, a.b.c.d/prefix, a.b.c.d:port or a.b.c.d/prefix:port), found "
            "'127.0.0.1/33'");
  EXPECT_NE(
      error_of("fap_stream:\n  allow: ['127.0.0.1:0']\n").find("FILE:5:11: fap_stream.allow[0]"),
      std::string::npos);
  EXPECT_EQ(error_of("fap_stream:\n  allow: []\n"),
            "FILE:5:10: fap_stream.allow: expected at least one address or network, found a "
            "sequence");
  EXPECT_NE(error_of("fap_stream: { max_peers: 1 }\n").find("fap_stream.max_peers: expected"),
            std::string::npos)
      << "one slot would leave none beside the sender playing";
  EXPECT_NE(error_of("fap_stream: { peer_idle_s: 5 }\n").find("peer_idle_s"), std::string::npos)
      << "gone: a full table evicts instead";
}

TEST(FapStreamConfig, AnAllowedSenderMayPinItsPort) {
  TempFile f(kRequired + "fap_stream:\n  allow:\n    - 127.0.0.1:5005\n");
  const RuntimeConfig cfg = load_runtime_config(f.path());
  ASSERT_TRUE(cfg.fap_stream);
  EXPECT_EQ(cfg.fap_stream->allow, (std::vector<UdpSenderRule>{{{0x7F000001u, 32}, 5005}}));
}

}  // namespace
}  // namespace facectl
