#include "firmware-host/serve/http_api.hpp"

#include <httplib.h>
#include <openssl/err.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>
#include <utility>

#include "firmware-host/serve/api_json.hpp"
#include "firmware-host/serve/face_landmarks.hpp"

namespace facectl {
namespace {

using nlohmann::json;
using Result = HeadService::Result;

constexpr std::size_t kMaxBodyBytes = 64 * 1024;  // no operation needs more
constexpr double kMinStreamHz = 10.0;             // the rates a client may pick
constexpr double kMaxStreamHz = 100.0;

void reply(httplib::Response& res, int status, const json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void reply_error(httplib::Response& res, int status, const std::string& why) {
  reply(res, status, json{{"error", why}});
}

std::string who(const httplib::Request& req) {
  return "api " + req.remote_addr;
}

// The request's JSON body; an empty body is an empty object. Throws
// std::invalid_argument with the parser's position.
json body_json(const httplib::Request& req) {
  if (req.body.empty()) return json::object();
  try {
    return json::parse(req.body);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw std::invalid_argument(std::string("malformed JSON body: ") + e.what());
  }
}

std::string required_name(const json& body) {
  if (!body.is_object() || !body.contains("name") || !body["name"].is_string()) {
    throw std::invalid_argument(R"(expected {"name": "<name>"})");
  }
  return body["name"].get<std::string>();
}

// HTTPS when the options name a certificate and key (cpp-httplib over
// OpenSSL, as Debian builds it), else plain HTTP. Throws naming the files and
// OpenSSL's reason when they do not load or do not match.
std::unique_ptr<httplib::Server> make_server(const HttpApi::Options& o) {
  if (o.tls_cert.empty()) return std::make_unique<httplib::Server>();
  // OpenSSL says only "system lib" for a file it cannot open.
  for (const auto& [what, file] : {std::pair{"certificate", &o.tls_cert}, {"key", &o.tls_key}}) {
    if (::access(file->c_str(), R_OK) != 0) {
      throw std::runtime_error(std::string("cannot read TLS ") + what + " " + *file + ": " +
                               std::strerror(errno));
    }
  }
  ERR_clear_error();
  auto s = std::make_unique<httplib::SSLServer>(o.tls_cert.c_str(), o.tls_key.c_str());
  if (!s->is_valid()) {
    char why[256] = "unknown reason";
    if (const unsigned long e = ERR_peek_last_error(); e != 0) {
      ERR_error_string_n(e, why, sizeof why);
    }
    throw std::runtime_error("cannot use TLS certificate " + o.tls_cert + " with key " + o.tls_key +
                             ": " + why);
  }
  return s;
}

}  // namespace

HttpApi::HttpApi(HeadService& service, Options options)
    : service_(service),
      options_(std::move(options)),
      geometry_(load_face_geometry(*service.head().cfg)),
      server_(make_server(options_)) {
  if (geometry_.geometry) geometry_body_ = face_geometry_json(*geometry_.geometry).dump();
  routes();
}

HttpApi::~HttpApi() {
  stop();
}

void HttpApi::bind() {
  const ListenAddress& a = options_.listen;
  // Port 0: any free port (tests); address() then tells which.
  port_ = a.port == 0 ? server_->bind_to_any_port(a.host) : a.port;
  if (port_ <= 0 || (a.port != 0 && !server_->bind_to_port(a.host, a.port))) {
    throw std::runtime_error("cannot listen on " + a.host + ":" + std::to_string(a.port) +
                             " (in use, or not an address of this machine)");
  }
}

std::string HttpApi::url() const {
  return (options_.tls_cert.empty() ? "http://" : "https://") + address() + "/";
}

std::string HttpApi::address() const {
  const std::string& h = options_.listen.host;
  return (h.find(':') != std::string::npos ? "[" + h + "]" : h) + ":" + std::to_string(port_);
}

void HttpApi::serve() {
  server_->listen_after_bind();
}

void HttpApi::wait_until_serving() const {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!server_->is_running() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void HttpApi::stop() {
  stopping_.store(true);
  if (server_) server_->stop();
}

void HttpApi::routes() {
  httplib::Server& s = *server_;
  s.set_payload_max_length(kMaxBodyBytes);
  s.set_read_timeout(5, 0);
  s.set_write_timeout(5, 0);
  // Each telemetry stream holds a worker; leave room for the operations.
  const auto workers = static_cast<std::size_t>(options_.max_streams) + 16;
  s.new_task_queue = [workers] { return new httplib::ThreadPool(workers); };

  s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    if (options_.token.empty()) {
      const auto refused =
          loopback_request_refusal(req.get_header_value("Host"), req.get_header_value("Origin"));
      if (!refused) return httplib::Server::HandlerResponse::Unhandled;
      reply_error(res, 403, *refused);
      return httplib::Server::HandlerResponse::Handled;
    }
    const auto given =
        bearer_token(req.get_header_value("Authorization"), req.get_param_value("access_token"));
    if (given && token_matches(options_.token, *given)) {
      return httplib::Server::HandlerResponse::Unhandled;
    }
    res.set_header("WWW-Authenticate", R"(Bearer realm="facectl")");
    reply_error(res, 401, given ? "wrong access token" : "this server needs an access token");
    return httplib::Server::HandlerResponse::Handled;
  });
  s.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return;
    if (res.status == 400 && req.method == "POST" && !req.has_header("Content-Length")) {
      reply_error(res, 400, "a POST needs a Content-Length header (an empty body: curl -d '')");
    } else if (res.status == 404) {
      reply_error(res, 404, "no such resource: " + req.method + " " + req.path);
    } else {
      reply_error(res, res.status, "request refused (HTTP " + std::to_string(res.status) + ")");
    }
  });
  s.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr ep) {
        try {
          std::rethrow_exception(ep);
        } catch (const std::invalid_argument& e) {
          reply_error(res, 400, e.what());
        } catch (const std::exception& e) {
          reply_error(res, 500, e.what());
        }
      });

  // Answers an operation's result: 200 with the state, or its refusal.
  auto answer = [this](httplib::Response& res, const Result& r) {
    if (r.status >= 300) return reply_error(res, r.status, r.error);
    reply(res, 200, state_json(service_));
  };

  s.Get("/api/v1/state", [this](const httplib::Request&, httplib::Response& res) {
    reply(res, 200, state_json(service_));
  });
  s.Post("/api/v1/enable", [this, answer](const httplib::Request& req, httplib::Response& res) {
    body_json(req);
    answer(res, service_.enable(who(req)));
  });
  s.Post("/api/v1/disable", [this, answer](const httplib::Request& req, httplib::Response& res) {
    body_json(req);
    answer(res, service_.disable(who(req)));
  });
  s.Post("/api/v1/reset", [this, answer](const httplib::Request& req, httplib::Response& res) {
    const json body = body_json(req);
    // Resetting an e-stop or fault must not itself start motion (ISO 13850):
    // enabling again is asked for explicitly.
    bool enable = false;
    if (body.is_object() && body.contains("enable")) {
      if (!body["enable"].is_boolean())
        throw std::invalid_argument("enable: expected true or false");
      enable = body["enable"].get<bool>();
    }
    answer(res, service_.reset(who(req), enable));
  });
  s.Get("/api/v1/rig", [this](const httplib::Request&, httplib::Response& res) {
    reply(res, 200, rig_json(service_));
  });
  s.Get("/api/v1/face/geometry", [this](const httplib::Request&, httplib::Response& res) {
    if (!geometry_.geometry) return reply_error(res, 404, geometry_.why_not);
    res.set_content(geometry_body_, "application/json");
  });
  s.Get("/api/v1/shows", [this](const httplib::Request&, httplib::Response& res) {
    json shows = json::array();
    for (const auto& l : service_.shows().list()) {
      json item{{"name", l.name}, {"duration_s", l.duration_s}};
      if (!l.error.empty()) item["error"] = l.error;
      shows.push_back(item);
    }
    reply(res, 200, json{{"shows", shows}});
  });
  s.Post("/api/v1/show/play", [this, answer](const httplib::Request& req, httplib::Response& res) {
    answer(res, service_.play(who(req), required_name(body_json(req)), false));
  });
  s.Post("/api/v1/show/queue", [this, answer](const httplib::Request& req, httplib::Response& res) {
    answer(res, service_.play(who(req), required_name(body_json(req)), true));
  });
  s.Post("/api/v1/show/stop", [this, answer](const httplib::Request& req, httplib::Response& res) {
    body_json(req);
    answer(res, service_.stop_show(who(req)));
  });
  s.Get("/api/v1/expressions", [this](const httplib::Request&, httplib::Response& res) {
    json names = json::array();
    for (const auto& [name, pose] : service_.head().cfg->expressions.all()) names.push_back(name);
    reply(res, 200, json{{"expressions", names}});
  });
  s.Post("/api/v1/expression/hold",
         [this, answer](const httplib::Request& req, httplib::Response& res) {
           const json body = body_json(req);
           double weight = 1.0;
           if (body.is_object() && body.contains("weight")) {
             const json& w = body["weight"];
             if (!w.is_number()) {
               throw std::invalid_argument("weight: expected a number, found " + w.dump());
             }
             if (!(w.get<double>() >= 0.0 && w.get<double>() <= 1.0)) {
               return reply_error(res, 422, "weight: expected 0..1, found " + w.dump());
             }
             weight = w.get<double>();
           }
           answer(res, service_.hold_expression(who(req), required_name(body), weight));
         });
  s.Post("/api/v1/pose", [this, answer](const httplib::Request& req, httplib::Response& res) {
    const json body = body_json(req);  // malformed JSON: 400
    std::string summary;
    FaceDirector::Pose pose;
    try {
      pose = parse_pose_request(body, service_.head().model(), summary);
    } catch (const std::invalid_argument& e) {
      return reply_error(res, 422, e.what());
    }
    answer(res, service_.hold_pose(who(req), pose, summary));
  });
  s.Post("/api/v1/jog/start", [this, answer](const httplib::Request& req, httplib::Response& res) {
    body_json(req);
    answer(res, service_.jog_start(who(req)));
  });
  s.Post("/api/v1/jog/stop", [this, answer](const httplib::Request& req, httplib::Response& res) {
    body_json(req);
    answer(res, service_.jog_stop(who(req)));
  });
  s.Post("/api/v1/jog", [this, answer](const httplib::Request& req, httplib::Response& res) {
    const json body = body_json(req);
    if (!body.is_object() || !body.contains("actuator") || !body["actuator"].is_string() ||
        !body.contains("position") || !body["position"].is_number()) {
      throw std::invalid_argument(R"(expected {"actuator": "<name>", "position": <deg or mm>})");
    }
    answer(res, service_.jog(who(req), body["actuator"].get<std::string>(),
                             body["position"].get<double>()));
  });
  s.Get("/api/v1/events", [this](const httplib::Request& req, httplib::Response& res) {
    std::size_t limit = 100;
    if (req.has_param("limit")) {
      const std::string v = req.get_param_value("limit");
      char* end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (v.empty() || *end != '\0' || n < 1 || n > 1000) {
        throw std::invalid_argument("limit: expected 1..1000, found '" + v + "'");
      }
      limit = static_cast<std::size_t>(n);
    }
    reply(res, 200, events_json(service_.log(), limit));
  });
  s.Get("/api/v1/telemetry", [this](const httplib::Request& req, httplib::Response& res) {
    double hz = 20.0;
    if (req.has_param("rate_hz")) {
      const std::string v = req.get_param_value("rate_hz");
      char* end = nullptr;
      hz = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !(hz >= kMinStreamHz && hz <= kMaxStreamHz)) {
        throw std::invalid_argument("rate_hz: expected 10..100, found '" + v + "'");
      }
    }
    if (streams_.fetch_add(1) >= options_.max_streams) {
      streams_.fetch_sub(1);
      return reply_error(res, 503, "too many telemetry streams (serve.max_streams)");
    }
    const auto period = std::chrono::duration<double>(1.0 / hz);
    // This stream's own evaluation of the reduced model, off the tick.
    std::shared_ptr<FaceLandmarks> landmarks;
    if (geometry_.geometry) landmarks = std::make_shared<FaceLandmarks>(geometry_.geometry);
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, period, landmarks, next = std::chrono::steady_clock::now()](
            std::size_t, httplib::DataSink& sink) mutable {
          if (stopping_.load()) {
            sink.done();
            return false;
          }
          next += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
          std::this_thread::sleep_until(next);
          TelemetryRecord rec;
          service_.latest(rec);
          const auto moved =
              landmarks ? landmarks->displacements_mm(rec.face) : std::span<const double>{};
          const std::string event =
              "data: " + telemetry_json(rec, service_.head().model(), moved).dump() + "\n\n";
          return sink.write(event.data(), event.size());
        },
        [this](bool) { streams_.fetch_sub(1); });
  });
  // The console's page at / and its files under /console/ (the API contract);
  // the page loads them from /console/.
  if (!options_.console_dir.empty() && (!s.set_mount_point("/", options_.console_dir) ||
                                        !s.set_mount_point("/console/", options_.console_dir))) {
    std::fprintf(stderr, "warning: no operator console in %s; serving the API only\n",
                 options_.console_dir.c_str());
  }
}

}  // namespace facectl
