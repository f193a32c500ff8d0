#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace facectl {

// A serial port in raw 8N1 mode at any baud rate (termios2's BOTHER, so the
// 1, 2, 3 and 4 Mbit/s of smart servos work as well as the standard rates).
// Non-blocking underneath: every call waits at most its timeout, so the I/O
// thread that owns it can always tell a silent device from a slow one. Also
// works on a pseudo-terminal, which ignores the rate (the tests' wire).
class SerialPort {
 public:
  // Throws std::runtime_error naming the device and the system's error.
  SerialPort(const std::string& device, long baud);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  const std::string& device() const { return device_; }
  long baud() const { return baud_; }

  // Writes every byte, waiting up to `timeout_ns` in all. False on a timeout
  // or an error (errno set).
  bool write_all(std::span<const std::uint8_t> bytes, std::int64_t timeout_ns);
  // Reads what has arrived into `out`, waiting up to `timeout_ns` for the
  // first byte. Returns the count (0 on timeout), -1 on an error (errno set),
  // e.g. a USB adapter unplugged.
  long read_some(std::span<std::uint8_t> out, std::int64_t timeout_ns);
  // Drops bytes received and not read: a late reply must not be taken for the
  // answer to the next request.
  void discard_input();

 private:
  std::string device_;
  long baud_ = 0;
  int fd_ = -1;
};

// Seconds one byte (start, 8 data, stop) takes at `baud`.
constexpr double serial_byte_s(long baud) {
  return 10.0 / static_cast<double>(baud);
}

}  // namespace facectl
