#pragma once

#include <atomic>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "sim/devices/maestro_sim.hpp"

namespace facectl::sim {

// Faults a test injects into the wire (any thread, any time).
struct MaestroWireFaults {
  std::atomic<bool> mute{false};      // the Maestro never answers
  std::atomic<int> truncate_next{0};  // drop the last reply byte of the next N answers
};

// A simulated Maestro on the master side of a pseudo-terminal, on its own
// thread. The driver opens device(), a symbolic link to the pty's slave (as
// /dev/serial/by-id/... is to a USB adapter), so that unplug() and replug()
// can take the port away and bring a new one back under the same name.
class MaestroPtyWire {
 public:
  explicit MaestroPtyWire(MaestroSim maestro);
  ~MaestroPtyWire();
  MaestroPtyWire(const MaestroPtyWire&) = delete;
  MaestroPtyWire& operator=(const MaestroPtyWire&) = delete;

  const std::string& device() const { return link_; }
  MaestroWireFaults& faults() { return faults_; }
  // Runs `f(maestro)` under the wire's lock.
  template <typename F>
  void with_maestro(F&& f) {
    std::lock_guard lock(mutex_);
    f(maestro_);
  }
  // The port goes away (the driver's reads fail) and the link with it.
  void unplug();
  // A new pty behind the same link, and the Maestro power-cycled.
  void replug();
  std::uint64_t bytes_received() const { return bytes_.load(); }

 private:
  void open_pty();
  void close_pty();
  void run();

  MaestroSim maestro_;
  std::mutex mutex_;
  std::string link_;
  int master_ = -1;
  int slave_ = -1;  // held open so the pty lives while the driver reopens it
  std::mutex pty_mutex_;
  MaestroWireFaults faults_;
  std::atomic<std::uint64_t> bytes_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl::sim
