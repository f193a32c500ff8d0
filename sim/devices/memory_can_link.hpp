#pragma once

#include <memory>

#include "control/realtime/spsc_ring.hpp"
#include "drivers/can/can_transport.hpp"

namespace facectl {

// The in-process twin of a CAN wire: two endpoints joined by lock-free rings
// of a fixed depth (the TX queue). A full ring refuses the frame, as a full
// SocketCAN queue does. Tests inject error frames into either end.
class MemoryCanLink {
 public:
  explicit MemoryCanLink(std::size_t depth = 256);

  class End final : public CanTransport {
   public:
    bool send(const CanFrame& frame) override;
    bool receive(CanFrame& frame, CanError& error) override;
    // Delivered to this end by its next receive() calls, in order.
    void inject_error(CanError e) { errors_.try_push(e); }

   private:
    friend class MemoryCanLink;
    End(SpscRing<CanFrame>& rx, SpscRing<CanFrame>& tx) : rx_(rx), tx_(tx) {}
    SpscRing<CanFrame>& rx_;
    SpscRing<CanFrame>& tx_;
    SpscRing<CanError> errors_{64};
  };

  End& host() { return *host_; }
  End& devices() { return *devices_; }

 private:
  SpscRing<CanFrame> to_devices_;
  SpscRing<CanFrame> to_host_;
  std::unique_ptr<End> host_;
  std::unique_ptr<End> devices_;
};

}  // namespace facectl
