#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "firmware-host/config/udp_listen_config.hpp"
#include "firmware-host/fap/udp_listener.hpp"
#include "firmware-host/model/model_builder.hpp"
#include "firmware-host/serve/face_director.hpp"
#include "firmware-host/serve/head_service.hpp"
#include "firmware-host/serve/osc_message.hpp"

namespace facectl {

struct OscStats {
  std::uint64_t datagrams = 0;        // received
  std::uint64_t messages = 0;         // decoded
  std::uint64_t applied = 0;          // messages the head service took
  std::uint64_t refused = 0;          // messages it refused (state, unknown name, range)
  std::uint64_t malformed = 0;        // datagrams that are not OSC: nothing of them applied
  std::uint64_t unknown_address = 0;  // messages to an address not in the address space
  std::uint64_t refused_senders = 0;  // datagrams from senders off the allow list
  std::uint64_t kernel_drops = 0;     // dropped by the kernel, receive buffer full
  std::string last_error;
};

// Show control over OSC for `facectl serve` (docs/INPUTS.md, "OSC"): the
// runtime file's `osc:` block says where it listens (127.0.0.1:9000 by
// default) and whom it hears. Each message is an operation of the head
// service, as the HTTP API's: checked against the state machine, logged
// in the event log as from "osc ADDRESS:PORT", and passed to the face
// command source; nothing here enables the head or moves it past a limit.
//
//   /facectl/expression ,s[f]   hold an expression at a weight 0..1 (default 1)
//   /facectl/signal/KEY ,f      set one signal in its YAML unit (jaw_pitch_deg),
//                               held with the others set over OSC since the
//                               last expression, show or neutral
//   /facectl/neutral            back to the neutral face; forgets set signals
//   /facectl/show/play ,s       play a show of the catalog now
//   /facectl/show/queue ,s      play it after the current one
//   /facectl/show/stop          stop the show, back to neutral
//
// A datagram that is not OSC is counted and nothing of it applied; an
// unknown address or wrong arguments are counted per message.
// One line for the event log: "12 datagrams, 14 messages, 11 applied, ...".
std::string describe(const OscStats& s);

class OscControl {
 public:
  // Binds (ConfigError naming the address when it cannot).
  OscControl(HeadService& service, const UdpListenOptions& options);
  ~OscControl() = default;
  OscControl(const OscControl&) = delete;
  OscControl& operator=(const OscControl&) = delete;

  std::uint16_t port() const { return listener_.port(); }
  const std::string& bound() const { return listener_.bound(); }  // "127.0.0.1:9000"
  void start() { listener_.start(); }
  void stop() { listener_.stop(); }
  // Handles the datagrams already queued (tests; not while start()'s thread runs).
  void poll() { listener_.poll(); }
  std::size_t wait_and_poll(int timeout_ms) { return listener_.wait_and_poll(timeout_ms); }

  OscStats stats() const;

 private:
  std::size_t handle(const UdpDatagram& d, std::string_view bytes);
  // The service's answer to one message; throws std::invalid_argument for
  // arguments the address does not take.
  HeadService::Result apply(const OscMessage& m, const std::string& who);
  // Writes a refused or unknown message to the event log, as the HTTP API
  // answers its client: at most kRefusalsLoggedPerSecond, the rest counted.
  void log_refusal(const std::string& who, const std::string& why);

  HeadService& service_;
  const FaceBounds bounds_;
  FaceDirector::Pose held_;  // the receiver's: signals set since the last reset
  std::chrono::steady_clock::time_point refusal_window_{};  // the receiver's, as the two below
  int refusals_in_window_ = 0;
  std::uint64_t refusals_unlogged_ = 0;

  mutable std::mutex mutex_;  // guards stats_ between the receiver and stats()
  OscStats stats_;

  // Last: destroyed first, so its thread stops before what it calls into.
  UdpListener listener_;
};

}  // namespace facectl
