// Modbus TCP replies to the requests ModbusBus makes (docs/PROTOCOLS.md,
// "Modbus actuator board"): a libmodbus client connected, as the driver's is,
// to a socket this target answers with the input's bytes. libmodbus checks
// the reply (transaction id, unit, function, length) and the driver decodes
// the registers it returns (status bits, positions through each channel's
// WireEncoding). Each input gets a fresh connection, so the transaction ids
// are the same on every run and a finding reproduces.
#include <arpa/inet.h>
#include <fuzzer/FuzzedDataProvider.h>
#include <modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>

#include "drivers/protocol/modbus_register_map.hpp"
#include "drivers/protocol/wire_encoding.hpp"

namespace {

int listener(int& port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0 ||
      ::listen(fd, 4) != 0 || ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    std::abort();
  }
  port = ntohs(addr.sin_port);
  return fd;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace facectl;
  static int port = 0;
  static const int listen_fd = listener(port);
  FuzzedDataProvider in(data, size);
  const int request = in.ConsumeIntegralInRange(0, 3);
  const int unit = in.ConsumeIntegralInRange(1, 247);
  const int channels = in.ConsumeIntegralInRange(1, modbus_map::kChannelsPerBoard);
  ActuatorEncoding encoding;
  encoding.raw = in.ConsumeBool() ? ActuatorEncoding::Raw::kInt16 : ActuatorEncoding::Raw::kUint16;
  const WireEncoding wire(in.ConsumeBool() ? ActuatorKind::kRotary : ActuatorKind::kLinear,
                          encoding);
  const std::vector<std::uint8_t> reply = in.ConsumeRemainingBytes<std::uint8_t>();

  modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
  if (ctx == nullptr || modbus_connect(ctx) != 0) std::abort();
  const int server = ::accept4(listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
  if (server < 0) std::abort();
  // The reply is queued before the request goes out; what libmodbus does
  // not take in 2 ms (a short reply) counts as a timeout, as on the wire.
  if (!reply.empty() && ::send(server, reply.data(), reply.size(), MSG_NOSIGNAL) !=
                            static_cast<ssize_t>(reply.size())) {
    std::abort();
  }
  modbus_set_response_timeout(ctx, 0, 2000);
  modbus_set_byte_timeout(ctx, 0, 2000);
  modbus_set_slave(ctx, unit);
  std::array<std::uint16_t, modbus_map::kInputCount> regs{};
  int rc = -1;
  switch (request) {
    case 0:  // STATUS .. POSITION of every channel (ModbusBus::serve_board)
      rc = modbus_read_input_registers(ctx, modbus_map::kIrStatus,
                                       modbus_map::kIrPosition0 + channels, regs.data());
      break;
    case 1:  // CONTROL, HEARTBEAT and the targets
      rc = modbus_write_registers(ctx, modbus_map::kHrControl, 2 + channels, regs.data());
      break;
    case 2:  // CONTROL = 0 (disabled)
      rc = modbus_write_registers(ctx, modbus_map::kHrControl, 1, regs.data());
      break;
    default:  // the watchdog, on connect
      rc = modbus_write_register(ctx, modbus_map::kHrWatchdogMs, 100);
      break;
  }
  if (rc >= 0 && request == 0) {
    if (rc != modbus_map::kIrPosition0 + channels) std::abort();  // libmodbus checks the count
    for (int ch = 0; ch < channels; ++ch) {
      const double p =
          wire.decode_u16(regs[static_cast<std::size_t>(modbus_map::kIrPosition0 + ch)]);
      if (!std::isfinite(p)) std::abort();
    }
  }
  modbus_flush(ctx);  // as the driver does after a bad reply
  modbus_close(ctx);
  modbus_free(ctx);
  ::close(server);
  return 0;
}
