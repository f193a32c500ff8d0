#pragma once

#include <string>

#include "drivers/can/can_transport.hpp"

namespace facectl {

// A SocketCAN raw socket (CAN_RAW) bound to one interface, non-blocking, with
// error frames enabled (bus-off, controller state, no-ACK, protocol) and,
// when asked, CAN FD frames. Its send buffer is kept small so that frames
// queued before an e-stop cannot pile up and fire later.
class SocketCanTransport final : public CanTransport {
 public:
  // Throws std::runtime_error naming the interface and the failing call.
  SocketCanTransport(const std::string& interface, bool fd);
  ~SocketCanTransport() override;
  SocketCanTransport(const SocketCanTransport&) = delete;
  SocketCanTransport& operator=(const SocketCanTransport&) = delete;

  bool send(const CanFrame& frame) override;
  bool receive(CanFrame& frame, CanError& error) override;

 private:
  int fd_ = -1;
  bool can_fd_ = false;
};

}  // namespace facectl
