// The HTTP side of `facectl serve`, through a real HTTP client on loopback:
// bad requests get a 4xx with a reason and leave the head as it was, the
// access token guards every path, and the telemetry stream keeps its rate.
#include "firmware-host/serve/http_api.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "control/face/reduced_face_model.hpp"
#include "tests/firmware-host/serve/served_head.hpp"

namespace facectl {
namespace {

using nlohmann::json;
using testing::ServedHead;

constexpr const char* kToken = "0123456789abcdef-token";

// The API of a ServedHead on a free loopback port, with or without a token.
class ServedApi {
 public:
  explicit ServedApi(std::string token = "",
                     const std::string& config = std::string(FACECTL_SOURCE_DIR) +
                                                 "/config/facectl.yaml")
      : head_(config) {
    HttpApi::Options o;
    o.listen = parse_listen_address("127.0.0.1:0");
    o.token = std::move(token);
    o.console_dir = head_.shows().path();  // any folder: the static files' mount
    api_ = std::make_unique<HttpApi>(head_.service(), o);
    api_->bind();
    thread_ = std::thread([this] { api_->serve(); });
    client_ = std::make_unique<httplib::Client>("http://" + api_->address());
    // Long enough for the first request that proves the jog ranges in a sanitizer build.
    client_->set_read_timeout(60, 0);
  }
  ~ServedApi() {
    api_->stop();
    thread_.join();
  }

  httplib::Client& client() { return *client_; }
  ServedHead& head() { return head_; }
  std::string address() const { return api_->address(); }

