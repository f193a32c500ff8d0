// The runtime file's `fap_stream:` block and the IPv4 networks of its allow
// list: beyond loopback only with allow_remote, every error at its line.
#include <gtest/gtest.h>

#include <string>

#include "firmware-host/config/ipv4_cidr.hpp"
#include "firmware-host/config/runtime_config.hpp"
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

TEST(FapStreamConfig, DefaultsToLoopbackOnly) {
  TempFile f(kRequired + "fap_stream: { port: 5005 }\n");
  const RuntimeConfig cfg = load_runtime_config(f.path());
  ASSERT_TRUE(cfg.fap_stream);
  EXPECT_EQ(cfg.fap_stream->bind_address, "127.0.0.1");
  EXPECT_EQ(cfg.fap_stream->port, 5005);
  EXPECT_FALSE(cfg.fap_stream->allow_remote);
  EXPECT_EQ(cfg.fap_stream->allow, std::vector<Ipv4Cidr>{kIpv4Loopback});
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
  EXPECT_EQ(cfg.fap_stream->allow, std::vector<Ipv4Cidr>{*parse_ipv4_cidr("192.168.1.0/24")});
}

TEST(FapStreamConfig, AllowedSendersAreCheckedAtTheirLine) {
  EXPECT_EQ(error_of("fap_stream:\n  allow:\n    - 127.0.0.1\n    - 10.0.0.0/8\n"),
            "FILE:7:7: fap_stream.allow[1]: expected senders within loopback (127.0.0.0/8), or "
            "allow_remote: true to go beyond loopback, found '10.0.0.0/8'");
  EXPECT_EQ(error_of("fap_stream:\n  allow: [127.0.0.1/33]\n"),
            "FILE:5:11: fap_stream.allow[0]: expected an IPv4 address or network (a.b.c.d or "
            "a.b.c.d/prefix), found '127.0.0.1/33'");
  EXPECT_EQ(error_of("fap_stream:\n  allow: []\n"),
            "FILE:5:10: fap_stream.allow: expected at least one address or network, found a "
            "sequence");
  EXPECT_NE(error_of("fap_stream: { max_peers: 0 }\n").find("fap_stream.max_peers: expected"),
            std::string::npos);
}

}  // namespace
}  // namespace facectl
