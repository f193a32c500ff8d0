#include "drivers/can/socketcan_transport.hpp"

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace facectl {

namespace {
[[noreturn]] void fail(const std::string& interface, const char* what) {
  throw std::runtime_error("SocketCAN " + interface + ": " + what + ": " + std::strerror(errno));
}

// The most severe condition an error frame reports (linux/can/error.h).
CanError classify(const canfd_frame& f) {
  const canid_t id = f.can_id;
  if ((id & CAN_ERR_BUSOFF) != 0) return CanError::kBusOff;
  if ((id & CAN_ERR_RESTARTED) != 0) return CanError::kRestarted;
  if ((id & CAN_ERR_CRTL) != 0) {
    if ((f.data[1] & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      return CanError::kErrorPassive;
    }
    if ((f.data[1] & (CAN_ERR_CRTL_RX_OVERFLOW | CAN_ERR_CRTL_TX_OVERFLOW)) != 0) {
      return CanError::kOverflow;
    }
    return CanError::kWarning;  // warning levels, or back to error-active
  }
  if ((id & CAN_ERR_ACK) != 0) return CanError::kNoAck;
  if ((id & (CAN_ERR_PROT | CAN_ERR_TRX | CAN_ERR_BUSERROR)) != 0) return CanError::kProtocol;
  return CanError::kWarning;
}
}  // namespace

SocketCanTransport::SocketCanTransport(const std::string& interface, bool fd) : can_fd_(fd) {
  fd_ = socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
  if (fd_ < 0) fail(interface, "socket(PF_CAN, SOCK_RAW, CAN_RAW)");
  const can_err_mask_t mask = CAN_ERR_BUSOFF | CAN_ERR_CRTL | CAN_ERR_ACK | CAN_ERR_PROT |
                              CAN_ERR_TRX | CAN_ERR_BUSERROR | CAN_ERR_RESTARTED;
  if (setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask) != 0) {
    fail(interface, "CAN_RAW_ERR_FILTER");
  }
  if (fd) {
    const int on = 1;
    if (setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on) != 0) {
      fail(interface, "CAN_RAW_FD_FRAMES");
    }
  }
  const int sndbuf = 0;  // the kernel rounds up to its minimum: a few frames at most
  setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
  ifreq ifr{};
  if (interface.size() >= IFNAMSIZ) {
    errno = ENAMETOOLONG;
    fail(interface, "interface name");
  }
  std::strncpy(ifr.ifr_name, interface.c_str(), IFNAMSIZ - 1);
  if (ioctl(fd_, SIOCGIFINDEX, &ifr) != 0) fail(interface, "no such interface");
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  addr.can_ifindex = ifr.ifr_ifindex;
  if (bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) fail(interface, "bind");
}

SocketCanTransport::~SocketCanTransport() {
  if (fd_ >= 0) close(fd_);
}

bool SocketCanTransport::send(const CanFrame& frame) {
  canfd_frame f{};
  f.can_id = frame.id & CAN_SFF_MASK;
  f.len = frame.len;
  std::memcpy(f.data, frame.data.data(), frame.len);
  const std::size_t size = frame.fd && can_fd_ ? CANFD_MTU : CAN_MTU;
  // MSG_DONTWAIT: a full queue (ENOBUFS/EAGAIN) refuses the frame at once.
  return ::send(fd_, &f, size, MSG_DONTWAIT) == static_cast<ssize_t>(size);
}

bool SocketCanTransport::receive(CanFrame& frame, CanError& error) {
  canfd_frame f{};
  const ssize_t n = ::recv(fd_, &f, sizeof f, MSG_DONTWAIT);
  if (n != static_cast<ssize_t>(CAN_MTU) && n != static_cast<ssize_t>(CANFD_MTU)) return false;
  if ((f.can_id & CAN_ERR_FLAG) != 0) {
    error = classify(f);
    return true;
  }
  error = CanError::kNone;
  frame.id = f.can_id & CAN_SFF_MASK;
  frame.len = f.len;
  frame.fd = n == static_cast<ssize_t>(CANFD_MTU);
  std::memcpy(frame.data.data(), f.data, f.len);
  return true;
}

}  // namespace facectl
