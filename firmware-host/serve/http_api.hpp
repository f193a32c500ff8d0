#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "firmware-host/serve/access_control.hpp"
#include "firmware-host/serve/face_geometry.hpp"
#include "firmware-host/serve/head_service.hpp"

namespace httplib {
class Server;
}

namespace facectl {

// The HTTP side of `facectl serve` (cpp-httplib): the /api/v1 operations of
// docs/API.md, the telemetry stream (server-sent events) and the operator
// console's files. Its threads are ordinary ones, off the loop's CPU; every
// operation goes through HeadService, which checks it against the state machine.
class HttpApi {
 public:
  struct Options {
    ListenAddress listen;
    std::string token;     // empty: no token (loopback only)
    std::string tls_cert;  // PEM files: HTTPS; empty: plain HTTP
    std::string tls_key;
    std::string console_dir;  // served at / and /console/
    long max_streams = 16;
  };

  HttpApi(HeadService& service, Options options);
  ~HttpApi();
  HttpApi(const HttpApi&) = delete;
  HttpApi& operator=(const HttpApi&) = delete;

  // Binds, or throws naming the address and the reason.
  void bind();
  // Serves until stop(); call on its own thread.
  void serve();
  void stop();
  // Blocks until serve() accepts connections (stop() is a no-op before).
  void wait_until_serving() const;
  std::string address() const;  // host:port as bound
  std::string url() const;      // http(s)://host:port/

 private:
  void routes();

  HeadService& service_;
  Options options_;
  FaceGeometryLoad geometry_;  // loaded once, here: GET /api/v1/face/geometry
  std::string geometry_body_;
  std::unique_ptr<httplib::Server> server_;
  int port_ = 0;
  std::atomic<bool> stopping_{false};
  std::atomic<long> streams_{0};
};

}  // namespace facectl