 private:
  ServedHead head_;
  std::unique_ptr<HttpApi> api_;
  std::thread thread_;
  std::unique_ptr<httplib::Client> client_;
};

json body(const httplib::Result& r) {
  return json::parse(r->body);
}

TEST(HttpApi, StateNamesTheSafetyState) {
  ServedApi api;
  const auto r = api.client().Get("/api/v1/state");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(body(r)["state"], "IDLE");
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/json");
}

TEST(HttpApi, WithoutATokenRefusesOtherSitesPagesAndLeavesTheHeadIdle) {
  ServedApi api;
  // A cross-site POST from a page open in a browser on the controller.
  auto r = api.client().Post("/api/v1/enable", {{"Origin", "http://attacker.example"}}, "",
                             "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_NE(body(r)["error"].get<std::string>().find("Origin http://attacker.example"),
            std::string::npos);
  // A rebound name: the request reaches 127.0.0.1 but names the page's host.
  r = api.client().Post("/api/v1/enable", {{"Host", "attacker.example"}}, "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403);
  EXPECT_EQ(api.head().service().state(), SafetyState::kIdle);
  // The console's own requests carry its origin.
  r = api.client().Post("/api/v1/enable", {{"Origin", "http://" + api.address()}}, "",
                        "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_TRUE(api.head().wait_for(SafetyState::kRunning));
}

TEST(HttpApi, EnableAndDisableMoveTheStateMachine) {
  ServedApi api;
  auto r = api.client().Post("/api/v1/enable", "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  ASSERT_TRUE(api.head().wait_for(SafetyState::kRunning));
  r = api.client().Post("/api/v1/disable", "", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  ASSERT_TRUE(api.head().wait_for(SafetyState::kIdle));
}

TEST(HttpApi, BadRequestsGetAReasonAndChangeNothing) {
  ServedApi api;
  ASSERT_EQ(
      api.client().Post("/api/v1/expression/hold", R"({"name":"joy"})", "application/json")->status,
      200);
  struct Case {
    const char* path;
    const char* body;
    int status;
    const char* says;
  };
  for (const Case& c : {
           Case{"/api/v1/enable", "{bad", 400, "malformed JSON"},
           Case{"/api/v1/show/play", R"({"nam":"demo"})", 400, "expected {\"name\""},
           Case{"/api/v1/show/play", R"({"name":"nope"})", 404, "no show 'nope'"},
           Case{"/api/v1/show/play", R"({"name":"../../etc/passwd"})", 404, "not a show name"},
           Case{"/api/v1/expression/hold", R"({"name":"joy","weight":3})", 422, "weight"},
           Case{"/api/v1/expression/hold", R"({"name":"joy","weight":"1"})", 400, "weight"},
           Case{"/api/v1/pose", "{", 400, "malformed JSON"},
           // nlohmann throws out_of_range, not parse_error, for this one.
           Case{"/api/v1/pose", R"({"signals":{"jaw_pitch_deg":1e999}})", 400, "malformed JSON"},
           Case{"/api/v1/pose", R"({"signals":{"jaw_pitch_deg":30}})", 422,
                "jaw_pitch_deg: expected -4..18, found 30"},
           Case{"/api/v1/pose", R"({"signals":{"jaw_yaw_deg":-6}})", 422, "jaw_yaw_deg"},
           Case{"/api/v1/pose", R"({"signals":{"no_such_muscle":0.5}})", 422, "no such signal"},
           Case{"/api/v1/pose", R"({"signals":{"jaw_pitch_deg":"6"}})", 422, "expected a number"},
           Case{"/api/v1/reset", R"({"enable":"yes"})", 400, "enable: expected true or false"},
           Case{"/api/v1/launch", "{}", 404, "no such resource: POST /api/v1/launch"},
       }) {
    const auto r = api.client().Post(c.path, c.body, "application/json");
    ASSERT_TRUE(r) << c.path;
    EXPECT_EQ(r->status, c.status) << c.path << " " << c.body << ": " << r->body;
    EXPECT_NE(body(r)["error"].get<std::string>().find(c.says), std::string::npos)
        << c.path << " " << c.body << ": " << r->body;
  }
  const auto r = api.client().Get("/api/v1/telemetry?rate_hz=1000");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(r->body.find("rate_hz"), std::string::npos);
  // The head was left alone: IDLE, still holding the expression.
  EXPECT_EQ(api.head().service().state(), SafetyState::kIdle);
  EXPECT_EQ(api.head().service().director().status().name, "joy");
}

TEST(HttpApi, AResetDoesNotEnableUnlessAskedTo) {
  ServedApi api;
  SimHardware& sim = *api.head().session().head.sim;
  ASSERT_EQ(api.client().Post("/api/v1/enable", "", "application/json")->status, 200);
  ASSERT_TRUE(api.head().wait_for(SafetyState::kRunning));
  sim.io.press_estop();
  ASSERT_TRUE(api.head().wait_for(SafetyState::kEstop));
  sim.io.release_estop();
  ASSERT_EQ(api.client().Post("/api/v1/reset", "", "application/json")->status, 200);
  ASSERT_TRUE(api.head().wait_for(SafetyState::kIdle));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_EQ(api.head().service().state(), SafetyState::kIdle);  // motion needs its own enable
}

TEST(HttpApi, EveryPathNeedsTheTokenWhenOneIsSet) {
  ServedApi api(kToken);
  for (const char* path :
       {"/api/v1/state", "/api/v1/rig", "/api/v1/face/geometry", "/", "/index.html", "/nope"}) {
    const auto r = api.client().Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 401) << path;
    EXPECT_EQ(r->get_header_value("WWW-Authenticate"), R"(Bearer realm="facectl")");
  }
  const auto enable = api.client().Post("/api/v1/enable", "", "application/json");
  ASSERT_TRUE(enable);
  EXPECT_EQ(enable->status, 401);
  EXPECT_EQ(api.head().service().state(), SafetyState::kIdle);

  const auto wrong = api.client().Get("/api/v1/state", {{"Authorization", "Bearer nope"}});
  EXPECT_EQ(wrong->status, 401);
  const auto prefix =
      api.client().Get("/api/v1/state", {{"Authorization", std::string("Bearer ") + kToken + "x"}});
  EXPECT_EQ(prefix->status, 401);
  const auto right =
      api.client().Get("/api/v1/state", {{"Authorization", std::string("Bearer ") + kToken}});
  EXPECT_EQ(right->status, 200);
  const auto param = api.client().Get(std::string("/api/v1/state?access_token=") + kToken);
  EXPECT_EQ(param->status, 200);
  const auto geometry = api.client().Get("/api/v1/face/geometry",
                                         {{"Authorization", std::string("Bearer ") + kToken}});
  EXPECT_EQ(geometry->status, 200);
}

TEST(HttpApi, TheRigDescribesActuatorsAndSignalsInYamlUnits) {
  ServedApi api;
  const json rig = body(api.client().Get("/api/v1/rig"));
  const ControllerModel& m = api.head().session().head.model();
  ASSERT_EQ(rig["actuators"].size(), m.actuators.size());
  ASSERT_EQ(rig["signals"].size(), m.layout.size());
  for (const json& s : rig["signals"]) {
    if (s["key"] == "jaw_pitch_deg") {
      EXPECT_NEAR(s["min"].get<double>(), -4.0, 1e-9);
      EXPECT_NEAR(s["max"].get<double>(), 18.0, 1e-9);
    }
  }
  for (const json& a : rig["actuators"]) {
    EXPECT_LE(a["min"].get<double>(), a["soft_min"].get<double>()) << a;
    EXPECT_LT(a["soft_min"].get<double>(), a["soft_max"].get<double>()) << a;
    EXPECT_LE(a["soft_max"].get<double>(), a["max"].get<double>()) << a;
  }
}

// The rig names each actuator's jog range, and POST /api/v1/jog keeps to
// exactly that range: its ends are accepted, a step past them is refused.
TEST(HttpApi, TheRigGivesTheJogRangeThatJogKeepsTo) {
  ServedApi api;
  const json rig = body(api.client().Get("/api/v1/rig"));
  ASSERT_EQ(api.client().Post("/api/v1/enable", "", "application/json")->status, 200);
  ASSERT_TRUE(api.head().wait_for(SafetyState::kRunning));
  ASSERT_EQ(api.client().Post("/api/v1/jog/start", "", "application/json")->status, 200);
  const auto jog = [&](const json& a, double position) {
    const json request{{"actuator", a["name"]}, {"position", position}};
    return api.client().Post("/api/v1/jog", request.dump(), "application/json")->status;
  };
  int jogable = 0;
  for (const json& a : rig["actuators"]) {
    ASSERT_TRUE(a.contains("jog")) << a;
    const std::string name = a["name"].get<std::string>();
    if (name.starts_with("jaw_")) {  // the mandible's struts: refused, so no range
      EXPECT_TRUE(a["jog"].is_null()) << a;
      EXPECT_EQ(jog(a, a["rest"].get<double>()), 409) << a;
      continue;
    }
    ASSERT_TRUE(a["jog"].is_object()) << a;
    ++jogable;
    const double lo = a["jog"]["min"].get<double>();
    const double hi = a["jog"]["max"].get<double>();
    EXPECT_LE(a["soft_min"].get<double>(), lo + 1e-9) << a;
    EXPECT_LT(lo, hi) << a;
    EXPECT_LE(hi, a["soft_max"].get<double>() + 1e-9) << a;
    EXPECT_EQ(jog(a, lo - 0.01), 422) << a;
    EXPECT_EQ(jog(a, hi + 0.01), 422) << a;
    EXPECT_EQ(jog(a, hi), 200) << a;
    EXPECT_EQ(jog(a, lo), 200) << a;
    if (name == "lip_pucker") {    // soft range -40..40 deg; no admissible face takes
      EXPECT_NEAR(lo, 0.0, 1e-6);  // it below 0 or past 35 deg
      EXPECT_NEAR(hi, 35.0, 1e-6);
    }
  }
  EXPECT_EQ(jogable, static_cast<int>(rig["actuators"].size()) - 3);
}

TEST(HttpApi, ThePoseHoldsTheGivenSignalsOverNeutral) {
  ServedApi api;
  const auto r =
      api.client().Post("/api/v1/pose", R"({"signals":{"jaw_pitch_deg":6}})", "application/json");
  ASSERT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(body(r)["source"]["kind"], "pose");
  const std::size_t pitch = api.head().session().head.model().layout.jaw_pitch();
  // After the crossfade the tick's face command carries the pose (in SI).
  ASSERT_TRUE(testing::wait_until(
      [&] {
        TelemetryRecord rec;
        api.head().service().latest(rec);
        return std::abs(rec.face[pitch] - 6.0 * M_PI / 180.0) < 1e-3;
      },
      3.0));
}

TEST(HttpApi, TheTelemetryStreamSendsJsonEventsAtTheChosenRate) {
  ServedApi api;
  httplib::Client c("http://" + api.address());
  std::vector<std::string> events;
  std::string pending;
  const auto start = std::chrono::steady_clock::now();
  c.Get("/api/v1/telemetry?rate_hz=50", [&](const char* data, std::size_t n) {
    pending.append(data, n);
    for (std::size_t end; (end = pending.find("\n\n")) != std::string::npos;) {
      events.push_back(pending.substr(0, end));
      pending.erase(0, end + 2);
    }
    return events.size() < 25;  // then hang up
  });
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_GE(events.size(), 25u);
  // 25 events at 50 Hz take 0.5 s; a stream that ignored the rate would be far quicker.
  EXPECT_GT(took, 0.4);
  const ControllerModel& m = api.head().session().head.model();
  for (const std::string& e : events) {
    ASSERT_EQ(e.rfind("data: ", 0), 0u) << e;
    const json j = json::parse(e.substr(6));
    EXPECT_EQ(j["commands"].size(), m.actuators.size());
    EXPECT_EQ(j["face"].size(), m.layout.size());
    EXPECT_EQ(j["state"], "IDLE");
  }
}

TEST(HttpApi, TheFaceGeometryIsTheReducedModelsPointsAndTheSkin) {
  ServedApi api;
  const auto r = api.client().Get("/api/v1/face/geometry");
  ASSERT_EQ(r->status, 200) << r->body;
  const json g = body(r);
  const auto& reduced = *api.head().session().head.model().mapping.reduced;
  ASSERT_EQ(g["landmarks"].size(), reduced.control_points.size());
  EXPECT_EQ(g["landmarks"][0]["name"], reduced.control_points[0]);
  EXPECT_EQ(g["landmarks"][0]["position_mm"].size(), 3u);
  const std::size_t vertices = g["skin"]["vertices_mm"].size() / 3;
  EXPECT_GT(vertices, 400u);
  EXPECT_EQ(g["weights"].size(), vertices * reduced.control_points.size());
}

// A head without reduced_face.txt, on a rig that reads no control points: no geometry,
// and the console keeps its schematic face.
TEST(HttpApi, TheFaceGeometryIs404ForAHeadWithoutAReducedModel) {
  testing::TempDir dir;
  ServedApi api("", testing::copied_head_config(dir, testing::kTermsOnlyRig, false));
  const auto r = api.client().Get("/api/v1/face/geometry");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 404);
  EXPECT_NE(body(r)["error"].get<std::string>().find("reduced face model"), std::string::npos);
  // Its telemetry has no landmarks_mm.
  httplib::Client c("http://" + api.address());
  std::string first;
  c.Get("/api/v1/telemetry?rate_hz=50", [&](const char* data, std::size_t n) {
    first.append(data, n);
    return first.find("\n\n") == std::string::npos;
  });
  ASSERT_EQ(first.rfind("data: ", 0), 0u) << first;
  EXPECT_FALSE(json::parse(first.substr(6, first.find("\n\n") - 6)).contains("landmarks_mm"));
}

// Each telemetry frame carries the control points' displacements (mm) that face::evaluate
// gives for the frame's face signals: a smile moves the left lip corner up and out.
TEST(HttpApi, TelemetryCarriesTheReducedModelsDisplacements) {
  ServedApi api;
  const ControllerModel& m = api.head().session().head.model();
  const std::size_t zyg = *m.layout.find("zygomaticus_major_l");
  auto frame = [&] {
    httplib::Client c("http://" + api.address());
    std::string text;
    c.Get("/api/v1/telemetry?rate_hz=50", [&](const char* data, std::size_t n) {
      text.append(data, n);
      return text.find("\n\n") == std::string::npos;
    });
    return json::parse(text.substr(6, text.find("\n\n") - 6));
  };
  const json neutral = frame();
  ASSERT_EQ(
      api.client()
          .Post("/api/v1/pose", R"({"signals":{"zygomaticus_major_l":1}})", "application/json")
          ->status,
      200);
  ASSERT_TRUE(testing::wait_until(
      [&] {
        TelemetryRecord rec;
        api.head().service().latest(rec);
        return std::abs(rec.face[zyg] - 1.0) < 1e-6;
      },
      3.0));
  const json smile = frame();

  const auto& reduced = *m.mapping.reduced;
  ASSERT_EQ(smile["landmarks_mm"].size(), 3 * reduced.control_points.size());
  // The frame's signals in SI, through the reduced model (muscles first, head.yaml order).
  std::vector<double> contractions;
  for (std::size_t k = 0; k < reduced.muscles.size(); ++k)
    contractions.push_back(smile["face"][k].get<double>());
  const auto yaml = [&](std::size_t i) {
    return smile["face"][i].get<double>() * yaml_to_si(m.layout.signal(i).kind);
  };
  face::ReducedFaceWorkspace w = face::make_reduced_workspace(reduced);
  std::vector<double> expected(3 * reduced.control_points.size());
  face::ReducedInput in{contractions, yaml(m.layout.jaw_pitch()), yaml(m.layout.jaw_yaw()),
                        yaml(m.layout.jaw_protrusion())};
  in.eyelid_closure[0] = yaml(m.layout.eyelid_closure(0));
  in.eyelid_closure[1] = yaml(m.layout.eyelid_closure(1));
  face::evaluate(reduced, w, in, expected);
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(smile["landmarks_mm"][i].get<double>(), expected[i] * 1e3, 2e-4) << i;

  const std::size_t corner =
      std::find(reduced.control_points.begin(), reduced.control_points.end(), "fdp_8_3") -
      reduced.control_points.begin();
  const auto moved = [&](std::size_t axis) {
    return smile["landmarks_mm"][3 * corner + axis].get<double>() -
           neutral["landmarks_mm"][3 * corner + axis].get<double>();
  };
  EXPECT_GT(moved(0), 0.5);  // out: +x is the head's left
  EXPECT_GT(moved(1), 0.5);  // up
}

// The whole answer to `request`, sent as it is over a plain TCP connection.
std::string raw_exchange(int port, const std::string& request) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string answer;
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
      write(fd, request.data(), request.size()) == static_cast<ssize_t>(request.size())) {
    char buf[4096];
    for (ssize_t n; (n = read(fd, buf, sizeof buf)) > 0;)
      answer.append(buf, static_cast<std::size_t>(n));
  }
  close(fd);
  return answer;
}

TEST(HttpApi, APostWithoutContentLengthIsToldWhy) {
  ServedApi api;
  const int port = std::stoi(api.address().substr(api.address().rfind(':') + 1));
  // As `curl -X POST` sends it: no body and no Content-Length.
  const std::string answer = raw_exchange(
      port, "POST /api/v1/enable HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << answer;
  EXPECT_NE(answer.find("Content-Length header"), std::string::npos) << answer;
  EXPECT_EQ(api.head().service().state(), SafetyState::kIdle);
}

}  // namespace
}  // namespace facectl
