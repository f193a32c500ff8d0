// `facectl serve` as a user starts it: a child process on the default head,
// simulated hardware. It refuses to listen beyond loopback without the flag
// and a token, says where it listens, and stops on SIGTERM with the head at rest.
#include <gtest/gtest.h>
#include <httplib.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/facectl_child.hpp"
#include "tests/support/loopback_udp.hpp"
#include "tests/support/temp_dir.hpp"

namespace facectl {
namespace {

using testing::Child;
using testing::TempDir;
using testing::wait_exit;

std::string read_all(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A runtime file next to the shipped one's folders, with a `serve:` block.
std::string config_with(const TempDir& dir, const std::string& serve_block) {
  const std::string src = std::string(FACECTL_SOURCE_DIR) + "/config/";
  std::string text = read_all(src + "facectl.yaml");
  for (const char* key : {"head: ", "rig: ", "expressions: ", "show: "}) {
    const auto at = text.find(std::string("\n") + key);
    text.insert(at + 1 + std::string(key).size(), src);
  }
  text += "\n" + serve_block + "\n";
  dir.write("facectl.yaml", text);
  return dir.file("facectl.yaml");
}

// systemd's end of Type=notify (sd_notify(3)): a datagram socket whose path
// the service finds in NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const std::string& path) : path_(path) {
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un a{};
    a.sun_family = AF_UNIX;
    std::strncpy(a.sun_path, path.c_str(), sizeof a.sun_path - 1);
    bound_ = fd_ >= 0 && bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
    const timeval timeout{0, 50'000};
    setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  ~NotifySocket() {
    if (fd_ >= 0) close(fd_);
  }
  NotifySocket(const NotifySocket&) = delete;
  NotifySocket& operator=(const NotifySocket&) = delete;

  bool bound() const { return bound_; }
  std::string env() const { return "NOTIFY_SOCKET=" + path_; }

  // Every message received for `seconds`, or until one contains `until`.
  std::vector<std::string> receive(double seconds, const std::string& until = "") {
    std::vector<std::string> got;
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    char buf[4096];
    while (std::chrono::steady_clock::now() < end) {
      const ssize_t n = recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) continue;
      got.emplace_back(buf, static_cast<std::size_t>(n));
      if (!until.empty() && got.back().find(until) != std::string::npos) break;
    }
    return got;
  }

 private:
  std::string path_;
  int fd_ = -1;
  bool bound_ = false;
};

std::string joined(const std::vector<std::string>& messages) {
  std::string all;
  for (const auto& m : messages) all += "[" + m + "] ";
  return all;
}

TEST(ServeProcess, TellsSystemdItIsReadyPetsTheWatchdogAndSaysStopping) {
  TempDir dir;
  const std::string config = config_with(dir, "");
  NotifySocket systemd(dir.file("notify"));
  ASSERT_TRUE(systemd.bound()) << std::strerror(errno);
  Child c = testing::spawn_facectl({"serve", "--config", config, "--listen", "127.0.0.1:0"},
                                   {RLIM_INFINITY, {systemd.env()}});

  const std::vector<std::string> start = systemd.receive(20.0, "READY=1");
  ASSERT_FALSE(start.empty()) << read_all(c.out_path);
  EXPECT_NE(start.back().find("STATUS=IDLE, listening on http://127.0.0.1:"), std::string::npos)
      << joined(start);

  // The loop ticks in IDLE: a ping each 100 ms (WatchdogSec in the unit is far longer).
  const std::vector<std::string> running = systemd.receive(2.0);
  const auto pings = std::count(running.begin(), running.end(), "WATCHDOG=1");
  EXPECT_GE(pings, 5) << joined(running);

  kill(c.pid, SIGTERM);
  const std::vector<std::string> stop = systemd.receive(10.0, "STOPPING=1");
  ASSERT_FALSE(stop.empty());
  EXPECT_EQ(stop.back(), "STOPPING=1") << joined(stop);
  EXPECT_EQ(wait_exit(c), 0) << read_all(c.out_path);
}

// A self-signed certificate for 127.0.0.1 and its key, made by the openssl tool.
void make_certificate(const TempDir& dir, const std::string& stem) {
  const std::string cmd =
      "openssl req -x509 -newkey rsa:2048 -nodes -days 1 -subj /CN=127.0.0.1 "
      "-addext subjectAltName=IP:127.0.0.1 -keyout " +
      dir.file(stem + "-key.pem") + " -out " + dir.file(stem + "-cert.pem") + " >/dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
}

// The port of "listening on <scheme>://127.0.0.1:PORT/" in the child's output, or 0.
int listening_port(const Child& c, const std::string& scheme) {
  const std::regex listening("listening on " + scheme + R"(://127\.0\.0\.1:(\d+)/)");
  std::smatch m;
  std::string out;
  const bool found = testing::wait_until(
      [&] {
        out = read_all(c.out_path);
        return std::regex_search(out, m, listening);
      },
      20.0);
  return found ? std::stoi(m[1]) : 0;
}

TEST(ServeProcess, ServesHttpsWithTheCertificateOfItsConfig) {
  TempDir dir;
  make_certificate(dir, "head");
  // Relative to the runtime file, as every path in it.
  const std::string config =
      config_with(dir, "serve: { tls_cert: head-cert.pem, tls_key: head-key.pem }");
  Child c = testing::spawn_facectl({"serve", "--config", config, "--listen", "127.0.0.1:0"});
  const int port = listening_port(c, "https");
  ASSERT_NE(port, 0) << read_all(c.out_path);

  httplib::SSLClient tls("127.0.0.1", port);
  tls.set_ca_cert_path(dir.file("head-cert.pem").c_str());
  tls.enable_server_certificate_verification(true);
  const auto r = tls.Get("/api/v1/state");
  ASSERT_TRUE(r) << httplib::to_string(r.error());
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(nlohmann::json::parse(r->body)["state"], "IDLE");
  // Plain HTTP gets no answer from an HTTPS listener.
  httplib::Client plain("127.0.0.1", port);
  const auto p = plain.Get("/api/v1/state");
  EXPECT_FALSE(p && p->status == 200);

  kill(c.pid, SIGTERM);
  EXPECT_EQ(wait_exit(c), 0) << read_all(c.out_path);
}

TEST(ServeProcess, RefusesHalfATlsPairAMissingFileAndAKeyThatIsNotTheCertificates) {
  TempDir dir;
  make_certificate(dir, "a");
  make_certificate(dir, "b");
  Child c = testing::spawn_facectl({"serve", "--config",
                                    config_with(dir, "serve: { tls_cert: a-cert.pem }"), "--listen",
                                    "127.0.0.1:0"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_NE(read_all(c.out_path).find("expected tls_cert together with tls_key"), std::string::npos)
      << read_all(c.out_path);

  c = testing::spawn_facectl(
      {"serve", "--config", config_with(dir, "serve: { tls_cert: a-cert.pem, tls_key: b-key.pem }"),
       "--listen", "127.0.0.1:0"});
  EXPECT_EQ(wait_exit(c), 2);
  const std::string out = read_all(c.out_path);
  EXPECT_NE(out.find("cannot use TLS certificate " + dir.file("a-cert.pem") + " with key " +
                     dir.file("b-key.pem")),
            std::string::npos)
      << out;

  c = testing::spawn_facectl(
      {"serve", "--config",
       config_with(dir, "serve: { tls_cert: a-cert.pem, tls_key: missing-key.pem }"), "--listen",
       "127.0.0.1:0"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_NE(read_all(c.out_path)
                .find("cannot read TLS key " + dir.file("missing-key.pem") +
                      ": No such file or directory"),
            std::string::npos)
      << read_all(c.out_path);
}

TEST(ServeProcess, ANonLoopbackAddressNeedsTheFlagAndAToken) {
  TempDir dir;
  const std::string plain = config_with(dir, "");
  Child c = testing::spawn_facectl({"serve", "--config", plain, "--listen", "0.0.0.0:0"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_NE(read_all(c.out_path).find("needs --allow-remote"), std::string::npos)
      << read_all(c.out_path);

  c = testing::spawn_facectl(
      {"serve", "--config", plain, "--listen", "0.0.0.0:0", "--allow-remote"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_NE(read_all(c.out_path).find("needs an access token"), std::string::npos)
      << read_all(c.out_path);

  c = testing::spawn_facectl({"serve", "--config", plain, "--listen", "nowhere"});
  EXPECT_EQ(wait_exit(c), 2);
  EXPECT_NE(read_all(c.out_path).find("expected ADDR:PORT"), std::string::npos);
}

TEST(ServeProcess, ServesWithATokenStopsOnSigtermAtRestAndKeepsItsLog) {
  TempDir dir;
  const std::string config = config_with(dir, "serve: { token_env: FACECTL_TEST_TOKEN }");
  const std::string log = dir.file("events.jsonl");
  Child c = testing::spawn_facectl(
      {"serve", "--config", config, "--listen", "0.0.0.0:0", "--allow-remote", "--event-log", log},
      {RLIM_INFINITY, {"FACECTL_TEST_TOKEN=0123456789abcdef-process"}});
  std::smatch m;
  std::string out;
  const std::regex listening(R"(listening on http://0\.0\.0\.0:(\d+)/)");
  ASSERT_TRUE(testing::wait_until(
      [&] {
        out = read_all(c.out_path);
        return std::regex_search(out, m, listening);
      },
      20.0))
      << out;
  EXPECT_NE(out.find("warning: plain HTTP beyond loopback"), std::string::npos) << out;
  httplib::Client client("127.0.0.1", std::stoi(m[1]));
  EXPECT_EQ(client.Get("/api/v1/state")->status, 401);
  const httplib::Headers auth{{"Authorization", "Bearer 0123456789abcdef-process"}};
  ASSERT_EQ(client.Post("/api/v1/enable", auth, "", "application/json")->status, 200);
  ASSERT_TRUE(testing::wait_until(
      [&] {
        const auto r = client.Get("/api/v1/state", auth);
        return r && nlohmann::json::parse(r->body)["state"] == "RUNNING";
      },
      10.0));

  kill(c.pid, SIGTERM);
  EXPECT_EQ(wait_exit(c), 0) << read_all(c.out_path);
  const std::string events = read_all(log);
  EXPECT_NE(events.find("RUNNING -> STOPPING: shutdown requested"), std::string::npos) << events;
  EXPECT_NE(events.find("STOPPING -> IDLE"), std::string::npos) << events;
  EXPECT_NE(events.find(R"("text":"stopped in IDLE")"), std::string::npos) << events;
}

TEST(ServeProcess, TakesOscFromAnIndependentSenderAndLogsWhatItCounted) {
  TempDir dir;
  const std::uint16_t port = testing::free_udp_port();
  const std::string config = config_with(dir, "osc: { port: " + std::to_string(port) + " }");
  const std::string log = dir.file("events.jsonl");
  Child c = testing::spawn_facectl(
      {"serve", "--config", config, "--listen", "127.0.0.1:0", "--event-log", log});
  const std::string on = "OSC control on udp 127.0.0.1:" + std::to_string(port);
  ASSERT_TRUE(
      testing::wait_until([&] { return read_all(log).find(on) != std::string::npos; }, 60.0))
      << read_all(c.out_path);
  const std::string peer =
      std::string(FACECTL_SOURCE_DIR) + "/tests/firmware-host/inputs/peers/osc_peer.py";
  ASSERT_EQ(
      std::system(("python3 " + peer + " send " + std::to_string(port) + " > /dev/null").c_str()),
      0);
  ASSERT_TRUE(testing::wait_until(
      [&] { return read_all(log).find("neck_pan_deg=10") != std::string::npos; }, 20.0))
      << read_all(log);

  kill(c.pid, SIGTERM);
  EXPECT_EQ(wait_exit(c), 0) << read_all(c.out_path);
  const std::string events = read_all(log);
  EXPECT_NE(events.find("hold expression joy at 0.5"), std::string::npos) << events;
  EXPECT_NE(events.find("5 datagrams, 5 messages, 3 applied, 1 refused, 1 malformed, "
                        "1 to unknown addresses"),
            std::string::npos)
      << events;
  EXPECT_NE(events.find("refused: /facectl/signal/jaw_pitch_deg: expected -4..18"),
            std::string::npos)
      << events;
}

}  // namespace
}  // namespace facectl
