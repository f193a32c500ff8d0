#pragma once

#include <modbus/modbus.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "sim/devices/modbus_actuator_board.hpp"

namespace facectl::sim {

// Faults a test injects into the server's replies (any thread, any time).
struct ModbusServerFaults {
  std::atomic<bool> silent{false};            // receive requests, never answer
  std::atomic<int> delay_us{0};               // delay every reply
  std::atomic<int> exception_code{0};         // answer every request with this exception
  std::atomic<int> drop_every{0};             // leave every Nth request unanswered
  std::atomic<int> corrupt_next{0};           // send the next N replies corrupted
  std::atomic<bool> close_connection{false};  // drop the TCP connection on the next request
  std::atomic<int> only_unit{0};              // nonzero: the faults above hit this unit only
};

// A real libmodbus server (TCP on 127.0.0.1, or RTU on the master side of a
// pseudo-terminal) serving simulated actuator boards by unit id, on its own
// thread. It is the peer of the integration tests and the benchmarks.
class ModbusBoardServer {
 public:
  // Listens on 127.0.0.1 at an ephemeral port (port()).
  // `at` moves the boards' register blocks (a board whose map starts at
  // another address; its watchdog stays 10 after CONTROL).
  static std::unique_ptr<ModbusBoardServer> tcp(std::vector<ModbusActuatorBoard*> boards,
                                                modbus_map::Addresses at = {});
  // Opens a pty pair; the driver opens device() as its serial port. RTU
  // filters requests by unit id, so one board per line here.
  static std::unique_ptr<ModbusBoardServer> rtu_pty(ModbusActuatorBoard* board, int baud);
  ~ModbusBoardServer();
  ModbusBoardServer(const ModbusBoardServer&) = delete;
  ModbusBoardServer& operator=(const ModbusBoardServer&) = delete;

  int port() const { return port_; }
  const std::string& device() const { return device_; }
  ModbusServerFaults& faults() { return faults_; }
  std::uint64_t requests() const { return requests_.load(); }
  std::uint64_t connections() const { return connections_.load(); }

 private:
  ModbusBoardServer(std::vector<ModbusActuatorBoard*> boards, modbus_map::Addresses at);
  void run();
  void serve_one();
  void handle(const std::uint8_t* query, int length);
  void send_corrupt(const std::uint8_t* query);
  void reply_normally(const std::uint8_t* query, int length, ModbusActuatorBoard& board,
                      modbus_mapping_t* map, int function, int header);
  void close_client();

  std::vector<ModbusActuatorBoard*> boards_;
  modbus_map::Addresses at_;
  std::vector<modbus_mapping_t*> maps_;
  modbus_t* ctx_ = nullptr;
  bool tcp_ = true;
  int listen_fd_ = -1;
  int client_fd_ = -1;
  int pty_slave_fd_ = -1;  // held open so the line stays up between clients
  int port_ = 0;
  std::string device_;
  ModbusServerFaults faults_;
  std::atomic<std::uint64_t> requests_{0};
  std::atomic<std::uint64_t> connections_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace facectl::sim
