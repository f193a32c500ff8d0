#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace facectl::sim {

// The master side of a pseudo-terminal in raw mode: the wire of a simulated
// serial device. The driver under test opens device() as its serial port;
// the slave side is held open so the pty lives while the driver reopens it.
class PtyMaster {
 public:
  PtyMaster();  // throws std::runtime_error
  ~PtyMaster();
  PtyMaster(const PtyMaster&) = delete;
  PtyMaster& operator=(const PtyMaster&) = delete;

  const std::string& device() const { return device_; }
  // Waits up to `timeout_ms` for bytes; returns the count, 0 if none.
  std::size_t read(std::uint8_t* out, std::size_t size, int timeout_ms);
  void write_all(const std::uint8_t* data, std::size_t n);

 private:
  std::string device_;
  int master_ = -1;
  int slave_ = -1;
};

void sleep_us(int us);

}  // namespace facectl::sim
