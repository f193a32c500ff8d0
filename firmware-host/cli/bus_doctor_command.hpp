#pragma once

#include <string>

namespace facectl {

struct BusDoctorOptions {
  std::string rig;        // rig file; empty = the runtime file's rig
  std::string config;     // runtime file (head, loop rate); empty = the shipped default
  std::string bus;        // only this bus; empty = every bus
  int samples = 20;       // Modbus reads per board
  double listen_s = 0.5;  // CAN listening time
};

// `facectl bus doctor [RIG]`: per bus, whether it is reachable and its devices
// answer, their round-trip times, known bad defaults (libmodbus's 500 ms
// timeout, a USB serial latency timer above 1 ms) and the bus load. It only
// reads: nothing is enabled and no target is sent.
// Exit codes: 0 no problem (warnings allowed); 1 problems found; 2 unusable input.
int bus_doctor_command(const BusDoctorOptions& options);

}  // namespace facectl
